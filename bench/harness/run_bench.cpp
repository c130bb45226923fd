#include "harness/run_bench.h"

#include <algorithm>
#include <set>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_file.h"
#include "core/json_input.h"
#include "core/options.h"
#include "harness/dataset_choice.h"
#include "harness/machine_info.h"
#include "harness/plot.h"
#include "harness/table_registry.h"
#include "harness/timing_stats.h"

namespace vsil::bench {
namespace {

// Before any table runs (they take minutes): the output's folder exists and the output is not
// a folder itself.
void checkOutputFolder(const std::string& flag, const std::filesystem::path& path) {
  if (path.empty()) return;
  const auto folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(folder)) {
    throwInputError(flag + " " + path.string(), "folder " + folder.string() + " does not exist");
  }
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throwInputError(flag + " " + path.string(), "is a folder, not a file");
  }
}

// The three outputs, each its own file (OutputBatch::claim refuses two naming one).
OutputBatch claimOutputs(const BenchOptions& options) {
  OutputBatch outputs;
  outputs.claim("--json", options.json);
  outputs.claim("--markdown", options.markdown);
  outputs.claim("--plot", options.plot);
  return outputs;
}

// Before any table runs (they take minutes): each dataset --only asks for is read once, so that
// a file missing or unreadable fails the run here and not after the other datasets ran; the
// files of the others are noted as inputs (noteInputFile), so that claimOutputs refuses an
// output naming one. (Datasets run by default may be missing: their rows say so.)
void checkDatasets(const BenchOptions& options) {
  std::set<std::filesystem::path> seen;
  for (const auto& name : options.tables) {
    const TableDefinition& table = implementedTable(name);
    if (!table.datasetFile) continue;
    for (const auto& dataset : table.datasets) {
      const std::optional<std::string> file = table.datasetFile(dataset);
      if (!file) continue;
      const std::filesystem::path path = options.datasetsDir / *file;
      if (!seen.insert(path).second) continue;
      const bool asked =
          std::find(options.only.begin(), options.only.end(), dataset) != options.only.end();
      std::string missing;
      if (asked && !readDatasetVolume(path, missing) && isMissingFile(missing)) {
        throw InputError("--only " + dataset + ": " + missing);
      }
      std::error_code error;
      if (!asked && std::filesystem::is_regular_file(path, error)) noteInputFile(path);
    }
  }
}

std::string markdownReport(const MachineInfo& machine, const std::vector<TableResult>& tables) {
  std::string out = "# vsil bench\n\n";
  out += "- CPU: " + machine.cpuModel + ", " + std::to_string(machine.hardwareThreads) +
         " hardware threads\n";
  out += "- GL: " + machine.glBackend + ", " + machine.glVendor + ", " + machine.glRenderer + ", " +
         machine.glVersion + "\n";
  out += "- LP_NUM_THREADS: " + machine.lpNumThreads + "\n";
  out +=
      "- vsil " + machine.vsilVersion + " (" + machine.buildType + "), " + machine.dateUtc + "\n";
  for (const auto& table : tables) {
    out += "\n## " + table.name + ": " + table.title + "\n\n" + table.markdown + "\n";
    for (const auto& note : table.notes) out += "- " + note + "\n";
    for (const auto& failure : table.failures) out += "- **check failed**: " + failure + "\n";
  }
  return out;
}

// The timed frames of the rows that carry them ("ms"), named by dataset, size and case; with no
// warm-up frame the first, which pays for warming up (round 15), left out.
std::vector<CaseFrames> caseFramesOf(const std::vector<nlohmann::json>& rows, int warmup) {
  std::vector<CaseFrames> cases;
  for (const auto& row : rows) {
    const auto ms = row.find("ms");
    if (ms == row.end() || !ms->is_array()) continue;
    std::string name;
    const auto add = [&](const std::string& text) { name += (name.empty() ? "" : " ") + text; };
    for (const char* key : {"dataset", "width", "case", "technique"}) {
      const auto field = row.find(key);
      if (field == row.end() || field->is_null()) continue;
      if (std::string(key) == "width") {
        add(field->dump() + "²");
      } else if (field->is_string()) {
        add(field->get<std::string>());
      }
      if (std::string(key) == "case") break;  // the case names its technique
    }
    CaseFrames frames{name, {}};
    for (std::size_t i = warmup > 0 ? 0 : 1; i < ms->size(); ++i) {
      if ((*ms)[i].is_number()) frames.ms.push_back((*ms)[i].get<double>());
    }
    cases.push_back(std::move(frames));
  }
  return cases;
}

}  // namespace

