// The illustrate table in the nk3 table's four steps: choosing (datasets, windows), measuring
// (the cases of a dataset take turns frame by frame, then check their own output), rows (JSON,
// failed checks, lines) and formatting. runIllustrateTable at the end calls them in that order.
#include "tables/illustrate_table.h"
#include "core/clock.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <optional>

#include "core/transfer_function.h"
#include "harness/dataset_choice.h"
#include "harness/format.h"
#include "harness/scratch_folder.h"
#include "harness/text_table.h"
#include "harness/timing_stats.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"

namespace vsil::bench {
namespace {

// ---- What is measured -------------------------------------------------------------------------

// The transfer function of each dataset: transparent below the nk3 table's iso value (the
// surface RA shows, nk3_table.cpp says why each), rising from 0.1 there to 0.8 forty units
// above, one colour (ivory): the same material RA shows, so that their frame rates compare,
// and the empty-space skipping of both skips the same bricks.
struct IllustrateDataset {
  const char* name;
  const char* file;
  float iso;
  bool byDefault;  // measured without --only
};

const IllustrateDataset kDatasets[] = {
    {"bonsai", "bonsai.vti", 40.0f, true},
    {"engine", "engine.vti", 90.0f, true},
    {"neghip", "neghip_64x64x64_uint8.nhdr", 64.0f, false},
};

TransferFunction benchTransferFunction(float iso) {
  const glm::dvec3 ivory = glm::dvec3(255, 255, 240) / 255.0;
  TransferFunction tf;
  tf.source = "bench";
  tf.points = {{iso - 0.5, ivory, 0.0}, {iso, ivory, 0.1}, {iso + 40.0, ivory, 0.8}};
  return tf;
}

std::string writeTransferFunction(const TransferFunction& tf, const std::filesystem::path& dir,
                                  const std::string& name) {
  const std::filesystem::path path = dir / ("vsil-bench-tf-" + name + ".json");
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file) throw std::runtime_error("cannot write " + path.string());
  const std::string text = tf.toJson().dump();
  std::fwrite(text.data(), 1, text.size(), file);
  std::fclose(file);
  return path.string();
}

// The columns: RA, the plain composite, each effect alone, all of them. `target`: the largest
// frame-time ratio to the plain composite the issue allows (0: none).
struct IllustrateCase {
  std::string key;      // JSON "case" and the table
  std::string effects;  // --effects ("" plain); RA has none
  bool ra = false;
  double target = 0;
};

const std::vector<IllustrateCase>& illustrateCases() {
  static const std::vector<IllustrateCase> cases = {
      {"ra", "", true, 0},
      {"plain", "", false, 0},
      {"boundary", "boundary", false, 1.3},
      {"silhouette", "silhouette", false, 1.3},
      {"fading", "fading", false, 1.3},
      {"sketch", "sketch", false, 1.3},
      {"distance", "distance", false, 1.3},
      {"halo", "halo", false, 1.6},
      {"tone", "tone", false, 1.3},
      {"all", "boundary,silhouette,fading,sketch,distance,halo,tone", false, 2.0},
  };
  return cases;
}
constexpr std::size_t kRa = 0, kPlain = 1;
constexpr double kPlainOverRaTarget = 1.5;

// The nk3 orbit: timed frame i from azimuth 30° + 3.6°·i at elevation 20°; warm-up frames from
// the first position.
constexpr double kOrbitStartDeg = 30.0;
constexpr double kOrbitStepDeg = 3.6;
constexpr double kElevationDeg = 20.0;

// ---- Choosing ---------------------------------------------------------------------------------

using Choice = DatasetChoice<IllustrateDataset>;

std::vector<int> windowSizes(const BenchOptions& options) {
  return options.sizes.empty() ? std::vector<int>{512} : options.sizes;
}

// ---- Measuring --------------------------------------------------------------------------------

struct CaseResult {
  const IllustrateCase* column = nullptr;
  std::vector<double> ms;
  std::vector<double> cpuMs;  // the process's CPU time over the frame (all of llvmpipe's threads)
  TimingStats stats;
  cv::Mat firstFrame;  // timed frame 0: colour (illustrate) or states (RA)
  std::vector<cv::Mat> warmupFrames;
  int sliceCount = 0;
  double coveredMedian = 0;
  std::vector<std::string> problems;
};

struct Measured {
  const IllustrateDataset& dataset;
  std::string missing;
  glm::ivec3 dims{0};
  double gradientMs = 0;  // building the gradient texture, once per volume (not in any frame)
  struct Window {
    int size = 0;
    std::vector<CaseResult> cases;
  };
  std::vector<Window> windows;
  std::string glBackend;  // the back end its frames ran on ("osmesa", "egl"): the JSON rows say it
};

RenderSettings caseSettings(const IllustrateCase& c, const IllustrateDataset& d,
                            const std::string& tfPath, int window) {
  RenderSettings settings;
  settings.size = {window, window};
  settings.camera.elevationDeg = kElevationDeg;
  settings.samplesPerVoxel = 1.0;
  if (c.ra) {
    settings.technique = "rightangle";
    settings.options["iso"] = double(d.iso);
  } else {
    settings.technique = "illustrate";
    settings.options["tf"] = tfPath;
    settings.options["effects"] = c.effects;
  }
  return settings;
}

// Pixels that show something: colour alpha > 0, or a state other than Empty.
int coveredPixels(const FrameBuffers& frame) {
  if (!frame.state.empty()) return cv::countNonZero(frame.state);
  int covered = 0;
  for (auto it = frame.color.begin(); it != frame.color.end(); ++it) covered += (*it)[3] > 0.0f;
  return covered;
}

// Colour must be premultiplied and in [0, 1]: every channel finite, within [0, alpha].
std::string colorProblem(const cv::Mat4f& color) {
  for (int y = 0; y < color.rows; ++y) {
    for (int x = 0; x < color.cols; ++x) {
      const cv::Vec4f c = color(y, x);
      const bool finite =
          std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && std::isfinite(c[3]);
      const float slack = 1e-5f;
      if (!finite || c[3] < 0 || c[3] > 1 + slack || c[0] < 0 || c[1] < 0 || c[2] < 0 ||
          c[0] > c[3] + slack || c[1] > c[3] + slack || c[2] > c[3] + slack) {
        return "pixel " + std::to_string(x) + "," + std::to_string(y) +
               " is not a premultiplied colour in [0, 1]";
      }
    }
  }
  return "";
}

void renderFrame(Renderer& renderer, RenderSettings settings, int k, const BenchOptions& options,
                 CaseResult& result) {
  const bool warm = k < options.warmup;
  const int timedIndex = k - options.warmup;
  settings.camera.azimuthDeg = kOrbitStartDeg + kOrbitStepDeg * std::max(timedIndex, 0);
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = processCpuMs();
  const RenderResult frame = renderer.render(settings);
  const double ms = millisecondsSince(start);
  const double cpuMs = processCpuMs() - cpuStart;
  result.sliceCount = frame.sliceCount;
  const cv::Mat image =
      frame.frame.state.empty() ? cv::Mat(frame.frame.color) : cv::Mat(frame.frame.state);
  if (image.cols != settings.size.x || image.rows != settings.size.y) {
    result.problems.push_back("the frame is " + std::to_string(image.cols) + "x" +
                              std::to_string(image.rows));
    return;
  }
  if (!frame.frame.color.empty()) {
    if (const std::string problem = colorProblem(frame.frame.color); !problem.empty()) {
      result.problems.push_back("frame " + std::to_string(timedIndex + 1) + ": " + problem);
    }
  }
  if (warm) {
    result.warmupFrames.push_back(image.clone());
    return;
  }
  if (timedIndex == 0) result.firstFrame = image.clone();
  result.ms.push_back(ms);
  result.cpuMs.push_back(cpuMs);
  const int covered = coveredPixels(frame.frame);
  if (covered < settings.size.x * settings.size.y / 100) {
    result.problems.push_back("frame " + std::to_string(timedIndex + 1) + " shows only " +
                              std::to_string(covered) + " pixels");
  }
  result.coveredMedian += covered;
}

bool sameImage(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() &&
         std::equal(a.datastart, a.dataend, b.datastart);
}

std::vector<CaseResult> measureWindow(Renderer& renderer, const IllustrateDataset& d,
                                      const std::string& tfPath, int window,
                                      const BenchOptions& options, Progress& progress) {
  const auto& columns = illustrateCases();
  std::vector<CaseResult> results(columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) results[c].column = &columns[c];
  progress.startCase(std::string(d.name) + " " + std::to_string(window) + "²");
  const int total = options.warmup + options.frames;
  // The cases take turns frame by frame, so that load from other processes falls on all alike.
  for (int k = 0; k < total; ++k) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const bool warm = k < options.warmup;
      progress.step(columns[c].key + (warm ? " warm-up " : " frame ") +
                    std::to_string((warm ? k : k - options.warmup) + 1));
      renderFrame(renderer, caseSettings(columns[c], d, tfPath, window), k, options, results[c]);
    }
  }
  for (CaseResult& r : results) {
    r.stats = summarize(r.ms);
    if (!r.ms.empty()) r.coveredMedian /= double(r.ms.size());
    for (std::size_t i = 0; i < r.warmupFrames.size(); ++i) {
      if (!r.firstFrame.empty() && !sameImage(r.warmupFrames[i], r.firstFrame)) {
        r.problems.push_back("warm-up frame " + std::to_string(i + 1) +
                             " differs from timed frame 1 (same view: not deterministic)");
      }
    }
  }
  // Every effect changes the picture: a case that renders the plain composite's bytes did not
  // apply its effect.
  for (std::size_t c = kPlain + 1; c < results.size(); ++c) {
    if (!results[c].firstFrame.empty() &&
        sameImage(results[c].firstFrame, results[kPlain].firstFrame)) {
      results[c].problems.push_back("renders exactly the plain composite");
    }
  }
  return results;
}

