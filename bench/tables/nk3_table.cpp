// Table 3 in four steps, each a section below: choosing (the datasets and window sizes, and the
// missing ones), measuring (each case's frames, timed, then self-checked), rows (JSON rows,
// failed checks, table lines) and formatting (text, Markdown, plot, notes). runNk3Table at the
// end calls them in that order.
#include "tables/nk3_table.h"
#include "core/clock.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "harness/dataset_choice.h"
#include "harness/format.h"
#include "harness/text_table.h"
#include "harness/timing_stats.h"
#include "postfx/broaden.h"
#include "postfx/compose.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"
#include "slicing/technique_table.h"

namespace vsil::bench {
namespace {

// ---- The paper's numbers (Table 3; 3 GHz Pentium 4, ATI Fire GL X1) ------------------------

struct PaperFps {
  int window = 0;
  double ra = 0, ops = 0, bs = 0, raOverOps = 0;
};

// The datasets of Table 3. The paper does not state its iso values; ours were chosen from the
// value histograms (`vsil info`) and by looking at renders, so that the surface is the object
// the paper's figures show:
struct Nk3Dataset {
  const char* name;  // our name (--only, JSON "dataset"): the file's base name up to its size
  const char* paperName;
  const char* paperSize;
  const char* file;  // in the datasets folder; nullptr: no stored copy
  float iso;         // in the file's units (all five are 8-bit)
  PaperFps paper256, paper512;
  const char* isoReason;
};

const Nk3Dataset kDatasets[] = {
    {"bonsai",
     "Bonsai",
     "256³",
     "bonsai.vti",
     40.0f,
     {256, 39.37, 5.82, 3.24, 6.76},
     {512, 10.00, 1.60, 1.04, 6.25},
     "iso 40: trunk, branches and the pot; the foliage noise below ~30 stays outside"},
    {"engine",
     "Engine",
     "256²·128",
     "engine.vti",
     90.0f,
     {256, 54.13, 8.47, 4.27, 6.39},
     {512, 13.78, 2.30, 1.27, 5.99},
     "iso 90: the engine block without the low-density air noise"},
    {"hydrogen_atom",
     "Hydrog. Atom",
     "128³",
     "hydrogen_atom_128x128x128_uint8.nhdr",
     20.0f,
     {256, 39.37, 5.98, 3.51, 6.58},
     {512, 9.84, 1.60, 1.02, 6.15},
     "iso 20: the outer lobes and the torus of the probability cloud"},
    {"neghip",
     "NegHip",
     "64³",
     "neghip_64x64x64_uint8.nhdr",
     64.0f,
     {256, 19.95, 3.05, 2.26, 6.54},
     {512, 9.85, 1.58, 1.07, 6.23},
     "iso 64: the lobes of positive and negative potential"},
    {"skull",
     "Skull",
     "256³",
     nullptr,
     0.0f,
     {256, 39.41, 5.82, 3.61, 6.77},
     {512, 9.85, 1.58, 1.06, 6.23},
     ""},
    {"teddybear",
     "Teddy",
     "128²·64",
     "teddybear_128x128x62_uint8.nhdr",
     60.0f,
     {256, 44.0, 5.41, 3.37, 8.13},
     {512, 11.12, 1.47, 0.94, 7.56},
     "iso 60: the bear's surface (the scan's board above it stays at any iso; the background noise "
     "is below 33)"},
};

constexpr const char* kSkullMissing =
    "not available (no stored copy; see ../shared/datasets/README.md)";

// ---- Method ---------------------------------------------------------------------------------

// The camera orbit: timed frame i looks from azimuth kOrbitStartDeg + i·kOrbitStepDeg at
// elevation kElevationDeg (10 frames span 32.4°, "10 frames over 36°" counting the step after the
// last). Warm-up frames all look from the first position, so each can be compared with timed
// frame 0 byte for byte (rendering is deterministic).
constexpr double kOrbitStartDeg = 30.0;
constexpr double kOrbitStepDeg = 3.6;
constexpr double kElevationDeg = 20.0;
// BS: a fixed line width, as in the paper's broadened figures.
constexpr double kBroadenedWidth = 5.0;
// Self-check bounds, see checkFrames().
constexpr double kMaxStepChange = 0.25;
constexpr double kMinStepSlack = 0.125;
constexpr int kPlacementRadius = 2;
constexpr double kMinPlacedFraction = 0.98;

// The three columns of Table 3 (RA, OPS, BS), each measured once per slicing pipeline
// (technique_table.h: fast, paper, tiles; both techniques offer the same ones, so RA and OPS
// are compared like with like): what each renders (an entry of the table of techniques), with
// which pipeline, and what it adds after the render.
struct Nk3Column {
  // JSON "technique", progress and failures: ra, ops, bs for the fast pipeline (the keys the
  // table had before it had pipelines), ra-paper, ops-tiles, ... for the others
  std::string key;
  std::string label;     // the printed table and the plot: RA, OPS, BS
  std::string pipeline;  // --pipeline
  const TechniqueInfo& technique;
  bool broadened;        // BS: FFT broadening to kBroadenedWidth and composition, timed
  bool resolvesContour;  // finished frames hold no Contour pixel (the extra empty slice)
  double PaperFps::*paperFps;
  bool isDefault = false;  // `pipeline` is the technique's default: what a user gets
};

// The technique's --pipeline default (technique_table.h: each technique's fastest).
std::string defaultPipelineOf(const TechniqueInfo& technique) {
  return std::get<std::string>(*technique.option("pipeline")->defaultValue);
}

// Positions within a pipeline's three columns, for the checks between columns.
constexpr std::size_t kRa = 0, kOps = 1, kBs = 2, kColumnsPerPipeline = 3;

// The pipelines, fast first: its columns keep the keys ra, ops, bs that the table had before it
// had pipelines (fast was then both techniques' default; since, silhouette's is tiles).
const std::vector<std::string>& nk3Pipelines() {
  static const std::vector<std::string> pipelines = [] {
    const OptionSpec spec = pipelineOption(SlicingPipeline::Fast);
    const std::string first = pipelineName(SlicingPipeline::Fast);
    std::vector<std::string> ordered{first};
    for (const auto& choice : spec.choices) {
      if (choice != first) ordered.push_back(choice);
    }
    return ordered;
  }();
  return pipelines;
}

// kColumnsPerPipeline columns per pipeline, in nk3Pipelines() order.
const std::vector<Nk3Column>& nk3Columns() {
  static const std::vector<Nk3Column> columns = [] {
    std::vector<Nk3Column> all;
    for (const std::string& pipeline : nk3Pipelines()) {
      const std::string suffix = pipeline == nk3Pipelines().front() ? "" : "-" + pipeline;
      all.push_back({"ra" + suffix, "RA", pipeline, findTechnique("rightangle"), false, false,
                     &PaperFps::ra});
      all.push_back({"ops" + suffix, "OPS", pipeline, findTechnique("silhouette"), false, true,
                     &PaperFps::ops});
      all.push_back(
          {"bs" + suffix, "BS", pipeline, findTechnique("silhouette"), true, true, &PaperFps::bs});
    }
    for (Nk3Column& column : all) {
      column.isDefault = column.pipeline == defaultPipelineOf(column.technique);
    }
    return all;
  }();
  return columns;
}

// ---- Choosing: which datasets at which window sizes, and which of them cannot be measured ---

struct Nk3Choice {
  const Nk3Dataset& dataset;
  std::filesystem::path path;
  std::string missing;  // why it cannot be measured; empty: it can (if its file reads)
};

std::vector<int> windowSizes(const BenchOptions& options) {
  return options.sizes.empty() ? std::vector<int>{256, 512} : options.sizes;
}

std::vector<Nk3Choice> chooseDatasets(const BenchOptions& options) {
  std::vector<Nk3Choice> chosen;
  for (const Nk3Dataset& d : kDatasets) {
    if (!options.only.empty() &&
        std::find(options.only.begin(), options.only.end(), d.name) == options.only.end()) {
      continue;
    }
    if (!d.file) {
      chosen.push_back({d, {}, kSkullMissing});
      continue;
    }
    const std::filesystem::path path = options.datasetsDir / d.file;
    const bool found = std::filesystem::exists(path);
    chosen.push_back({d, path, found ? "" : notFound(path)});
  }
  return chosen;
}

int casesToMeasure(const std::vector<Nk3Choice>& chosen, const std::vector<int>& sizes) {
  const auto present = std::count_if(chosen.begin(), chosen.end(),
                                     [](const Nk3Choice& c) { return c.missing.empty(); });
  return int(present * std::ptrdiff_t(sizes.size()));
}

// ---- Measuring: the frames of each case, timed, then checked ---------------------------------

struct FrameSample {
  double ms = 0, renderMs = 0, readbackMs = 0, postfxMs = 0;
  double cpuMs = 0;  // the process's CPU time over the timed region, every llvmpipe thread
  int silhouettes = 0, filled = 0, contours = 0, linePixels = 0;
};

// One column at one window size.
struct CaseResult {
  const Nk3Column* column = nullptr;
  std::vector<FrameSample> frames;  // timed frames only
  TimingStats stats;
  cv::Mat1b firstState;  // timed frame 0 (orbit start)
  int sliceCount = 0;
  std::vector<std::string> problems;
};

// A dataset as measured: every window size, each with its cases (none when missing).
struct Nk3Measured {
  const Nk3Dataset& dataset;
  std::string missing;  // why it was not measured; empty: measured
  glm::ivec3 dims{0};
  struct Window {
    int size = 0;
    std::vector<CaseResult> cases;  // in nk3Columns() order
  };
  std::vector<Window> windows;
  std::string glBackend;  // the back end its frames ran on ("osmesa", "egl"): the JSON rows say it
};

void countStates(const cv::Mat1b& state, FrameSample& sample) {
  for (auto it = state.begin(); it != state.end(); ++it) {
    switch (PixelState(*it)) {
      case PixelState::Filled:
        ++sample.filled;
        break;
      case PixelState::Contour:
        ++sample.contours;
        break;
      case PixelState::Silhouette:
        ++sample.silhouettes;
        break;
      default:
        break;
    }
  }
}

cv::Mat1b statesEqualTo(const cv::Mat1b& state, PixelState wanted) {
  cv::Mat1b mask;
  cv::compare(state, int(wanted), mask, cv::CMP_EQ);
  return mask;
}

// Renders one frame of a case: warm-up frame `k` (k < warmup) or timed frame k - warmup. The
// timed region is the whole Renderer::render call (slicing ended by glFinish, then readback
// into CPU images) and, for BS, the broadening and the composition of the illustration after
// it. Counting pixels for the self-checks happens after the timed region.
void renderFrame(Renderer& renderer, RenderSettings settings, int k, const BenchOptions& options,
                 FftGaussianBlur& blur, CaseResult& result, std::vector<cv::Mat1b>& warmupStates) {
  const Nk3Column& column = *result.column;
  settings.technique = column.technique.name;
  settings.options["pipeline"] = column.pipeline;
  const bool warm = k < options.warmup;
  const int timedIndex = k - options.warmup;
  settings.camera.azimuthDeg = kOrbitStartDeg + kOrbitStepDeg * std::max(timedIndex, 0);
  PostfxOptions postfx;
  postfx.width = WidthLaw::fixed(kBroadenedWidth);

  FrameSample sample;
  const double cpuStart = processCpuMs();
  const auto start = std::chrono::steady_clock::now();
  RenderResult frame = renderer.render(settings);
  cv::Mat1b lines;
  if (column.broadened) {
    const auto postStart = std::chrono::steady_clock::now();
    lines = broadenSilhouettes(frame.frame, postfx.width, blur);
    const cv::Mat illustration = composeIllustration(frame.frame, postfx, blur, lines);
    sample.postfxMs = millisecondsSince(postStart);
    if (illustration.size() != frame.frame.state.size()) {
      result.problems.push_back("the illustration has the wrong size");
    }
  }
  sample.ms = millisecondsSince(start);
  sample.cpuMs = processCpuMs() - cpuStart;
  sample.renderMs = frame.timings.render.wallMs + frame.timings.programs.wallMs;
  sample.readbackMs = frame.timings.readback.wallMs;
  result.sliceCount = frame.sliceCount;

  const cv::Mat1b& state = frame.frame.state;
  if (state.cols != settings.size.x || state.rows != settings.size.y) {
    result.problems.push_back("the state image is " + std::to_string(state.cols) + "x" +
                              std::to_string(state.rows));
    return;
  }
  countStates(state, sample);
  if (column.broadened) {
    sample.linePixels = cv::countNonZero(lines);
    cv::Mat1b uncovered;
    cv::bitwise_and(statesEqualTo(state, PixelState::Silhouette), ~lines, uncovered);
    if (const int n = cv::countNonZero(uncovered); n > 0) {
      result.problems.push_back("frame " + std::to_string(timedIndex + 1) + ": " +
                                std::to_string(n) + " silhouette pixels missing from the lines");
    }
  }
  if (warm) {
    warmupStates.push_back(state.clone());
    return;
  }
  if (timedIndex == 0) result.firstState = state.clone();
  result.frames.push_back(sample);
}

// Runs RA, OPS and BS of every pipeline at one window size. They take turns frame by frame (RA,
// OPS, BS of each pipeline at the first orbit position, then at the next, ...), so that load
// from other processes on a shared machine falls on all of them alike and their ratios stay
// meaningful.
std::vector<CaseResult> runCases(Renderer& renderer, const RenderSettings& settings,
                                 const std::string& label, const BenchOptions& options,
                                 Progress& progress) {
  const std::vector<Nk3Column>& columns = nk3Columns();
  std::vector<CaseResult> results(columns.size());
  for (std::size_t t = 0; t < columns.size(); ++t) results[t].column = &columns[t];
  std::vector<std::vector<cv::Mat1b>> warmupStates(columns.size());
  FftGaussianBlur blur;  // plans cached per window size, made during the warm-up frames
  progress.startCase(label);
  const int total = options.warmup + options.frames;
  for (int k = 0; k < total; ++k) {
    for (std::size_t t = 0; t < columns.size(); ++t) {
      const bool warm = k < options.warmup;
      progress.step(columns[t].key + " " +
                    (warm
                         ? "warm-up " + std::to_string(k + 1) + "/" + std::to_string(options.warmup)
                         : "frame " + std::to_string(k - options.warmup + 1) + "/" +
                               std::to_string(options.frames)));
      renderFrame(renderer, settings, k, options, blur, results[t], warmupStates[t]);
    }
  }
  for (std::size_t t = 0; t < columns.size(); ++t) {
    CaseResult& result = results[t];
    std::vector<double> ms;
    for (const auto& f : result.frames) ms.push_back(f.ms);
    result.stats = summarize(ms);
    for (std::size_t i = 0; i < warmupStates[t].size(); ++i) {
      if (!result.firstState.empty() &&
          cv::countNonZero(warmupStates[t][i] != result.firstState) != 0) {
        result.problems.push_back("warm-up frame " + std::to_string(i + 1) +
                                  " differs from timed frame 1 (same view: not deterministic)");
      }
    }
  }
  return results;
}

// Checks one case's own output, so that a fast wrong result cannot pass:
//  - every frame has silhouette (line) pixels, and OPS/BS frames hold no Contour pixel (the
//    extra empty slice resolves them all);
//  - the silhouette count is stable along the orbit: consecutive frames are 3.6° apart, which
//    moves an outline by a few pixels but cannot change its length much. The bound between
//    neighbours is 25 % of the larger count, but at least kMinStepSlack·window pixels, since
//    small outlines (a few dozen pixels at 64²) change by whole stair steps. Measured on the
//    five datasets at 256² and 512² (JSON field "silhouette_step_change_max"): OPS at most 3 %,
//    RA at most 18 % (its lines are short dashes of a thresholded dot product that come and
//    go). A frame that lost or invented a large part of its lines exceeds the bound.
void checkFrames(CaseResult& result, int window) {
  for (std::size_t i = 0; i < result.frames.size(); ++i) {
    const FrameSample& f = result.frames[i];
    const std::string frame = "frame " + std::to_string(i + 1);
    if (f.silhouettes == 0) result.problems.push_back(frame + " has no line pixels");
    if (result.column->resolvesContour && f.contours != 0) {
      result.problems.push_back(frame + " has " + std::to_string(f.contours) +
                                " Contour pixels (a finished frame has none)");
    }
    if (result.column->broadened && f.linePixels < f.silhouettes) {
      result.problems.push_back(frame + ": fewer broadened line pixels than silhouette pixels");
    }
    if (i == 0) continue;
    const double a = result.frames[i - 1].silhouettes, b = f.silhouettes;
    if (std::abs(b - a) > std::max(kMaxStepChange * std::max(a, b), kMinStepSlack * window)) {
      char text[160];
      std::snprintf(text, sizeof text, "silhouette count jumps %d -> %d between frames %zu and %zu",
                    int(a), int(b), i, i + 1);
      result.problems.push_back(text);
    }
  }
}

// The largest relative change of the silhouette count between consecutive timed frames.
double maxStepChange(const std::vector<FrameSample>& frames) {
  double largest = 0;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    const double a = frames[i - 1].silhouettes, b = frames[i].silhouettes;
    largest = std::max(largest, std::abs(b - a) / std::max(1.0, std::max(a, b)));
  }
  return largest;
}

// OPS frames of another pipeline show the silhouettes of the fast pipeline's, frame for
// frame, up to a few pixels: where a slice polygon's edge passes within a rounding error of a
// pixel centre, rasterisation (fast, paper) and the texture-extent test alone (tiles, like the
// CPU reference) may decide that pixel differently.
constexpr double kPipelineSlack = 0.002;
void checkPipelinesAgree(const CaseResult& reference, CaseResult& other) {
  for (std::size_t i = 0; i < std::min(reference.frames.size(), other.frames.size()); ++i) {
    const double a = reference.frames[i].silhouettes, b = other.frames[i].silhouettes;
    if (std::abs(a - b) > std::max(2.0, kPipelineSlack * a)) {
      other.problems.push_back("frame " + std::to_string(i + 1) + " has " + std::to_string(int(b)) +
                               " silhouette pixels, " + reference.column->key + " had " +
                               std::to_string(int(a)));
      return;
    }
  }
}

// The same views give the same silhouettes: BS renders what OPS rendered, frame for frame.
void checkSameSilhouettes(const CaseResult& ops, CaseResult& bs) {
  for (std::size_t i = 0; i < std::min(ops.frames.size(), bs.frames.size()); ++i) {
    if (ops.frames[i].silhouettes != bs.frames[i].silhouettes) {
      bs.problems.push_back(
          "frame " + std::to_string(i + 1) + " has " + std::to_string(bs.frames[i].silhouettes) +
          " silhouette pixels, OPS had " + std::to_string(ops.frames[i].silhouettes));
      return;
    }
  }
}

// RA and OPS see the same iso-surface from the same camera: OPS silhouette pixels lie on the
// outline of the surface's footprint, which RA covers with its first hits (Filled or line). At
// least 98 % of them must lie within 2 pixels of RA's footprint (both sample the same slices;
// the slack is for thin features that one technique's sampling catches and the other's misses).
void checkPlacement(const CaseResult& ra, CaseResult& ops) {
  if (ra.firstState.empty() || ops.firstState.empty()) return;
  cv::Mat1b footprint;
  cv::compare(ra.firstState, int(PixelState::Empty), footprint, cv::CMP_NE);
  const int size = 2 * kPlacementRadius + 1;
  cv::dilate(footprint, footprint, cv::getStructuringElement(cv::MORPH_RECT, {size, size}));
  const cv::Mat1b silhouettes = statesEqualTo(ops.firstState, PixelState::Silhouette);
  const int all = cv::countNonZero(silhouettes);
  if (all == 0) return;  // reported by checkFrames
  cv::Mat1b placed;
  cv::bitwise_and(silhouettes, footprint, placed);
  const double fraction = double(cv::countNonZero(placed)) / all;
  if (fraction < kMinPlacedFraction) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "only %.1f %% of the silhouette pixels lie within %d px of RA's surface",
                  100.0 * fraction, kPlacementRadius);
    ops.problems.push_back(text);
  }
}

