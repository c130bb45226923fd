#include "core/limits.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "core/brick_layout.h"
#include "core/error.h"

namespace vsil::limits {

std::size_t defaultMemoryBytes() {
  static const std::size_t bytes = [] {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long pageSize = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return std::size_t(4) << 30;
    const std::uint64_t physical = std::uint64_t(pages) * std::uint64_t(pageSize);
    return std::size_t(std::max<std::uint64_t>(physical / 2, std::uint64_t(256) << 20));
  }();
  return bytes;
}

int workerThreads() {
  return std::clamp(int(std::thread::hardware_concurrency()), 1, kMaxWorkerThreads);
}

std::uint64_t renderImageBytes(glm::ivec2 size, double maxLineWidth) {
  // Broadening pads the image by the Gaussian's support on each side (a few line widths).
  const double width = std::isfinite(maxLineWidth) ? std::max(1.0, maxLineWidth) : 1.0;
  // In double, saturating: an absurd width must give an absurd (refused) size, not wrap around.
  const double pad = std::ceil(4.0 * width) + 2.0;
  const double bytes = (std::max(size.x, 0) + 2.0 * pad) * (std::max(size.y, 0) + 2.0 * pad) *
                       double(kRenderBytesPerPixel);
  return bytes >= 1.8e19 ? std::uint64_t(1.8e19) : std::uint64_t(bytes);
}

std::uint64_t renderVolumeBytes(glm::ivec3 dims, std::size_t bytesPerSample, bool gradients,
                                std::uint64_t maxTextureBytes, bool oneTexture) {
  const glm::u64vec3 d(glm::max(dims, glm::ivec3(0)));
  const std::uint64_t voxels = d.x * d.y * d.z;
  const std::uint64_t textureBytes = bytesPerSample == 1 ? 2 : 4;
  std::uint64_t texels = voxels;
  if (voxels > 0) {
    try {
      texels = BrickLayout::choose(
                   dims, textureBytes, maxTextureBytes, kMaxVolumeSide,
                   oneTexture ? BrickLayout::Bricking::OneIfItFits : BrickLayout::Bricking::Compact)
                   .texels();
    } catch (const std::invalid_argument&) {
      // No layout: the upload refuses it with its own error; count the voxels.
    }
  }
  const glm::u64vec3 b = (d + std::uint64_t(7)) / std::uint64_t(8);  // 8³ bricks
  const std::uint64_t rangeBytes = 8;                                // ValueRange
  const std::uint64_t rangesBytes =
      rangeBytes * (b.x * b.y * b.z + kMaxWorkerThreads * (b.x * d.y + b.x * b.y));
  const std::uint64_t slabBytes = std::max<std::uint64_t>(kUploadSlabBytes, d.x * d.y * 4);
  return voxels * (bytesPerSample + (gradients ? kGradientCpuBytesPerVoxel : 0)) +
         texels * (textureBytes + (gradients ? kGradientBytesPerTexel : 0)) + rangesBytes +
         2 * slabBytes;
}

std::int64_t sliceCountBound(glm::ivec3 dims, glm::dvec3 spacing, double samplesPerVoxel) {
  const double finest = std::min({spacing.x, spacing.y, spacing.z});
  const double diagonal = glm::length(glm::dvec3(dims) * (spacing / finest));
  const double slices = std::ceil(diagonal * samplesPerVoxel) + 1.0;
  // Not `slices > 1e15`: NaN (a spacing of 0 or inf) saturates too.
  return slices <= 1e15 ? std::int64_t(slices) : std::int64_t(1e15);
}

void checkMemory(const std::string& what, std::uint64_t bytes, std::size_t limitBytes) {
  if (bytes <= limitBytes) return;
  const auto mib = [](std::uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20); };
  throw InputError(what + " needs " + mib(bytes) + " MiB, over the --max-memory limit of " +
                   std::to_string(limitBytes >> 20) + " MiB");
}

}  // namespace vsil::limits