Measured measureDataset(const Choice& chosen, const std::vector<int>& sizes,
                        const BenchOptions& options, Progress& progress) {
  Measured measured{chosen.dataset, chosen.missing, {}, 0, {}, {}};
  for (int size : sizes) measured.windows.push_back({size, {}});
  if (!measured.missing.empty()) return measured;
  const std::optional<Volume> volume = readDatasetVolume(chosen.path, measured.missing);
  if (!volume) return measured;
  measured.dims = volume->dims;
  // A folder of this run's own: two runs at once (the test suite's GL back ends) must not
  // share the file, nor one remove it under the other.
  const ScratchFolder scratch("illustrate");
  const std::string tfPath = writeTransferFunction(benchTransferFunction(chosen.dataset.iso),
                                                   scratch.path(), chosen.dataset.name);
  gl::GlContext context(options.gl);
  measured.glBackend = gl::backendName(context.info().backend);
  Renderer renderer(context);
  renderer.setVolume(*volume);
  {
    // The gradient texture is built by the first frame that needs it: once, not timed.
    RenderSettings first = caseSettings(illustrateCases()[kPlain], chosen.dataset, tfPath, 16);
    const auto start = std::chrono::steady_clock::now();
    renderer.render(first);
    measured.gradientMs = millisecondsSince(start);
  }
  for (auto& window : measured.windows) {
    window.cases = measureWindow(renderer, chosen.dataset, tfPath, window.size, options, progress);
  }
  return measured;
}

