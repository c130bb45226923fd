#include "mpi/rank_report.h"

#include <sys/resource.h>

#include <array>
#include <vector>

#include "mpi/mpi_world.h"
#include "mpi/slab_render.h"
#include "slicing/volume_texture.h"

namespace vsil::mpi {

std::uint64_t heldTextureBytes(const SlabPart& part) {
  std::uint64_t bytes = 0;
  const std::vector<Brick>& bricks = part.layout.bricks();
  for (std::size_t i = 0; i < bricks.size(); ++i) {
    if (!part.holds(i)) continue;
    const glm::ivec3 s = bricks[i].size;
    bytes += std::uint64_t(s.x) * std::uint64_t(s.y) * std::uint64_t(s.z) *
             texelSize(part.internalFormat);
  }
  return bytes;
}

double peakResidentBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024.0;  // Linux reports KiB
}

nlohmann::json gatherRankNumbers(const RankNumbers& mine) {
  // One gather per field (gatherOnRoot): seven small collectives, once per render.
  const std::array<std::pair<const char*, double>, 7> fields{{
      {"frame_ms", mine.frameMs},
      {"frame_cpu_ms", mine.frameCpuMs},
      {"render_ms", mine.renderMs},
      {"reduce_ms", mine.reduceMs},
      {"held_bytes", mine.heldBytes},
      {"peak_rss_bytes", mine.peakResidentBytes},
      {"checked_bytes", mine.checkedBytes},
  }};
  nlohmann::json ranks = nlohmann::json::array();
  if (rank() == 0) {
    for (int r = 0; r < size(); ++r) ranks.push_back({{"rank", r}});
  }
  for (const auto& [name, value] : fields) {
    const std::vector<double> all = gatherOnRoot(value);
    for (std::size_t r = 0; r < all.size(); ++r) ranks[r][name] = all[r];
  }
  return ranks;
}

}  // namespace vsil::mpi