// RA, OPS and BS of every pipeline for one dataset at one window size, each checked on its own
// and against the others.
std::vector<CaseResult> measureWindow(Renderer& renderer, const Nk3Dataset& d, int window,
                                      const BenchOptions& options, Progress& progress) {
  RenderSettings settings;
  settings.size = {window, window};
  settings.options["iso"] = double(d.iso);
  settings.camera.elevationDeg = kElevationDeg;
  settings.samplesPerVoxel = 1.0;
  std::vector<CaseResult> results =
      runCases(renderer, settings, std::string(d.name) + " " + std::to_string(window) + "²",
               options, progress);
  for (CaseResult& result : results) checkFrames(result, window);
  for (std::size_t first = 0; first < results.size(); first += kColumnsPerPipeline) {
    checkPlacement(results[first + kRa], results[first + kOps]);
    checkSameSilhouettes(results[first + kOps], results[first + kBs]);
    if (first > 0) checkPipelinesAgree(results[kOps], results[first + kOps]);
  }
  return results;
}

// Every window size of a chosen dataset; one GL context and one renderer for them all, and the
// upload is not timed. A file that cannot be read makes the dataset missing, not the run fail.
Nk3Measured measureDataset(const Nk3Choice& chosen, const std::vector<int>& sizes,
                           const BenchOptions& options, Progress& progress) {
  Nk3Measured measured{chosen.dataset, chosen.missing, {}, {}, {}};
  for (int window : sizes) measured.windows.push_back({window, {}});
  if (!measured.missing.empty()) return measured;
  const std::optional<Volume> volume = readDatasetVolume(chosen.path, measured.missing);
  if (!volume) return measured;
  measured.dims = volume->dims;
  gl::GlContext context(options.gl);
  measured.glBackend = gl::backendName(context.info().backend);
  Renderer renderer(context);
  renderer.setVolume(*volume);
  for (auto& window : measured.windows) {
    window.cases = measureWindow(renderer, chosen.dataset, window.size, options, progress);
  }
  return measured;
}

