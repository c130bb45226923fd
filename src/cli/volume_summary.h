#pragma once
// What `vsil info VOLUME` says about a volume's samples (value range, mean, deviation, nearest-rank
// percentiles, a histogram), computed once for the command's text and JSON and for the Python
// module's vsil.info, which returns the same JSON.
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/volume.h"
#include "io/volume_loader.h"

namespace vsil::cli {

inline constexpr int kHistogramBins = 16;
inline constexpr double kPercentiles[] = {1, 5, 25, 50, 75, 95, 99};

struct Summary {
  ValueRange range;
  double mean = 0.0;
  double stddev = 0.0;
  std::vector<std::size_t> histogram;  // kHistogramBins equal bins over [min, max]
  std::vector<float> percentiles;      // nearest-rank, one per kPercentiles entry
};

Summary summarize(const Volume& volume);
double binEdge(const Summary& s, int i);  // the lower edge of bin i (i = kHistogramBins: max)
// `vsil info --json` for the volume: source, name, dims, samples, type, spacing, read, file,
// min, max, mean, stddev, default_iso, percentiles, histogram.
nlohmann::ordered_json summaryJson(const Volume& volume, const Summary& s);
// `load` with the memory check of reading for a summary: the samples, and for floats the sorted
// copy the percentiles need (integers are counted).
LoadOptions summaryLoadOptions(LoadOptions load);

}  // namespace vsil::cli