// ---- Rows -------------------------------------------------------------------------------------

// Whether a case meets its target: its ratio to the plain composite, or for the plain
// composite its ratio to RA, both from paired frames (pairedRatio); in CPU time too.
struct Verdict {
  double ratio = std::numeric_limits<double>::quiet_NaN();
  double cpuRatio = std::numeric_limits<double>::quiet_NaN();
  double target = 0;
  bool met = true;
};

Verdict verdictOf(const std::vector<CaseResult>& cases, std::size_t c) {
  Verdict v;
  if (c != kRa) {
    const CaseResult& reference = cases[c == kPlain ? kRa : kPlain];
    v.ratio = pairedRatio(cases[c].ms, reference.ms);
    v.cpuRatio = pairedRatio(cases[c].cpuMs, reference.cpuMs);
    v.target = c == kPlain ? kPlainOverRaTarget : cases[c].column->target;
  }
  v.met = !(v.target > 0) || !std::isfinite(v.ratio) || v.ratio <= v.target;
  return v;
}

nlohmann::json jsonRow(const Measured& m, int window, const std::vector<CaseResult>& cases,
                       std::size_t c, const BenchOptions& options) {
  const CaseResult& r = cases[c];
  const Verdict v = verdictOf(cases, c);
  nlohmann::json row = {{"table", "illustrate"},
                        {"dataset", m.dataset.name},
                        {"width", window},
                        {"height", window},
                        {"case", r.column->key},
                        {"technique", r.column->ra ? "rightangle" : "illustrate"},
                        {"effects", r.column->effects},
                        {"frames", r.stats.frames},
                        {"warmup", options.warmup},
                        {"ms_median", r.stats.msMedian},
                        {"ms_min", r.stats.msMin},
                        {"ms_max", r.stats.msMax},
                        {"fps", r.stats.fps()},
                        {"cpu_ms_median", median(r.cpuMs)},
                        {"ms", r.ms},
                        {"cpu_ms", r.cpuMs},
                        {"ra_fps", cases[kRa].stats.fps()},
                        {"plain_fps", cases[kPlain].stats.fps()},
                        {"covered_pixels_mean", r.coveredMedian},
                        {"slices", r.sliceCount},
                        {"dims", {m.dims.x, m.dims.y, m.dims.z}},
                        {"gl_backend", m.glBackend},
                        {"iso", m.dataset.iso},
                        {"gradient_build_ms", m.gradientMs},
                        {"check", checkText(r.problems)}};
  // The frame-time ratio: to the plain composite for the effects, to RA for the plain one.
  row["ratio"] = std::isfinite(v.ratio) ? nlohmann::json(v.ratio) : nlohmann::json();
  row["cpu_ratio"] = std::isfinite(v.cpuRatio) ? nlohmann::json(v.cpuRatio) : nlohmann::json();
  row["ratio_to"] = c == kPlain ? "ra" : c == kRa ? "" : "plain";
  row["target"] = v.target > 0 ? nlohmann::json(v.target) : nlohmann::json();
  row["target_met"] = v.met;
  return row;
}

