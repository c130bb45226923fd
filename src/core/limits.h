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
// Bytes of one 3D texture beyond which llvmpipe creates none (measured with
// GL_PROXY_TEXTURE_3D, Mesa 22.3: 2048²·112 R32F = 1.75 GiB is created, 2048²·113 is not; with
// its row padding 720³ R32F fits, 800³ does not). The default largest brick of a bricked volume
// texture (core/brick_layout.h; --max-texture-mib); the exact test is the proxy texture at
// upload (slicing/volume_texture.h, textureFits).
inline constexpr std::uint64_t kMaxTextureBytes =
    (std::uint64_t(7) << 28) + (std::uint64_t(16) << 20);
// Pixels per image side (--size), and slices per voxel along the view (--sampling).
inline constexpr int kMaxImageSide = 16384;
inline constexpr double kMaxSamplesPerVoxel = 64.0;
// --zoom: 1/1000 .. 1000 (beyond, the volume is far below a pixel or a voxel covers the image:
// 1e-308 underflowed in the float camera matrix and gave a blank image without a word).
inline constexpr double kMinZoom = 1e-3;
inline constexpr double kMaxZoom = 1e3;
// Line width in pixels (--width, --width-near, --width-far): the broadening pads by a few widths.
inline constexpr double kMaxLineWidth = 1024.0;
// Slices per frame: the box's diagonal in voxels times --sampling.
inline constexpr std::int64_t kMaxSlices = std::int64_t(1) << 17;
// Frames of one `vsil animate` (--frames): over an hour of video at 25 frames per second.
inline constexpr int kMaxFrames = 100000;
// Bytes of a header or text file read whole (NRRD headers, rule, style, transfer functions).
inline constexpr std::size_t kMaxHeaderBytes = std::size_t(1) << 20;
// Containers nested in one JSON file (transfer functions, styles): every walk of a parsed value
// recurses, so a deeper file is refused while it is parsed.
inline constexpr int kMaxJsonDepth = 64;
// --stride accepts 1 .. this (a larger stride keeps one sample per axis of any volume).
inline constexpr int kMaxStride = 1 << 16;
// demip's equirectangular sphere map (--sphere-map FILE.png), kept as RGBA32F (16 bytes per
// pixel): at most this many pixels per side and kMaxSphereMapPixels in all (128 MiB), plenty
// for a colour sphere (its legend is a disc a tenth of the image across).
inline constexpr int kMaxSphereMapSide = 4096;
inline constexpr std::int64_t kMaxSphereMapPixels = std::int64_t(4096) * 2048;
// --max-memory accepts 1 MiB .. 1 TiB.
inline constexpr std::int64_t kMaxMemoryMiBFlag = std::int64_t(1) << 20;

// Threads that loading and upload work uses (VTI zlib blocks, brick ranges): the machine's
// hardware threads, 1 .. kMaxWorkerThreads.
inline constexpr int kMaxWorkerThreads = 16;
int workerThreads();

// The default memory ceiling: half of the machine's physical memory (sysconf), at least
// 256 MiB; 4 GiB when the machine does not say.
std::size_t defaultMemoryBytes();

// What a render holds at its peak, by the render's own shapes:
//   volume: per voxel, the samples in their own type (1, 2 or 4 bytes), the 3D texture, which
//           llvmpipe keeps in host memory (R16F, 2 bytes, for 8-bit samples; 4 bytes for the
//           others, which are R16F only when every sample turns out to be a small integer:
//           the check runs before reading, so it assumes R32F); the empty-space brick
//           ranges (a min and max per 8³ voxels) and, while they are built, two z planes of
//           ranges per worker thread (slicing/empty_space.cpp); the upload's staging slabs
//           (slicing/volume_texture.cpp, two in flight);
//   image:  render targets (ping-pong RGBA32F + two R8UI), readback copies, frame buffers,
//           the FFT broadening's padded float/complex buffers and the composed image,
//           bounded by kRenderBytesPerPixel per pixel of the padded image.
//   gradients (techniques that shade by them): the RGBA16F gradient texture (8 bytes per texel
//   of the bricks) and, while it is built, the gradients of every voxel on the CPU (8 bytes
//   per voxel; the samples read back, 4 per voxel, are freed before the upload).
inline constexpr std::size_t kGradientBytesPerTexel = 8;
inline constexpr std::size_t kGradientCpuBytesPerVoxel = 8;
inline constexpr std::size_t kRenderBytesPerPixel = 128;
inline constexpr std::size_t kUploadSlabBytes = std::size_t(8) << 20;
std::uint64_t renderImageBytes(glm::ivec2 size, double maxLineWidth);
// The texture counts the texels of the bricks it is cut into (core/brick_layout.h
// BrickLayout::choose; each a power of two along every axis), `maxTextureBytes` being the
// largest brick (--max-texture-mib); with `oneTexture` (a render that cannot follow bricks,
// TechniqueInfo::needsOneTexture) one texture padded to powers of two when it fits.
std::uint64_t renderVolumeBytes(glm::ivec3 dims, std::size_t bytesPerSample, bool gradients = false,
                                std::uint64_t maxTextureBytes = kMaxTextureBytes,
                                bool oneTexture = false);
// An upper bound of the slices a frame draws from any camera: the box's diagonal counted in its
// finest spacing, ceil(|dims * spacing / min(spacing)| * samplesPerVoxel) + 1 (slicing/slicer.h
// planSlices steps 1 / samplesPerVoxel voxels along the view, the finest axis the densest;
// its eye-distance range is at most the diagonal). Saturates at 1e15.
std::int64_t sliceCountBound(glm::ivec3 dims, glm::dvec3 spacing, double samplesPerVoxel);

// Throws InputError "<what> needs N MiB, over the --max-memory limit of M MiB" when
// bytes > limitBytes.
void checkMemory(const std::string& what, std::uint64_t bytes, std::size_t limitBytes);

}  // namespace vsil::limits