// ---- Rows: the JSON rows, the failed checks, and the lines of the printed table --------------

std::optional<PaperFps> paperFor(const Nk3Dataset& dataset, int window) {
  if (window == 256) return dataset.paper256;
  if (window == 512) return dataset.paper512;
  return std::nullopt;
}

template <typename Field>
std::vector<double> valuesOf(const std::vector<FrameSample>& frames, Field FrameSample::*field) {
  std::vector<double> values;
  for (const auto& f : frames) values.push_back(double(f.*field));
  return values;
}

template <typename Field>
double medianOf(const std::vector<FrameSample>& frames, Field FrameSample::*field) {
  return median(valuesOf(frames, field));
}

// Issue 36's ratio, as a user gets it: OPS at its default pipeline over RA at its default, in
// frame time (`field` &FrameSample::cpuMs: in CPU time, steadier on a loaded machine), from the
// frames taken in turn (runCases) paired (pairedRatio). nullopt when either is missing or a
// time is not positive.
std::optional<double> opsDefaultOverRaDefault(const std::vector<CaseResult>& cases,
                                              double FrameSample::*field = &FrameSample::ms) {
  const auto& columns = nk3Columns();
  const CaseResult *ra = nullptr, *ops = nullptr;
  for (const CaseResult& c : cases) {
    if (!c.column->isDefault || c.column->broadened) continue;
    if (c.column->label == columns[kRa].label) ra = &c;
    if (c.column->label == columns[kOps].label) ops = &c;
  }
  if (!ra || !ops) return std::nullopt;
  const double ratio = pairedRatio(valuesOf(ops->frames, field), valuesOf(ra->frames, field));
  if (!std::isfinite(ratio)) return std::nullopt;
  return ratio;
}

