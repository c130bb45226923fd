#include "core/limits.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

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

std::uint64_t renderImageBytes(glm::ivec2 size, double maxLineWidth) {
  // Broadening pads the image by the Gaussian's support on each side (a few line widths).
  const double width = std::isfinite(maxLineWidth) ? std::max(1.0, maxLineWidth) : 1.0;
  // In double, saturating: an absurd width must give an absurd (refused) size, not wrap around.
  const double pad = std::ceil(4.0 * width) + 2.0;
  const double bytes = (std::max(size.x, 0) + 2.0 * pad) * (std::max(size.y, 0) + 2.0 * pad) *
                       double(kRenderBytesPerPixel);
  return bytes >= 1.8e19 ? std::uint64_t(1.8e19) : std::uint64_t(bytes);
}

std::uint64_t renderVolumeBytes(glm::ivec3 dims, bool gradients) {
  return std::uint64_t(std::max(dims.x, 0)) * std::uint64_t(std::max(dims.y, 0)) *
         std::uint64_t(std::max(dims.z, 0)) *
         (kVolumeBytesPerVoxel + (gradients ? kGradientBytesPerVoxel : 0));
}

std::int64_t sliceCountBound(glm::ivec3 dims, double samplesPerVoxel) {
  const double diagonal = glm::length(glm::dvec3(dims));
  const double slices = std::ceil(diagonal * samplesPerVoxel) + 1.0;
  return slices > 1e15 ? std::int64_t(1e15) : std::int64_t(slices);
}

void checkMemory(const std::string& what, std::uint64_t bytes, std::size_t limitBytes) {
  if (bytes <= limitBytes) return;
  const auto mib = [](std::uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20); };
  throw InputError(what + " needs " + mib(bytes) + " MiB, over the --max-memory limit of " +
                   std::to_string(limitBytes >> 20) + " MiB");
}

}  // namespace vsil::limits
