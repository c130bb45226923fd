#include "tables/dv1_table.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "core/clock.h"
#include "harness/dataset_choice.h"
#include "harness/format.h"
#include "harness/text_table.h"
#include "harness/timing_stats.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"

namespace vsil::bench {
namespace {

// The paper's Table 1 (Core 2 Duo E8400, GeForce GTX 280, 512² viewport, one sample per voxel).
struct PaperRow {
  const char* model;
  const char* resolution;
  double mip, demip, mida, dvr;
};
const PaperRow kPaper[] = {
    {"Jaw", "512²·40", 64.7, 53.8, 48.1, 49.8},
    {"Aneurysm", "512²·120", 76.2, 54.5, 43.9, 45.8},
    {"Abdomen", "512²·171", 59.4, 51.8, 50.1, 53.4},
    {"Head", "512²·485", 28.9, 25.8, 17.3, 17.6},
    {"Body", "512²·512", 28.1, 24.1, 26.6, 27.1},
};

struct Dv1Dataset {
  const char* name;       // --only, JSON "dataset"
  const char* file;       // in the datasets folder
  const PaperRow* paper;  // the paper's row of the same dataset, if it has one
};
const Dv1Dataset kDatasets[] = {
    {"aneurism", "aneurism.vti", &kPaper[1]},
    {"bonsai", "bonsai.vti", nullptr},
    {"engine", "engine.vti", nullptr},
    {"teddybear", "teddybear_128x128x62_uint8.nhdr", nullptr},
    {"tooth", "tooth.nrrd", nullptr},
};

// The same orbit as nk3: timed frame i from azimuth 30° + 3.6°·i at elevation 20°.
constexpr double kOrbitStartDeg = 30.0, kOrbitStepDeg = 3.6, kElevationDeg = 20.0;
constexpr double kSphereWeight = 0.4;

struct Dv1Column {
  std::string key;    // JSON "technique"
  std::string label;  // printed
  std::string technique;
  OptionValues options;
};
const std::vector<Dv1Column>& dv1Columns() {
  static const std::vector<Dv1Column> columns = {
      {"mip", "MIP", "mip", {}},
      {"demip", "DEMIP", "demip", {}},
      {"demip_sphere", "DEMIP+sphere", "demip", {{"sphere-weight", kSphereWeight}}},
      // The paper's DVR column: the plain lit composite, front to back (illustrate, no effects,
      // its power opacity above Otsu's threshold).
      {"dvr", "DVR", "illustrate", {{"effects", std::string("none")}}},
  };
  return columns;
}
constexpr std::size_t kMip = 0, kDemip = 1, kSphere = 2, kDvr = 3;

struct CaseResult {
  std::vector<double> ms;
  std::vector<double> cpuMs;  // the process's CPU time over each timed frame
  TimingStats stats;
  int slices = 0;
  std::vector<std::string> problems;
};

cv::Mat1b coverage(const cv::Mat4f& colour) {
  cv::Mat1b shown(colour.size());
  for (int y = 0; y < colour.rows; ++y) {
    for (int x = 0; x < colour.cols; ++x) shown(y, x) = colour(y, x)[3] > 0 ? 255 : 0;
  }
  return shown;
}

// The columns take turns frame by frame (load from other processes falls on all alike).
// Timed: Renderer::render (both sweeps, glFinish, readback of the colour; no depth, as `vsil
// render` without --depth-out). Checked after the timed region: every frame shows something;
// MIP and DEMIP show the same pixels (DEMIP only shades them); the colour sphere changes some
// pixel.
std::vector<CaseResult> measureWindow(Renderer& renderer, int window, const BenchOptions& options) {
  const auto& columns = dv1Columns();
  std::vector<CaseResult> results(columns.size());
  for (int k = 0; k < options.warmup + options.frames; ++k) {
    const int timed = k - options.warmup;
    std::vector<cv::Mat4f> colours;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      RenderSettings settings;
      settings.technique = columns[c].technique;
      settings.options = columns[c].options;
      settings.size = {window, window};
      settings.camera.azimuthDeg = kOrbitStartDeg + kOrbitStepDeg * std::max(timed, 0);
      settings.camera.elevationDeg = kElevationDeg;
      settings.readDepth = false;
      const double cpuStart = processCpuMs();
      const auto start = std::chrono::steady_clock::now();
      RenderResult frame = renderer.render(settings);
      const double ms = millisecondsSince(start);
      const double cpuMs = processCpuMs() - cpuStart;
      results[c].slices = frame.sliceCount;
      if (timed >= 0) {
        results[c].ms.push_back(ms);
        results[c].cpuMs.push_back(cpuMs);
      }
      colours.push_back(frame.frame.color);
    }
    const std::string label = "frame " + std::to_string(k + 1);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (cv::countNonZero(coverage(colours[c])) == 0) {
        results[c].problems.push_back(label + " shows nothing");
      }
    }
    if (cv::countNonZero(coverage(colours[kMip]) != coverage(colours[kDemip])) != 0) {
      results[kDemip].problems.push_back(label + " covers other pixels than MIP");
    }
    cv::Mat difference;
    cv::absdiff(colours[kDemip], colours[kSphere], difference);
    if (cv::countNonZero(difference.reshape(1)) == 0) {
      results[kSphere].problems.push_back(label + ": the colour sphere changed nothing");
    }
  }
  for (auto& r : results) r.stats = summarize(r.ms);
  return results;
}

}  // namespace