// RA/OPS of one pipeline's columns (the case holding RA and the one holding OPS): RA's frame
// rate over OPS's, from the frames taken in turn, paired as every ratio the tables print.
std::optional<double> raOverOps(const CaseResult& ra, const CaseResult& ops) {
  const double ratio =
      pairedRatio(valuesOf(ops.frames, &FrameSample::ms), valuesOf(ra.frames, &FrameSample::ms));
  if (!std::isfinite(ratio)) return std::nullopt;
  return ratio;
}

nlohmann::json jsonOrNull(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json();
}

// What a row says of any case, measured or missing.
nlohmann::json caseRow(const Nk3Dataset& d, int window, const Nk3Column& column) {
  const auto paper = paperFor(d, window);
  return {{"table", "nk3"},
          {"dataset", d.name},
          {"width", window},
          {"height", window},
          {"technique", column.key},
          {"pipeline", column.pipeline},
          {"default_pipeline", column.isDefault},
          {"paper_fps", paper ? nlohmann::json((*paper).*column.paperFps) : nlohmann::json()}};
}

nlohmann::json missingRow(const Nk3Measured& m, int window, const Nk3Column& column) {
  nlohmann::json row = caseRow(m.dataset, window, column);
  row.update({{"frames", 0},
              {"ms_median", nullptr},
              {"ms_min", nullptr},
              {"ms_max", nullptr},
              {"fps", nullptr},
              {"missing", m.missing},
              {"ops_default_over_ra_default", nullptr},
              {"ops_default_over_ra_default_cpu", nullptr},
              {"ra_over_ops", nullptr},
              {"check", nullptr}});
  return row;
}

