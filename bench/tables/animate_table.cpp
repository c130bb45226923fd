// The animate table in three steps: running (one `vsil animate` and 36 `vsil render` processes
// per case, timed from spawn to exit), checking (every frame the same pixels from both paths)
// and reporting (rows, text, plot). runAnimateTable at the end calls them.
#include "tables/animate_table.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "core/image_file.h"
#include "harness/child_run.h"
#include "harness/dataset_choice.h"
#include "harness/format.h"
#include "harness/scratch_folder.h"
#include "harness/text_table.h"
#include "slicing/gl_context.h"
#include "tables/nk3_table.h"

namespace vsil::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The orbit: 36 frames of 10° from azimuth 30° at elevation 20°, the Nagy–Klein datasets with
// nk3's iso values; bonsai runs unless --only names others.
constexpr int kFrames = 36;
constexpr const char* kView = "30,20";
constexpr const char* kDefaultDataset = "bonsai";
const std::vector<std::string> kDatasetNames = {"bonsai", "neghip"};
constexpr int kDefaultSize = 512;

// ---- Running ---------------------------------------------------------------------------------

struct AnimateCase {
  std::string dataset;
  int size = 0;
  std::string missing;  // why it was not measured
  double animateSeconds = 0, rendersSeconds = 0;
  double animateLoopFps = 0, setupMs = 0;  // from frames.json
  std::vector<std::string> problems;
  bool measured() const { return missing.empty(); }
  double ratio() const { return rendersSeconds > 0 ? animateSeconds / rendersSeconds : 0; }
};

std::string frameName(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", frame);
  return name;
}

// ---- Checking --------------------------------------------------------------------------------

// Every frame: the same pixels from one animate as from its own render process.
void compareFrames(const fs::path& animated, const fs::path& rendered, AnimateCase& result) {
  int different = 0;
  std::string first;
  for (int i = 0; i < kFrames; ++i) {
    const std::string name = frameName(i);
    try {
      const cv::Mat a = readImage(animated / name), b = readImage(rendered / name);
      if (a.size() != b.size() || a.type() != b.type() || cv::norm(a, b, cv::NORM_INF) != 0) {
        if (different++ == 0) first = name;
      }
    } catch (const std::exception& e) {
      result.problems.push_back(e.what());
      return;
    }
  }
  if (different > 0) {
    result.problems.push_back(std::to_string(different) + " of " + std::to_string(kFrames) +
                              " frames differ between animate and render (first: " + first + ")");
  }
}

AnimateCase measureCase(const std::string& dataset, const fs::path& file, double iso, int size,
                        const gl::ContextOptions& gl, Progress& progress) {
  AnimateCase result;
  result.dataset = dataset;
  result.size = size;
  const std::string sizeText = std::to_string(size) + "x" + std::to_string(size);
  const std::string isoText = nlohmann::json(iso).dump();
  progress.startCase(dataset + " " + std::to_string(size) + "² animate");
  const ScratchFolder scratch("animate");
  const fs::path animated = scratch.path() / "animate", rendered = scratch.path() / "render";
  fs::create_directory(rendered);
  const fs::path errFile = scratch.path() / "stderr";

  const std::vector<std::string> glChoice = glArguments(gl);
  std::vector<std::string> animateArgs = {
      "animate", file.string(), "--iso",   isoText,     "--size",
      sizeText,  "--view",      kView,     "--frames",  std::to_string(kFrames),
      "--orbit", "360",         "--quiet", "--out-dir", animated.string()};
  animateArgs.insert(animateArgs.end(), glChoice.begin(), glChoice.end());
  const ChildRun animate = runVsilChild(animateArgs, errFile);
  result.animateSeconds = animate.seconds;
  if (animate.exitCode != 0) {
    result.problems.push_back("vsil animate: " + animate.error);
    return result;
  }
  nlohmann::json frames;
  try {
    const nlohmann::json document = nlohmann::json::parse(std::ifstream(animated / "frames.json"));
    frames = document.at("frames");
    result.animateLoopFps = document.at("fps");
    result.setupMs = document.at("timings_ms").at("setup");
  } catch (const std::exception& e) {
    result.problems.push_back(std::string("frames.json: ") + e.what());
    return result;
  }
  if (frames.size() != std::size_t(kFrames)) {
    result.problems.push_back("frames.json lists " + std::to_string(frames.size()) + " frames");
    return result;
  }

  // The same views, one process each; the views as animate wrote them (round-trip numbers).
  const auto start = Clock::now();
  for (int i = 0; i < kFrames; ++i) {
    progress.step("render " + std::to_string(i + 1) + "/" + std::to_string(kFrames));
    const nlohmann::json& view = frames[i]["parameters"]["view"];
    std::vector<std::string> renderArgs = {"render", file.string(),
                                           "--iso",  isoText,
                                           "--size", sizeText,
                                           "--view", view[0].dump() + "," + view[1].dump(),
                                           "--out",  (rendered / frameName(i)).string()};
    renderArgs.insert(renderArgs.end(), glChoice.begin(), glChoice.end());
    const ChildRun render = runVsilChild(renderArgs, errFile);
    if (render.exitCode != 0) {
      result.problems.push_back("vsil render (frame " + std::to_string(i) + "): " + render.error);
      return result;
    }
  }
  result.rendersSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  compareFrames(animated, rendered, result);
  return result;
}

