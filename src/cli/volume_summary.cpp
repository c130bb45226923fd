#include "cli/volume_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "cli/cli_volume_options.h"
#include "core/transfer_function.h"

namespace vsil::cli {

namespace {

// The nearest-rank percentiles of the samples: counted for integer types (no copy of the
// volume), from a sorted copy for floats.
std::vector<float> percentilesOf(const Volume& volume, ValueRange range) {
  const double n = double(volume.voxelCount());
  std::vector<std::size_t> ranks;
  for (double p : kPercentiles) ranks.push_back(std::size_t(std::ceil(p / 100.0 * n)) - 1);
  std::vector<float> result;
  if (volume.type() == SampleType::Float32) {
    const auto samples = volume.samples<float>();
    std::vector<float> sorted(samples.begin(), samples.end());
    for (std::size_t rank : ranks) {
      std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(rank), sorted.end());
      result.push_back(sorted[rank]);
    }
    return result;
  }
  // Integer samples: at most 65536 distinct values from range.min on.
  const auto lowest = std::int64_t(range.min);
  std::vector<std::size_t> counts(std::size_t(std::int64_t(range.max) - lowest + 1), 0);
  volume.visit([&](auto samples) {
    for (auto v : samples) ++counts[std::size_t(std::int64_t(v) - lowest)];
  });
  std::size_t below = 0, value = 0;
  for (std::size_t rank : ranks) {  // ranks grow, so one walk over the counts serves them all
    while (below + counts[value] <= rank) below += counts[value++];
    result.push_back(float(lowest + std::int64_t(value)));
  }
  return result;
}

}  // namespace

Summary summarize(const Volume& volume) {
  Summary s;
  s.range = valueRange(volume);
  double sum = 0.0, sumSquares = 0.0;
  s.histogram.assign(kHistogramBins, 0);
  const double width = double(s.range.max) - double(s.range.min);
  volume.visit([&](auto samples) {
    for (auto sample : samples) {
      const float value = float(sample);
      sum += value;
      sumSquares += double(value) * value;
      // In double: in float, max − min overflows where the values span more than FLT_MAX.
      const int bin = width > 0 ? int((double(value) - s.range.min) / width * kHistogramBins) : 0;
      ++s.histogram[std::min(bin, kHistogramBins - 1)];
    }
  });
  const double n = double(volume.voxelCount());
  s.mean = sum / n;
  s.stddev = std::sqrt(std::max(0.0, sumSquares / n - s.mean * s.mean));
  s.percentiles = percentilesOf(volume, s.range);
  return s;
}

double binEdge(const Summary& s, int i) {
  return s.range.min + (double(s.range.max) - s.range.min) * i / kHistogramBins;
}

nlohmann::ordered_json summaryJson(const Volume& volume, const Summary& s) {
  nlohmann::ordered_json percentiles = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < std::size(kPercentiles); ++i) {
    percentiles[std::to_string(int(kPercentiles[i]))] = s.percentiles[i];
  }
  nlohmann::ordered_json json = {
      {"source", volume.source},
      {"name", volume.name},
      {"dims", {volume.dims.x, volume.dims.y, volume.dims.z}},
      {"samples", volume.voxelCount()},
      {"type", sampleTypeName(volume.type())},
      {"spacing", {volume.spacing.x, volume.spacing.y, volume.spacing.z}},
  };
  if (auto read = describeRead<nlohmann::ordered_json>(volume); !read.is_null())
    json["read"] = read;
  if (auto file = describeFile<nlohmann::ordered_json>(volume); !file.is_null())
    json["file"] = file;
  json["min"] = s.range.min;
  json["max"] = s.range.max;
  json["mean"] = s.mean;
  json["stddev"] = s.stddev;
  const DerivedDefaults derived = derivedDefaults(volume);
  json["default_iso"] = derived.iso;
  json["default_window"] = {derived.iso, derived.windowHigh};
  json["suggested_tf"] = suggestedTransferFunction(derived);
  json["percentiles"] = percentiles;
  json["histogram"] = {{"min", s.range.min}, {"max", s.range.max}, {"counts", s.histogram}};
  return json;
}

LoadOptions summaryLoadOptions(LoadOptions load) {
  load.limits.taskBytes = [](glm::ivec3 dims, SampleType type) {
    const std::uint64_t voxels = std::uint64_t(dims.x) * std::uint64_t(dims.y) * dims.z;
    return voxels * sampleTypeSize(type) +
           (type == SampleType::Float32 ? voxels * 4 : 65536 * sizeof(std::size_t));
  };
  return load;
}

}  // namespace vsil::cli