nlohmann::json measuredRow(const Nk3Measured& m, int window, const CaseResult& r,
                           std::optional<double> opsOverRa, std::optional<double> opsOverRaCpu,
                           std::optional<double> pipelineRaOverOps, const BenchOptions& options) {
  nlohmann::json row = caseRow(m.dataset, window, *r.column);
  row.update({{"frames", r.stats.frames},
              {"warmup", options.warmup},
              {"ms_median", r.stats.msMedian},
              {"ms_min", r.stats.msMin},
              {"ms_max", r.stats.msMax},
              {"fps", r.stats.fps()},
              {"render_ms_median", medianOf(r.frames, &FrameSample::renderMs)},
              {"readback_ms_median", medianOf(r.frames, &FrameSample::readbackMs)},
              {"postfx_ms_median", medianOf(r.frames, &FrameSample::postfxMs)},
              {"silhouette_pixels_median", medianOf(r.frames, &FrameSample::silhouettes)},
              {"silhouette_step_change_max", maxStepChange(r.frames)},
              {"iso", m.dataset.iso},
              {"dims", {m.dims.x, m.dims.y, m.dims.z}},
              {"gl_backend", m.glBackend},
              {"slices", r.sliceCount},
              {"cpu_ms_median", medianOf(r.frames, &FrameSample::cpuMs)},
              {"ms", valuesOf(r.frames, &FrameSample::ms)},
              {"cpu_ms", valuesOf(r.frames, &FrameSample::cpuMs)},
              {"ops_default_over_ra_default", jsonOrNull(opsOverRa)},
              {"ops_default_over_ra_default_cpu", jsonOrNull(opsOverRaCpu)},
              {"ra_over_ops", jsonOrNull(pipelineRaOverOps)},
              {"check", checkText(r.problems)}});
  if (r.column->broadened) {
    row["line_width"] = kBroadenedWidth;
    row["line_pixels_median"] = medianOf(r.frames, &FrameSample::linePixels);
  }
  return row;
}