// ---- Reporting -------------------------------------------------------------------------------

std::string fixed(double value, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

std::string checkOf(const AnimateCase& c) {
  if (!c.measured()) return "missing";
  return checkText(c.problems);
}

nlohmann::json jsonRow(const AnimateCase& c) {
  nlohmann::json row = {{"table", "animate"},
                        {"dataset", c.dataset},
                        {"width", c.size},
                        {"height", c.size},
                        {"frames", kFrames}};
  if (!c.measured()) {
    row["missing"] = c.missing;
    return row;
  }
  row["animate_s"] = c.animateSeconds;
  row["renders_s"] = c.rendersSeconds;
  row["ratio"] = c.ratio();
  row["animate_fps"] = c.animateSeconds > 0 ? kFrames / c.animateSeconds : 0;
  row["renders_fps"] = c.rendersSeconds > 0 ? kFrames / c.rendersSeconds : 0;
  row["animate_loop_fps"] = c.animateLoopFps;
  row["animate_setup_ms"] = c.setupMs;
  row["check"] = checkOf(c);
  return row;
}

}  // namespace

std::vector<std::string> animateDatasetNames() {
  return kDatasetNames;
}

TableResult runAnimateTable(const BenchOptions& options, Progress& progress) {
  // --only picks among this table's datasets (names of other tables' are not run here).
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
  table.name = "animate";
  table.title = "one vsil animate against " + std::to_string(kFrames) +
                " vsil render processes: a 36-frame orbit, wall-clock seconds";
  std::vector<AnimateCase> cases;
  std::vector<std::pair<fs::path, Nk3DatasetFile>> files;
  int present = 0;
  for (const auto& name : datasets) {
    const auto entry = nk3DatasetFile(name);
    const fs::path path = options.datasetsDir / (entry ? entry->file : name);
    files.push_back({path, entry.value_or(Nk3DatasetFile{})});
    present += entry && fs::exists(path) ? int(sizes.size()) : 0;
  }
  progress.setTotalCases(present);
  for (std::size_t d = 0; d < datasets.size(); ++d) {
    const auto& [path, entry] = files[d];
    if (!fs::exists(path)) {
      for (int size : sizes) {
        AnimateCase missing;
        missing.dataset = datasets[d];
        missing.size = size;
        missing.missing = notFound(path);
        cases.push_back(missing);
      }
      continue;
    }
    table.notes.push_back(datasets[d] + ": " + entry.isoReason + " (as nk3)");
    for (int size : sizes)
      cases.push_back(measureCase(datasets[d], path, entry.iso, size, options.gl, progress));
  }
  progress.finish();

  TextTable text({"dataset", "window", "frames", "animate s", "renders s", "ratio", "animate fps",
                  "loop fps", "check"});
  table.plot.title = "animate: 36 frames, one process against 36 (s)";
  table.plot.valueLabel = "seconds";
  table.plot.logScale = false;
  table.plot.series = {{"one vsil animate"}, {"36 vsil render"}};
  for (const AnimateCase& c : cases) {
    table.rows.push_back(jsonRow(c));
    const std::string window = std::to_string(c.size) + "²";
    if (!c.measured()) {
      text.addRow({c.dataset, window, std::to_string(kFrames), "–", "–", "–", "–", "–", "missing"});
      table.notes.push_back(c.dataset + ": " + c.missing);
      continue;
    }
    text.addRow({c.dataset, window, std::to_string(kFrames), fixed(c.animateSeconds, 2),
                 fixed(c.rendersSeconds, 2), fixed(c.ratio(), 3),
                 fixed(kFrames / c.animateSeconds, 1), fixed(c.animateLoopFps, 1),
                 c.problems.empty() ? "ok" : "FAILED"});
    for (const auto& problem : c.problems) {
      table.failures.push_back(c.dataset + " " + window + " animate: " + problem);
    }
    table.plot.groups.push_back(c.dataset + " " + window);
    table.plot.values.push_back({c.animateSeconds, c.rendersSeconds});
  }
  table.notes.push_back(
      "ratio = one animate / 36 renders (target <= 0.6 for bonsai at 512²); each timed from "
      "spawn to exit, frames written as PNG both ways; animate fps counts its set-up, loop fps "
      "(its frames.json) does not");
  table.text = text.plain();
  table.markdown = text.markdown();
  return table;
}

}  // namespace vsil::bench
