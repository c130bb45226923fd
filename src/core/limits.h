#pragma once
// The documented limits on what vsil accepts, in one place (README, "Hostile input"). Every
// size that decides an allocation is checked against these before anything is allocated:
// a request beyond them is an InputError naming the flag or file, never an out-of-memory kill.
#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace vsil::limits {

// Samples per volume axis (llvmpipe's and most GPUs' GL_MAX_3D_TEXTURE_SIZE).
inline constexpr int kMaxVolumeSide = 2048;
// Pixels per image side (--size), and slices per voxel along the view (--sampling).
inline constexpr int kMaxImageSide = 16384;
inline constexpr double kMaxSamplesPerVoxel = 64.0;
// Line width in pixels (--width, --width-near, --width-far): the broadening pads by a few widths.
inline constexpr double kMaxLineWidth = 1024.0;
// Slices per frame: the box's diagonal in voxels times --sampling.
inline constexpr std::int64_t kMaxSlices = std::int64_t(1) << 17;
// Frames of one `vsil animate` (--frames): over an hour of video at 25 frames per second.
inline constexpr int kMaxFrames = 100000;
// Bytes of a header or text file read whole (NRRD headers, rule, style, transfer functions).
inline constexpr std::size_t kMaxHeaderBytes = std::size_t(1) << 20;
// --max-memory accepts 1 MiB .. 1 TiB.
inline constexpr std::int64_t kMaxMemoryMiBFlag = std::int64_t(1) << 20;

// The default memory ceiling: half of the machine's physical memory (sysconf), at least
// 256 MiB; 4 GiB when the machine does not say.
std::size_t defaultMemoryBytes();

// What a render holds at its peak, by the render's own shapes:
//   volume: the Volume's floats plus the R32F 3D texture (llvmpipe keeps it in host memory),
//           8 bytes per voxel;
//   image:  render targets (ping-pong RGBA32F + two R8UI), readback copies, frame buffers,
//           the FFT broadening's padded float/complex buffers and the composed image,
//           bounded by kRenderBytesPerPixel per pixel of the padded image.
inline constexpr std::size_t kVolumeBytesPerVoxel = 8;
inline constexpr std::size_t kRenderBytesPerPixel = 128;
std::uint64_t renderImageBytes(glm::ivec2 size, double maxLineWidth);
std::uint64_t renderVolumeBytes(glm::ivec3 dims);
// An upper bound of the slices a frame draws: ceil(|dims| * samplesPerVoxel) + 1.
std::int64_t sliceCountBound(glm::ivec3 dims, double samplesPerVoxel);

// Throws InputError "<what> needs N MiB, over the --max-memory limit of M MiB" when
// bytes > limitBytes.
void checkMemory(const std::string& what, std::uint64_t bytes, std::size_t limitBytes);

}  // namespace vsil::limits