// One row per window size and column.
std::vector<nlohmann::json> jsonRows(const Nk3Measured& m, const BenchOptions& options) {
  std::vector<nlohmann::json> rows;
  for (const auto& window : m.windows) {
    if (!m.missing.empty()) {
      for (const Nk3Column& column : nk3Columns()) {
        rows.push_back(missingRow(m, window.size, column));
      }
    }
    const std::optional<double> opsOverRa = opsDefaultOverRaDefault(window.cases);
    const std::optional<double> opsOverRaCpu =
        opsDefaultOverRaDefault(window.cases, &FrameSample::cpuMs);
    for (std::size_t i = 0; i < window.cases.size(); ++i) {
      // RA/OPS of the pipeline this case belongs to (its columns come kColumnsPerPipeline apart).
      const std::size_t first = i - i % kColumnsPerPipeline;
      const std::optional<double> pipelineRaOverOps =
          first + kOps < window.cases.size()
              ? raOverOps(window.cases[first + kRa], window.cases[first + kOps])
              : std::nullopt;
      rows.push_back(measuredRow(m, window.size, window.cases[i], opsOverRa, opsOverRaCpu,
                                 pipelineRaOverOps, options));
    }
  }
  return rows;
}

// "bonsai 512² ops: reason; reason" for each case whose checks failed.
std::vector<std::string> failedChecks(const Nk3Measured& m) {
  std::vector<std::string> failures;
  for (const auto& window : m.windows) {
    for (const CaseResult& r : window.cases) {
      if (r.problems.empty()) continue;
      failures.push_back(std::string(m.dataset.name) + " " + std::to_string(window.size) + "² " +
                         r.column->key + ": " + joinedProblems(r.problems));
    }
  }
  return failures;
}