nlohmann::json missingRow(const Measured& m, int window, const IllustrateCase& c) {
  return {{"table", "illustrate"}, {"dataset", m.dataset.name},
          {"width", window},       {"height", window},
          {"case", c.key},         {"frames", 0},
          {"ms_median", nullptr},  {"fps", nullptr},
          {"missing", m.missing},  {"check", nullptr}};
}

}  // namespace

std::optional<std::string> illustrateDatasetFile(const std::string& name) {
  return datasetFileOf(kDatasets, name);
}

std::vector<std::string> illustrateDatasetNames() {
  std::vector<std::string> names;
  for (const auto& d : kDatasets) names.push_back(d.name);
  return names;
}

TableResult runIllustrateTable(const BenchOptions& options, Progress& progress) {
  const std::vector<int> sizes = windowSizes(options);
  const std::vector<Choice> chosen =
      chooseDatasets(std::span<const IllustrateDataset>(kDatasets), options);
  int cases = 0;
  for (const auto& c : chosen) cases += c.missing.empty() ? int(sizes.size()) : 0;
  progress.setTotalCases(cases);
  std::vector<Measured> measured;
  for (const Choice& c : chosen) measured.push_back(measureDataset(c, sizes, options, progress));
  progress.finish();

  TableResult table;
  table.name = "illustrate";
  table.title =
      "Ebert–Rheingans volume illustration: fps of the plain composite, each effect alone and "
      "all together, frame-time ratios, RA from the same run";
  TextTable text({"dataset", "size", "window", "case", "fps", "ratio", "target", "RA fps", "cpu ms",
                  "cpu ratio", "check"});
  const auto& columns = illustrateCases();
  PlotSpec plot;
  plot.title = "illustrate: frames per second";
  plot.valueLabel = "fps";
  plot.logScale = false;
  for (std::size_t c = 0; c < columns.size(); ++c)
    plot.series.push_back({columns[c].key, false, int(c)});
  for (const Measured& m : measured) {
    for (const auto& window : m.windows) {
      if (!m.missing.empty()) {
        for (const auto& c : columns) table.rows.push_back(missingRow(m, window.size, c));
        continue;
      }
      std::vector<double> fps;
      for (std::size_t c = 0; c < window.cases.size(); ++c) {
        const CaseResult& r = window.cases[c];
        table.rows.push_back(jsonRow(m, window.size, window.cases, c, options));
        const Verdict v = verdictOf(window.cases, c);
        std::string check = r.problems.empty() ? "ok" : "FAILED";
        if (!v.met) check += " (over target)";
        text.addRow({m.dataset.name, dimsLabel(m.dims), std::to_string(window.size) + "²",
                     r.column->key, formatFps(r.stats.fps()),
                     c == kRa ? "–" : formatRatio(v.ratio) + (c == kPlain ? " ×RA" : ""),
                     v.target > 0 ? "≤ " + formatRatio(v.target) : "–",
                     formatFps(window.cases[kRa].stats.fps()), formatFps(median(r.cpuMs)),
                     c == kRa ? "–" : formatRatio(v.cpuRatio), check});
        fps.push_back(r.stats.fps());
        if (!r.problems.empty()) {
          table.failures.push_back(std::string(m.dataset.name) + " " + std::to_string(window.size) +
                                   "² " + r.column->key + ": " + joinedProblems(r.problems));
        }
      }
      plot.groups.push_back(std::string(m.dataset.name) + " " + std::to_string(window.size) + "²");
      plot.values.push_back(fps);
    }
    char note[256];
    if (m.missing.empty()) {
      std::snprintf(note, sizeof note,
                    "%s: transfer function 0 below %g, 0.1 at %g rising to 0.8 at %g (ivory); RA "
                    "at iso %g; gradient texture built once in %.0f ms (not in any frame)",
                    m.dataset.name, m.dataset.iso, m.dataset.iso, m.dataset.iso + 40, m.dataset.iso,
                    m.gradientMs);
    } else {
      std::snprintf(note, sizeof note, "%s: %s", m.dataset.name, m.missing.c_str());
    }
    table.notes.push_back(note);
  }
  char method[640];
  std::snprintf(method, sizeof method,
                "method: %d warm-up + %d timed frames per case, the cases taking turns frame by "
                "frame, orbit from azimuth %.0f° in steps of %.1f° at elevation %.0f°, 1 slice per "
                "voxel, empty-space skipping and early ray termination on; frame time = "
                "Renderer::render (slicing + glFinish + readback), fps = 1000 / median; ratio = "
                "the median over frames of the frame's time / the plain composite's in the same "
                "turn (for plain: / RA's); targets: effects ≤ 1.3 "
                "(halo ≤ 1.6, all ≤ 2), plain ≤ 1.5 × RA",
                options.warmup, options.frames, kOrbitStartDeg, kOrbitStepDeg, kElevationDeg);
  table.notes.insert(table.notes.begin(), method);
  table.text = text.plain();
  table.markdown = text.markdown();
  table.plot = plot;
  return table;
}

}  // namespace vsil::bench
