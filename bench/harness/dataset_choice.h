#pragma once
// Which of a table's datasets a run measures: those --only names, else those the table measures
// by default; each with its file under --datasets, or why it is missing. For tables whose
// datasets have `name`, `file` and `byDefault`.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/volume.h"
#include "harness/bench_options.h"

namespace vsil::bench {

template <typename Dataset>
struct DatasetChoice {
  const Dataset& dataset;
  std::filesystem::path path;
  std::string missing;  // empty when the file is there
};

// "not found: PATH (use --datasets DIR)"
std::string notFound(const std::filesystem::path& path);

// True for a reason notFound or readDatasetVolume gave: the dataset has a file that is not
// there or not readable (not one that has no stored copy at all, as the nk3 table's Skull).
bool isMissingFile(const std::string& missing);

template <typename Dataset>
std::vector<DatasetChoice<Dataset>> chooseDatasets(std::span<const Dataset> datasets,
                                                   const BenchOptions& options) {
  std::vector<DatasetChoice<Dataset>> chosen;
  for (const Dataset& d : datasets) {
    const bool asked =
        std::find(options.only.begin(), options.only.end(), d.name) != options.only.end();
    if (options.only.empty() ? !d.byDefault : !asked) continue;
    const std::filesystem::path path = options.datasetsDir / d.file;
    chosen.push_back({d, path, std::filesystem::exists(path) ? "" : notFound(path)});
  }
  return chosen;
}

// The file (in the datasets folder) of the dataset named `name`, or none for an unknown name:
// TableDefinition::datasetFile for tables whose datasets have `name` and `file`.
template <typename Datasets>
std::optional<std::string> datasetFileOf(const Datasets& datasets, const std::string& name) {
  for (const auto& d : datasets) {
    if (d.name == name) return d.file;
  }
  return std::nullopt;
}

// The volume in a dataset's file, or nothing with `missing` saying why: not there (use
// --datasets DIR) or not readable. A missing dataset leaves its rows empty; it does not fail the
// run.
std::optional<Volume> readDatasetVolume(const std::filesystem::path& path, std::string& missing);

}  // namespace vsil::bench