BenchOptions validateOptions(BenchOptions options) {
  if (options.tables.empty()) {
    for (const auto& table : tableRegistry()) {
      if (table.run && !table.onlyWhenNamed) options.tables.push_back(table.name);
    }
  }
  std::vector<std::string> unique;
  std::set<std::string> datasets;
  for (const auto& name : options.tables) {
    const TableDefinition& table = implementedTable(name);
    if (std::find(unique.begin(), unique.end(), name) == unique.end()) unique.push_back(name);
    datasets.insert(table.datasets.begin(), table.datasets.end());
  }
  options.tables = unique;
  for (const auto& name : options.only) {
    if (datasets.empty()) {
      throw InputError("--only: the selected tables (" + joined(options.tables, ", ") +
                       ") have no datasets");
    }
    if (!datasets.count(name)) {
      throw InputError("--only: unknown dataset '" + name +
                       "' (known: " + joined({datasets.begin(), datasets.end()}, ", ") + ")");
    }
  }
  std::vector<int> sizes;  // each once, in the order given (--sizes 16,16 ran it twice)
  for (int size : options.sizes) {
    if (size < 16 || size > 4096) {
      throw InputError("--sizes: " + std::to_string(size) + " is outside 16..4096");
    }
    if (std::find(sizes.begin(), sizes.end(), size) == sizes.end()) sizes.push_back(size);
  }
  options.sizes = sizes;
  if (options.frames < 1 || options.frames > 100000) {
    throw InputError("--frames: " + std::to_string(options.frames) + " is outside 1..100000");
  }
  if (options.warmup < 0 || options.warmup > 100000) {
    throw InputError("--warmup: " + std::to_string(options.warmup) + " is outside 0..100000");
  }
  if (options.datasetsDir.empty()) {
#ifdef VSIL_SOURCE_DIR
    const std::filesystem::path beside =
        std::filesystem::path(VSIL_SOURCE_DIR) / ".." / "shared" / "datasets";
#else
    const std::filesystem::path beside;
#endif
    options.datasetsDir = "../shared/datasets";
    if (!std::filesystem::is_directory(options.datasetsDir) && !beside.empty() &&
        std::filesystem::is_directory(beside)) {
      options.datasetsDir = beside.lexically_normal();
    }
  } else if (!std::filesystem::is_directory(options.datasetsDir)) {
    std::error_code error;
    throw InputError("--datasets " + options.datasetsDir.string() +
                     (std::filesystem::exists(options.datasetsDir, error) ? ": is not a folder"
                                                                          : ": no such folder"));
  }
  checkOutputFolder("--json", options.json);
  checkOutputFolder("--markdown", options.markdown);
  checkOutputFolder("--plot", options.plot);
  if (!options.plot.empty() && options.plot.extension() != ".png") {
    throw InputError("--plot " + options.plot.string() + ": the plot is a PNG (name it .png)");
  }
  claimOutputs(options);
  return options;
}

BenchReport runBench(const BenchOptions& options, std::ostream& out, std::ostream& progressOut,
                     bool progressIsTerminal) {
  checkDatasets(options);
  claimOutputs(options);
  const MachineInfo machine = collectMachineInfo(options.gl);
  out << "vsil bench: " << joined(options.tables, ", ") << "\n"
      << formatMachineInfo(machine) << std::flush;

  BenchReport report;
  std::vector<TableResult> tables;
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& name : options.tables) {
    TableResult table;
    {
      Progress progress(progressOut, progressIsTerminal);
      table = implementedTable(name).run(options, progress);
    }
    if (auto note = unsteadyNote(caseFramesOf(table.rows, options.warmup)))
      table.notes.push_back(*note);
    out << "\n" << table.name << ": " << table.title << "\n" << table.text;
    for (const auto& note : table.notes) out << "  " << note << "\n";
    for (const auto& failure : table.failures) out << "  check FAILED: " << failure << "\n";
    out << std::flush;
    report.failures.insert(report.failures.end(), table.failures.begin(), table.failures.end());
    for (const auto& row : table.rows) rows.push_back(row);
    tables.push_back(std::move(table));
  }

  // All written, or none (a full disk for one leaves the others as they were).
  OutputBatch outputs = claimOutputs(options);
  if (!options.json.empty()) {
    nlohmann::json document;
    document["format"] = "vsil-bench-1";
    document["machine"] = machineInfoJson(machine);
    document["settings"] = {{"tables", options.tables}, {"datasets", options.datasetsDir.string()},
                            {"only", options.only},     {"sizes", options.sizes},
                            {"frames", options.frames}, {"warmup", options.warmup}};
    document["tables"] = nlohmann::json::array();
    for (const auto& table : tables) {
      document["tables"].push_back({{"name", table.name},
                                    {"title", table.title},
                                    {"notes", table.notes},
                                    {"failures", table.failures}});
    }
    document["rows"] = rows;
    outputs.add(options.json, jsonText(document, 2) + "\n");
  }
  if (!options.markdown.empty()) {
    outputs.add(options.markdown, markdownReport(machine, tables));
  }
  if (!options.plot.empty()) {
    std::vector<const PlotSpec*> plots;
    for (const auto& table : tables) plots.push_back(&table.plot);
    const cv::Mat image = drawPlots(plots);
    if (!image.empty()) outputs.add(options.plot, encodePng(options.plot, image));
  }
  outputs.commit();
  return report;
}

}  // namespace vsil::bench