// One line of the printed table: a dataset at one window size with one pipeline.
struct Nk3Line {
  std::string dataset, size, window, pipeline;
  std::vector<double> fps;          // RA, OPS, BS (0: not measured)
  std::optional<double> raOverOps;  // paired (raOverOps)
  std::optional<PaperFps> paper;
  std::string check;
  // On a window's first line only: the ratio belongs to the window, not to one pipeline.
  std::optional<double> opsDefaultOverRaDefault = std::nullopt;
  std::optional<double> opsDefaultOverRaDefaultCpu = std::nullopt;
};

std::vector<Nk3Line> tableLines(const Nk3Measured& m) {
  std::vector<Nk3Line> lines;
  const bool missing = !m.missing.empty();
  const auto& columns = nk3Columns();
  for (const auto& window : m.windows) {
    for (std::size_t first = 0; first < columns.size(); first += kColumnsPerPipeline) {
      Nk3Line line{
          m.dataset.name, missing ? m.dataset.paperSize : dimsLabel(m.dims),
          std::to_string(window.size) + "²", columns[first].pipeline,
          std::vector<double>(kColumnsPerPipeline, 0.0), std::nullopt,
          paperFor(m.dataset, window.size), missing ? "missing" : "ok",
          // the window's ratio, on its first line only
          first == 0 ? opsDefaultOverRaDefault(window.cases) : std::nullopt,
          first == 0 ? opsDefaultOverRaDefault(window.cases, &FrameSample::cpuMs) : std::nullopt};
      std::string failed;
      for (std::size_t i = 0; i < kColumnsPerPipeline && first + i < window.cases.size(); ++i) {
        const CaseResult& result = window.cases[first + i];
        line.fps[i] = result.stats.fps();
        if (!result.problems.empty()) failed += " " + result.column->key;
      }
      if (!failed.empty()) line.check = "FAILED:" + failed;
      if (first + kOps < window.cases.size()) {
        line.raOverOps = raOverOps(window.cases[first + kRa], window.cases[first + kOps]);
      }
      lines.push_back(std::move(line));
    }
  }
  return lines;
}

// ---- Formatting: the printed table, Markdown, the plot and the notes -------------------------

// Ours, then the paper's: fps per column and RA/OPS.
TextTable textTable(const std::vector<Nk3Line>& lines) {
  const auto& columns = nk3Columns();
  std::vector<std::string> header{"dataset", "size", "window", "pipeline"};
  for (std::size_t i = 0; i < kColumnsPerPipeline; ++i) header.push_back(columns[i].label + " fps");
  header.push_back("RA/OPS");
  header.push_back("OPS default / RA default");
  header.push_back("cpu OPS default / RA default");
  for (std::size_t i = 0; i < kColumnsPerPipeline; ++i)
    header.push_back("paper " + columns[i].label);
  header.insert(header.end(), {"paper RA/OPS", "check"});
  TextTable text(header);
  for (const Nk3Line& l : lines) {
    std::vector<std::string> cells{l.dataset, l.size, l.window, l.pipeline};
    for (double fps : l.fps) cells.push_back(formatFps(fps));
    cells.push_back(l.raOverOps ? formatRatio(*l.raOverOps) : "");
    cells.push_back(l.opsDefaultOverRaDefault ? formatRatio(*l.opsDefaultOverRaDefault) : "");
    cells.push_back(l.opsDefaultOverRaDefaultCpu ? formatRatio(*l.opsDefaultOverRaDefaultCpu) : "");
    for (std::size_t i = 0; i < kColumnsPerPipeline; ++i) {
      cells.push_back(l.paper ? formatFps((*l.paper).*columns[i].paperFps) : "–");
    }
    cells.push_back(l.paper ? formatRatio(l.paper->raOverOps) : "–");
    cells.push_back(l.check);
    text.addRow(std::move(cells));
  }
  return text;
}

