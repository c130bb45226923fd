// The startup table in three steps: running (child `vsil render` processes, the two shader
// cache settings taking turns), checking (exit status, the same PNG bytes from every run) and
// reporting (medians per stage: rows, text, plot). runStartupTable at the end calls them.
#include "tables/startup_table.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <tuple>

#include <nlohmann/json.hpp>

#include "harness/child_run.h"
#include "harness/dataset_choice.h"
#include "harness/format.h"
#include "harness/scratch_folder.h"
#include "harness/text_table.h"
#include "harness/timing_stats.h"
#include "tables/nk3_table.h"

namespace vsil::bench {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kDatasetNames = {"bonsai", "engine", "neghip"};
constexpr const char* kDefaultDataset = "bonsai";
constexpr int kDefaultSize = 512;  // vsil render's default --size

// The stages `vsil render --meta-out` times (render_command.cpp, render_job.cpp), in the order
// they run; "rest" is the total less their sum (checks, metadata), "exit" the process's time
// after the metadata was written (freeing, unloading) and, in wall time, the spawn.
const std::vector<std::string> kStages = {"startup",  "context",  "read",   "upload",
                                          "defaults", "programs", "render", "readback",
                                          "postfx",   "write",    "rest",   "exit"};

// Mesa's on-disk shader cache as the environment has it, and turned off.
struct CacheSetting {
  std::string name;
  std::vector<std::string> environment;
};
const std::vector<CacheSetting> kCacheSettings = {{"on", {}},
                                                  {"off", {"MESA_SHADER_CACHE_DISABLE=true"}}};

// ---- Running ---------------------------------------------------------------------------------

struct RunTimes {
  double processWallMs = 0, processCpuMs = 0;
  std::map<std::string, double> wallMs, cpuMs;  // by stage
};

struct StartupCase {
  std::string dataset;
  int size = 0;
  std::string cache;
  std::string missing;  // why it was not measured
  std::vector<RunTimes> runs;
  std::vector<std::string> problems;
  bool measured() const { return missing.empty(); }
};

std::string readFileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One child render; its times, or a problem.
std::optional<RunTimes> runOnce(const fs::path& file, int size, const CacheSetting& cache,
                                const fs::path& scratch, const gl::ContextOptions& gl,
                                std::string& outBytes, std::vector<std::string>& problems) {
  const fs::path out = scratch / "out.png", meta = scratch / "meta.json";
  fs::remove(out);
  fs::remove(meta);
  const std::string sizeText = std::to_string(size) + "x" + std::to_string(size);
  std::vector<std::string> args = {"render",     file.string(), "--out",
                                   out.string(), "--meta-out",  meta.string()};
  if (size != kDefaultSize) args.insert(args.end(), {"--size", sizeText});
  const std::vector<std::string> glChoice = glArguments(gl);
  args.insert(args.end(), glChoice.begin(), glChoice.end());
  const ChildRun child = runVsilChild(args, scratch / "stderr", cache.environment);
  if (child.exitCode != 0) {
    problems.push_back("vsil render: " + child.error);
    return std::nullopt;
  }
  RunTimes times;
  times.processWallMs = child.seconds * 1e3;
  times.processCpuMs = child.cpuSeconds * 1e3;
  try {
    const nlohmann::json document = nlohmann::json::parse(std::ifstream(meta));
    for (const auto& [key, into, process] :
         {std::tuple{"timings_ms", &times.wallMs, times.processWallMs},
          std::tuple{"cpu_ms", &times.cpuMs, times.processCpuMs}}) {
      const nlohmann::json& stages = document.at(key);
      double sum = 0;
      for (const std::string& stage : kStages) {
        if (stage == "rest" || stage == "exit") continue;
        (*into)[stage] = stages.at(stage).get<double>();
        sum += (*into)[stage];
      }
      const double total = stages.at("total").get<double>();
      (*into)["rest"] = total - sum;
      (*into)["exit"] = process - total;
    }
  } catch (const std::exception& e) {
    problems.push_back(std::string("--meta-out: ") + e.what());
    return std::nullopt;
  }
  outBytes = readFileBytes(out);
  return times;
}

// ---- Reporting -------------------------------------------------------------------------------

std::string fixed(double value, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

double medianOfRuns(const StartupCase& c, double RunTimes::*field) {
  std::vector<double> values;
  for (const RunTimes& run : c.runs) values.push_back(run.*field);
  return values.empty() ? 0 : median(values);
}

double medianOfStage(const StartupCase& c, std::map<std::string, double> RunTimes::*field,
                     const std::string& stage) {
  std::vector<double> values;
  for (const RunTimes& run : c.runs) values.push_back((run.*field).at(stage));
  return values.empty() ? 0 : median(values);
}

std::string checkOf(const StartupCase& c) {
  if (!c.measured()) return "missing";
  return checkText(c.problems);
}

nlohmann::json jsonRow(const StartupCase& c) {
  nlohmann::json row = {{"table", "startup"},
                        {"dataset", c.dataset},
                        {"width", c.size},
                        {"height", c.size},
                        {"shader_cache", c.cache}};
  if (!c.measured()) {
    row["missing"] = c.missing;
    return row;
  }
  row["runs"] = c.runs.size();
  row["process_wall_ms_median"] = medianOfRuns(c, &RunTimes::processWallMs);
  row["process_cpu_ms_median"] = medianOfRuns(c, &RunTimes::processCpuMs);
  for (const std::string& stage : kStages) {
    row["stages_wall_ms_median"][stage] = medianOfStage(c, &RunTimes::wallMs, stage);
    row["stages_cpu_ms_median"][stage] = medianOfStage(c, &RunTimes::cpuMs, stage);
  }
  row["check"] = checkOf(c);
  return row;
}

}  // namespace

std::vector<std::string> startupDatasetNames() {
  return kDatasetNames;
}

TableResult runStartupTable(const BenchOptions& options, Progress& progress) {
  std::vector<std::string> datasets;
  for (const auto& name : options.only) {
    if (std::find(kDatasetNames.begin(), kDatasetNames.end(), name) != kDatasetNames.end()) {
      datasets.push_back(name);
    }
  }
  if (options.only.empty()) datasets = {kDefaultDataset};
  const std::vector<int> sizes =
      options.sizes.empty() ? std::vector<int>{kDefaultSize} : options.sizes;

  TableResult table;
  table.name = "startup";
  table.title = "a default vsil render from exec to exit, stage by stage (medians, ms)";
  std::vector<StartupCase> cases;
  int present = 0;
  for (const auto& name : datasets) {
    const auto entry = nk3DatasetFile(name);
    present += entry && fs::exists(options.datasetsDir / entry->file) ? int(sizes.size()) : 0;
  }
  progress.setTotalCases(present);
  for (const auto& name : datasets) {
    const auto entry = nk3DatasetFile(name);
    const fs::path path = options.datasetsDir / (entry ? entry->file : name);
    for (int size : sizes) {
      std::vector<StartupCase> settings;
      for (const CacheSetting& cache : kCacheSettings) {
        settings.push_back({name, size, cache.name, {}, {}, {}});
        if (!fs::exists(path)) {
          settings.back().missing = notFound(path);
        }
      }
      if (fs::exists(path)) {
        progress.startCase(name + " " + std::to_string(size) + "²");
        const ScratchFolder scratch("startup");
        std::string firstBytes;
        // Warm-up runs fill the page cache and Mesa's shader cache; then the settings take
        // turns run by run, so that load from other processes falls on both alike.
        const int total = options.warmup + options.frames;
        for (int run = 0; run < total; ++run) {
          for (std::size_t s = 0; s < kCacheSettings.size(); ++s) {
            StartupCase& c = settings[s];
            if (!c.problems.empty()) continue;
            progress.step("run " + std::to_string(run + 1) + "/" + std::to_string(total) +
                          ", shader cache " + c.cache);
            std::string bytes;
            const auto times = runOnce(path, size, kCacheSettings[s], scratch.path(), options.gl,
                                       bytes, c.problems);
            if (!times) continue;
            if (firstBytes.empty()) firstBytes = bytes;
            if (bytes != firstBytes) {
              c.problems.push_back("run " + std::to_string(run + 1) +
                                   " wrote other PNG bytes than the first run");
            }
            if (run >= options.warmup) c.runs.push_back(*times);
          }
        }
      }
      for (StartupCase& c : settings) cases.push_back(std::move(c));
    }
  }
  progress.finish();

  std::vector<std::string> header = {"dataset", "window", "shader cache", "time", "process"};
  header.insert(header.end(), kStages.begin(), kStages.end());
  header.push_back("check");
  TextTable text(header);
  table.plot.title = "startup: a default vsil render, process CPU time per stage (ms)";
  table.plot.valueLabel = "CPU ms (median)";
  table.plot.logScale = false;
  for (const std::string& stage : kStages) table.plot.series.push_back({stage});
  for (const StartupCase& c : cases) {
    table.rows.push_back(jsonRow(c));
    const std::string window = std::to_string(c.size) + "²";
    if (!c.measured()) {
      std::vector<std::string> cells = {c.dataset, window, c.cache, "–", "–"};
      cells.resize(header.size() - 1, "–");
      cells.push_back("missing");
      text.addRow(cells);
      table.notes.push_back(c.dataset + ": " + c.missing);
      continue;
    }
    for (const auto& [label, process, stages] :
         {std::tuple{"cpu", &RunTimes::processCpuMs, &RunTimes::cpuMs},
          std::tuple{"wall", &RunTimes::processWallMs, &RunTimes::wallMs}}) {
      std::vector<std::string> cells = {c.dataset, window, c.cache, label,
                                        fixed(medianOfRuns(c, process), 0)};
      for (const std::string& stage : kStages) {
        cells.push_back(fixed(medianOfStage(c, stages, stage), 0));
      }
      cells.push_back(c.problems.empty() ? "ok" : "FAILED");
      text.addRow(cells);
    }
    for (const auto& problem : c.problems) {
      table.failures.push_back(c.dataset + " " + window + " shader cache " + c.cache + ": " +
                               problem);
    }
    table.plot.groups.push_back(c.dataset + " " + window + " cache " + c.cache);
    std::vector<double> values;
    for (const std::string& stage : kStages) {
      values.push_back(medianOfStage(c, &RunTimes::cpuMs, stage));
    }
    table.plot.values.push_back(values);
  }
  table.notes.push_back(
      "each run: `vsil render FILE --out --meta-out` (no other flag), timed from spawn to exit; "
      "cpu = the process's CPU time (every thread, getrusage and CLOCK_PROCESS_CPUTIME_ID), which "
      "load from other processes does not inflate; wall includes waiting for a core; shader "
      "cache off = MESA_SHADER_CACHE_DISABLE=true; medians over " +
      std::to_string(options.frames) + " runs per setting after " + std::to_string(options.warmup) +
      " warm-up runs, the settings taking turns");
  table.text = text.plain();
  table.markdown = text.markdown();
  return table;
}

}  // namespace vsil::bench