std::optional<std::string> dv1DatasetFile(const std::string& name) {
  return datasetFileOf(kDatasets, name);
}

std::vector<std::string> dv1DatasetNames() {
  std::vector<std::string> names;
  for (const auto& d : kDatasets) names.push_back(d.name);
  return names;
}

TableResult runDv1Table(const BenchOptions& options, Progress& progress) {
  const std::vector<int> sizes = options.sizes.empty() ? std::vector<int>{512} : options.sizes;
  std::vector<const Dv1Dataset*> chosen;
  for (const auto& d : kDatasets) {
    if (options.only.empty() ||
        std::find(options.only.begin(), options.only.end(), d.name) != options.only.end()) {
      chosen.push_back(&d);
    }
  }
  progress.setTotalCases(int(chosen.size() * sizes.size()));

  TableResult table;
  table.name = "dv1";
  table.title = "Díaz–Vázquez Table 1: frames per second, ours beside the paper's (GTX 280)";
  const auto& columns = dv1Columns();
  std::vector<std::string> header{"dataset", "size", "window"};
  for (const auto& c : columns) header.push_back(c.label + " fps");
  header.insert(header.end(), {"DEMIP/MIP", "cpu DEMIP/MIP", "DVR/MIP", "paper MIP", "paper DEMIP",
                               "paper DVR", "paper DEMIP/MIP", "check"});
  TextTable text(header);
  table.plot.title = "dv1: frames per second (ours solid, paper hatched)";
  table.plot.valueLabel = "fps";
  for (std::size_t i = 0; i < columns.size(); ++i) table.plot.series.push_back({columns[i].label});
  table.plot.series.push_back({"MIP paper", true, int(kMip)});
  table.plot.series.push_back({"DEMIP paper", true, int(kDemip)});
  table.plot.series.push_back({"DVR paper", true, int(kDvr)});
  const double nan = std::nan("");

  for (const Dv1Dataset* d : chosen) {
    std::string missing;
    const std::optional<Volume> volume = readDatasetVolume(options.datasetsDir / d->file, missing);
    if (!volume) {
      table.notes.push_back(std::string(d->name) + ": " + missing);
      for (const auto& c : columns) {
        table.rows.push_back(
            {{"table", "dv1"}, {"dataset", d->name}, {"technique", c.key}, {"missing", missing}});
      }
      continue;
    }
    gl::GlContext context(options.gl);
    const std::string glBackend = gl::backendName(context.info().backend);
    Renderer renderer(context);
    renderer.setVolume(*volume);
    for (int window : sizes) {
      progress.startCase(std::string(d->name) + " " + std::to_string(window) + "²");
      const std::vector<CaseResult> results = measureWindow(renderer, window, options);
      const bool paper512 = d->paper && window == 512;
      std::vector<std::string> cells{d->name, dimsLabel(volume->dims),
                                     std::to_string(window) + "²"};
      std::string failed;
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const CaseResult& r = results[c];
        const std::string check = checkText(r.problems);
        if (!r.problems.empty()) {
          failed += " " + columns[c].key;
          table.failures.push_back(std::string(d->name) + " " + std::to_string(window) + "² " +
                                   columns[c].key + ": " + joinedProblems(r.problems));
        }
        nlohmann::json paperFps;
        if (paper512 && c == kMip) paperFps = d->paper->mip;
        if (paper512 && c == kDemip) paperFps = d->paper->demip;
        if (paper512 && c == kDvr) paperFps = d->paper->dvr;
        table.rows.push_back({{"table", "dv1"},
                              {"dataset", d->name},
                              {"width", window},
                              {"height", window},
                              {"technique", columns[c].key},
                              {"frames", r.stats.frames},
                              {"warmup", options.warmup},
                              {"ms_median", r.stats.msMedian},
                              {"ms_min", r.stats.msMin},
                              {"ms_max", r.stats.msMax},
                              {"cpu_ms_median", median(r.cpuMs)},
                              {"ms", r.ms},
                              {"cpu_ms", r.cpuMs},
                              {"fps", r.stats.fps()},
                              {"slices", r.slices},
                              {"dims", {volume->dims.x, volume->dims.y, volume->dims.z}},
                              {"gl_backend", glBackend},
                              {"paper_fps", paperFps},
                              {"check", check}});
        if (c != kMip) {  // to MIP, from paired frames (pairedRatio)
          nlohmann::json& row = table.rows.back();
          const double ratio = pairedRatio(r.ms, results[kMip].ms);
          const double cpuRatio = pairedRatio(r.cpuMs, results[kMip].cpuMs);
          row["ratio_to"] = "mip";
          row["ratio"] = std::isfinite(ratio) ? nlohmann::json(ratio) : nlohmann::json();
          row["cpu_ratio"] = std::isfinite(cpuRatio) ? nlohmann::json(cpuRatio) : nlohmann::json();
        }
        cells.push_back(formatFps(r.stats.fps()));
      }
      // DEMIP's and DVR's frame time over MIP's, frame by frame (pairedRatio).
      cells.push_back(formatRatio(pairedRatio(results[kDemip].ms, results[kMip].ms)));
      cells.push_back(formatRatio(pairedRatio(results[kDemip].cpuMs, results[kMip].cpuMs)));
      cells.push_back(formatRatio(pairedRatio(results[kDvr].ms, results[kMip].ms)));
      cells.push_back(paper512 ? formatFps(d->paper->mip) : "–");
      cells.push_back(paper512 ? formatFps(d->paper->demip) : "–");
      cells.push_back(paper512 ? formatFps(d->paper->dvr) : "–");
      cells.push_back(paper512 ? formatRatio(d->paper->mip / d->paper->demip) : "–");
      cells.push_back(failed.empty() ? "ok" : "FAILED:" + failed);
      text.addRow(std::move(cells));
      table.plot.groups.push_back(std::string(d->name) + " " + std::to_string(window));
      std::vector<double> values;
      for (const auto& r : results) values.push_back(r.stats.fps() > 0 ? r.stats.fps() : nan);
      values.push_back(paper512 ? d->paper->mip : nan);
      values.push_back(paper512 ? d->paper->demip : nan);
      values.push_back(paper512 ? d->paper->dvr : nan);
      table.plot.values.push_back(std::move(values));
    }
  }
  progress.finish();

  char method[1024];
  std::snprintf(
      method, sizeof method,
      "method: %d warm-up + %d timed frames per column, MIP/DEMIP/DEMIP+sphere/DVR "
      "taking turns, orbit from azimuth %.0f° in steps of %.1f° at elevation %.0f°, 1 slice per "
      "voxel, the default window (Otsu's threshold to the 99.5th percentile above it), DEMIP "
      "defaults (d_w 0.15, eps 5 %% of the range, exact depth), sphere weight %.1f "
      "(red-blue), DVR = illustrate with no effects (power opacity above Otsu's threshold); "
      "frame time = Renderer::render (every sweep + glFinish + readback of the "
      "colour, no depth; the gradient texture DVR shades with is built once per volume, on "
      "its first frame, a warm-up frame with --warmup >= 1), fps = 1000 / median; DEMIP/MIP "
      "and DVR/MIP: the median over frames of the frame's time / MIP's in the same turn; cpu "
      "DEMIP/MIP: the same ratio in the process's CPU time per frame, steadier on a shared "
      "machine",
      options.warmup, options.frames, kOrbitStartDeg, kOrbitStepDeg, kElevationDeg, kSphereWeight);
  table.notes.push_back(method);
  table.notes.push_back("not measured: the paper's MIDA column (no MIDA technique)");
  std::string paper = "the paper's Table 1 (fps at 512², MIP / DEMIP / MIDA / DVR):";
  for (const PaperRow& row : kPaper) {
    char line[120];
    std::snprintf(line, sizeof line, " %s %s %.1f / %.1f / %.1f / %.1f;", row.model, row.resolution,
                  row.mip, row.demip, row.mida, row.dvr);
    paper += line;
  }
  table.notes.push_back(paper);
  table.text = text.plain();
  table.markdown = text.markdown();
  return table;
}

}  // namespace vsil::bench