// Bars per line: each column's fps, ours solid beside the paper's hatched.
PlotSpec plotSpec(const std::vector<Nk3Line>& lines) {
  const auto& columns = nk3Columns();
  PlotSpec plot;
  plot.title = "nk3: frames per second (ours solid, paper hatched)";
  plot.valueLabel = "fps";
  plot.logScale = true;
  for (std::size_t i = 0; i < kColumnsPerPipeline; ++i) {
    plot.series.push_back({columns[i].label, false, int(i)});
    plot.series.push_back({columns[i].label + " paper", true, int(i)});
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Nk3Line& l : lines) {
    plot.groups.push_back(l.dataset + " " + l.window + " " + l.pipeline);
    std::vector<double> values;
    for (std::size_t i = 0; i < kColumnsPerPipeline; ++i) {
      values.push_back(l.fps[i] > 0 ? l.fps[i] : nan);
      values.push_back(l.paper ? (*l.paper).*columns[i].paperFps : nan);
    }
    plot.values.push_back(std::move(values));
  }
  return plot;
}

std::string methodNote(const BenchOptions& options) {
  std::string pipelines;
  for (const auto& pipeline : nk3Pipelines())
    pipelines += (pipelines.empty() ? "" : ", ") + pipeline;
  char method[640];
  std::snprintf(method, sizeof method,
                "method: %d warm-up + %d timed frames per technique and pipeline (%s; RA and OPS "
                "with the same one), all taking turns, orbit from azimuth %.0f° in "
                "steps of %.1f° at elevation %.0f°, 1 slice per voxel, empty-space skipping on for "
                "RA and OPS alike (the paper pipeline never skips); frame time = "
                "Renderer::render (slicing + glFinish + readback), fps = 1000 / median; "
                "BS adds broadening to W = %.0f px and composition",
                options.warmup, options.frames, pipelines.c_str(), kOrbitStartDeg, kOrbitStepDeg,
                kElevationDeg, kBroadenedWidth);
  return method;
}

// What the column of the defaults' ratio compares.
std::string defaultsNote() {
  const auto& columns = nk3Columns();
  return "OPS default / RA default: the frame time of " + columns[kOps].label +
         " at its default pipeline (" + defaultPipelineOf(columns[kOps].technique) + ") over " +
         columns[kRa].label + "'s at its default (" + defaultPipelineOf(columns[kRa].technique) +
         ") in the same turn, as a user gets them, the median over frames, on each window's "
         "first line; cpu: the same in the process's CPU time per frame (steadier on a loaded "
         "machine); JSON: ops_default_over_ra_default(_cpu) on every row of the window";
}

// Why a dataset is missing, or the iso value it was measured at and why.
std::string datasetNote(const Nk3Measured& m) {
  return std::string(m.dataset.paperName) + ": " +
         (m.missing.empty() ? std::string(m.dataset.isoReason) : m.missing);
}

}  // namespace

std::vector<std::string> nk3DatasetNames() {
  std::vector<std::string> names;
  for (const auto& d : kDatasets) names.push_back(d.name);
  return names;
}

std::optional<Nk3DatasetFile> nk3DatasetFile(const std::string& name) {
  for (const auto& d : kDatasets) {
    if (d.name == name && d.file) return Nk3DatasetFile{d.file, d.iso, d.isoReason};
  }
  return std::nullopt;
}

TableResult runNk3Table(const BenchOptions& options, Progress& progress) {
  const std::vector<int> sizes = windowSizes(options);
  const std::vector<Nk3Choice> chosen = chooseDatasets(options);
  progress.setTotalCases(casesToMeasure(chosen, sizes));
  std::vector<Nk3Measured> measured;
  for (const Nk3Choice& c : chosen) measured.push_back(measureDataset(c, sizes, options, progress));
  progress.finish();

  TableResult table;
  table.name = "nk3";
  table.title =
      "Nagy–Klein Table 3: frames per second, ours beside the paper's (3 GHz Pentium 4, "
      "ATI Fire GL X1)";
  table.notes.push_back(methodNote(options));
  table.notes.push_back(defaultsNote());
  std::vector<Nk3Line> lines;
  for (const Nk3Measured& m : measured) {
    table.notes.push_back(datasetNote(m));
    for (auto& row : jsonRows(m, options)) table.rows.push_back(std::move(row));
    const auto failures = failedChecks(m);
    table.failures.insert(table.failures.end(), failures.begin(), failures.end());
    const auto datasetLines = tableLines(m);
    lines.insert(lines.end(), datasetLines.begin(), datasetLines.end());
  }
  const TextTable text = textTable(lines);
  table.text = text.plain();
  table.markdown = text.markdown();
  table.plot = plotSpec(lines);
  return table;
}

}  // namespace vsil::bench
