#include "tables/nk3_table.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "harness/text_table.h"
#include "harness/timing_stats.h"
#include "io/volume_loader.h"
#include "postfx/broaden.h"
#include "postfx/compose.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"

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

enum class Technique { Ra, Ops, Bs };
const char* techniqueKey(Technique t) {
  return t == Technique::Ra ? "ra" : t == Technique::Ops ? "ops" : "bs";
}

struct FrameSample {
  double ms = 0, renderMs = 0, readbackMs = 0, postfxMs = 0;
  int silhouettes = 0, filled = 0, contours = 0, linePixels = 0;
};

struct CaseResult {
  Technique technique = Technique::Ops;
  std::vector<FrameSample> frames;  // timed frames only
  TimingStats stats;
  cv::Mat1b firstState;  // timed frame 0 (orbit start)
  int sliceCount = 0;
  std::vector<std::string> problems;
};

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

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
  const Technique technique = result.technique;
  settings.technique = technique == Technique::Ra ? "rightangle" : "silhouette";
  const bool warm = k < options.warmup;
  const int timedIndex = k - options.warmup;
  settings.camera.azimuthDeg = kOrbitStartDeg + kOrbitStepDeg * std::max(timedIndex, 0);
  PostfxOptions postfx;
  postfx.width = WidthLaw::fixed(kBroadenedWidth);

  FrameSample sample;
  const auto start = std::chrono::steady_clock::now();
  RenderResult frame = renderer.render(settings);
  cv::Mat1b lines;
  if (technique == Technique::Bs) {
    const auto postStart = std::chrono::steady_clock::now();
    lines = broadenSilhouettes(frame.frame, postfx.width, blur);
    const cv::Mat illustration = composeIllustration(frame.frame, postfx, blur, lines);
    sample.postfxMs = msSince(postStart);
    if (illustration.size() != frame.frame.state.size()) {
      result.problems.push_back("the illustration has the wrong size");
    }
  }
  sample.ms = msSince(start);
  sample.renderMs = frame.timings.renderMs;
  sample.readbackMs = frame.timings.readbackMs;
  result.sliceCount = frame.sliceCount;

  const cv::Mat1b& state = frame.frame.state;
  if (state.cols != settings.size.x || state.rows != settings.size.y) {
    result.problems.push_back("the state image is " + std::to_string(state.cols) + "x" +
                              std::to_string(state.rows));
    return;
  }
  countStates(state, sample);
  if (technique == Technique::Bs) {
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

// Runs RA, OPS and BS at one window size. The techniques take turns frame by frame (RA, OPS,
// BS at the first orbit position, then at the next, ...), so that load from other processes
// on a shared machine falls on all three alike and their ratios stay meaningful.
std::vector<CaseResult> runCases(Renderer& renderer, const RenderSettings& settings,
                                 const std::string& label, const BenchOptions& options,
                                 Progress& progress) {
  const Technique techniques[] = {Technique::Ra, Technique::Ops, Technique::Bs};
  std::vector<CaseResult> results(3);
  std::vector<std::vector<cv::Mat1b>> warmupStates(3);
  FftGaussianBlur blur;  // plans cached per window size, made during the warm-up frames
  progress.startCase(label);
  const int total = options.warmup + options.frames;
  for (int k = 0; k < total; ++k) {
    for (int t = 0; t < 3; ++t) {
      results[t].technique = techniques[t];
      const bool warm = k < options.warmup;
      progress.step(std::string(techniqueKey(techniques[t])) + " " +
                    (warm
                         ? "warm-up " + std::to_string(k + 1) + "/" + std::to_string(options.warmup)
                         : "frame " + std::to_string(k - options.warmup + 1) + "/" +
                               std::to_string(options.frames)));
      renderFrame(renderer, settings, k, options, blur, results[t], warmupStates[t]);
    }
  }
  for (int t = 0; t < 3; ++t) {
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
// The largest relative change of the silhouette count between consecutive timed frames.
double maxStepChange(const std::vector<FrameSample>& frames) {
  double largest = 0;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    const double a = frames[i - 1].silhouettes, b = frames[i].silhouettes;
    largest = std::max(largest, std::abs(b - a) / std::max(1.0, std::max(a, b)));
  }
  return largest;
}

void checkFrames(CaseResult& result, int window) {
  for (std::size_t i = 0; i < result.frames.size(); ++i) {
    const FrameSample& f = result.frames[i];
    const std::string frame = "frame " + std::to_string(i + 1);
    if (f.silhouettes == 0) result.problems.push_back(frame + " has no line pixels");
    if (result.technique != Technique::Ra && f.contours != 0) {
      result.problems.push_back(frame + " has " + std::to_string(f.contours) +
                                " Contour pixels (a finished frame has none)");
    }
    if (result.technique == Technique::Bs && f.linePixels < f.silhouettes) {
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

double medianOf(const std::vector<FrameSample>& frames, double FrameSample::*field) {
  std::vector<double> values;
  for (const auto& f : frames) values.push_back(f.*field);
  return median(values);
}
double medianOf(const std::vector<FrameSample>& frames, int FrameSample::*field) {
  std::vector<double> values;
  for (const auto& f : frames) values.push_back(f.*field);
  return median(values);
}

std::optional<PaperFps> paperFor(const Nk3Dataset& dataset, int window) {
  if (window == 256) return dataset.paper256;
  if (window == 512) return dataset.paper512;
  return std::nullopt;
}

double paperFpsOf(const PaperFps& p, Technique t) {
  return t == Technique::Ra ? p.ra : t == Technique::Ops ? p.ops : p.bs;
}

std::string dimsLabel(glm::ivec3 dims) {
  if (dims.x == dims.y && dims.y == dims.z) return std::to_string(dims.x) + "³";
  if (dims.x == dims.y) return std::to_string(dims.x) + "²·" + std::to_string(dims.z);
  return std::to_string(dims.x) + "·" + std::to_string(dims.y) + "·" + std::to_string(dims.z);
}

std::string formatFps(double fps) {
  if (!(fps > 0)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, fps >= 100 ? "%.0f" : fps >= 10 ? "%.1f" : "%.2f", fps);
  return text;
}

std::string formatRatio(double ratio) {
  if (!(ratio > 0) || !std::isfinite(ratio)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", ratio);
  return text;
}

// One line of the printed table: a dataset at one window size.
struct Nk3Line {
  std::string dataset, size, window;
  double fps[3] = {0, 0, 0};  // ra, ops, bs (0: not measured)
  std::optional<PaperFps> paper;
  std::string check;
};

}  // namespace

std::vector<std::string> nk3DatasetNames() {
  std::vector<std::string> names;
  for (const auto& d : kDatasets) names.push_back(d.name);
  return names;
}

TableResult runNk3Table(const BenchOptions& options, Progress& progress) {
  TableResult table;
  table.name = "nk3";
  table.title =
      "Nagy–Klein Table 3: frames per second, ours beside the paper's (3 GHz Pentium 4, "
      "ATI Fire GL X1)";
  const std::vector<int> sizes = options.sizes.empty() ? std::vector<int>{256, 512} : options.sizes;

  std::vector<const Nk3Dataset*> selected;
  for (const auto& d : kDatasets) {
    if (options.only.empty() ||
        std::find(options.only.begin(), options.only.end(), d.name) != options.only.end()) {
      selected.push_back(&d);
    }
  }
  int cases = 0;
  for (const auto* d : selected) {
    if (d->file && std::filesystem::exists(options.datasetsDir / d->file)) {
      cases += int(sizes.size());
    }
  }
  progress.setTotalCases(cases);

  std::vector<Nk3Line> lines;
  const Technique techniques[] = {Technique::Ra, Technique::Ops, Technique::Bs};

  auto missingRows = [&](const Nk3Dataset& d, const std::string& reason) {
    table.notes.push_back(std::string(d.paperName) + ": " + reason);
    for (int window : sizes) {
      const auto paper = paperFor(d, window);
      lines.push_back(
          {d.name, d.paperSize, std::to_string(window) + "²", {0, 0, 0}, paper, "missing"});
      for (Technique t : techniques) {
        table.rows.push_back(
            {{"table", "nk3"},
             {"dataset", d.name},
             {"width", window},
             {"height", window},
             {"technique", techniqueKey(t)},
             {"frames", 0},
             {"ms_median", nullptr},
             {"ms_min", nullptr},
             {"ms_max", nullptr},
             {"fps", nullptr},
             {"paper_fps", paper ? nlohmann::json(paperFpsOf(*paper, t)) : nlohmann::json(nullptr)},
             {"missing", reason},
             {"check", nullptr}});
      }
    }
  };

  for (const Nk3Dataset* d : selected) {
    if (!d->file) {
      missingRows(*d, kSkullMissing);
      continue;
    }
    const std::filesystem::path path = options.datasetsDir / d->file;
    if (!std::filesystem::exists(path)) {
      missingRows(*d, "not found: " + path.string() + " (use --datasets DIR)");
      continue;
    }
    Volume volume;
    try {
      volume = loadVolume(path.string());
    } catch (const InputError& e) {
      missingRows(*d, std::string("cannot be read: ") + e.what());
      continue;
    }
    char isoNote[256];
    std::snprintf(isoNote, sizeof isoNote, "%s: %s", d->paperName, d->isoReason);
    table.notes.push_back(isoNote);

    // One context and one renderer per dataset; the upload is not timed.
    gl::GlContext context(options.gl);
    Renderer renderer(context);
    renderer.setVolume(volume);
    for (int window : sizes) {
      RenderSettings settings;
      settings.size = {window, window};
      settings.iso = d->iso;
      settings.camera.elevationDeg = kElevationDeg;
      settings.samplesPerVoxel = 1.0;
      std::vector<CaseResult> results =
          runCases(renderer, settings, std::string(d->name) + " " + std::to_string(window) + "²",
                   options, progress);
      for (CaseResult& result : results) checkFrames(result, window);
      checkPlacement(results[0], results[1]);
      checkSameSilhouettes(results[1], results[2]);

      Nk3Line line;
      line.dataset = d->name;
      line.size = dimsLabel(volume.dims);
      line.window = std::to_string(window) + "²";
      line.paper = paperFor(*d, window);
      std::vector<std::string> failed;
      for (std::size_t i = 0; i < results.size(); ++i) {
        CaseResult& r = results[i];
        const Technique t = r.technique;
        std::string check = "ok";
        if (!r.problems.empty()) {
          check = "FAILED: " + r.problems.front();
          for (std::size_t k = 1; k < r.problems.size(); ++k) check += "; " + r.problems[k];
          table.failures.push_back(std::string(d->name) + " " + std::to_string(window) + "² " +
                                   techniqueKey(t) + ": " + check.substr(8));
          failed.push_back(techniqueKey(t));
        }
        line.fps[i] = r.stats.fps();
        nlohmann::json row = {
            {"table", "nk3"},
            {"dataset", d->name},
            {"width", window},
            {"height", window},
            {"technique", techniqueKey(t)},
            {"frames", r.stats.frames},
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
            {"iso", d->iso},
            {"dims", {volume.dims.x, volume.dims.y, volume.dims.z}},
            {"slices", r.sliceCount},
            {"paper_fps",
             line.paper ? nlohmann::json(paperFpsOf(*line.paper, t)) : nlohmann::json(nullptr)},
            {"check", check}};
        if (t == Technique::Bs) {
          row["line_width"] = kBroadenedWidth;
          row["line_pixels_median"] = medianOf(r.frames, &FrameSample::linePixels);
        }
        table.rows.push_back(std::move(row));
      }
      if (failed.empty()) {
        line.check = "ok";
      } else {
        line.check = "FAILED:";
        for (const auto& f : failed) line.check += " " + f;
      }
      lines.push_back(line);
    }
  }
  progress.finish();

  // Printed table and Markdown.
  TextTable text({"dataset", "size", "window", "RA fps", "OPS fps", "BS fps", "RA/OPS", "paper RA",
                  "paper OPS", "paper BS", "paper RA/OPS", "check"});
  table.plot.title = "nk3: frames per second (ours solid, paper hatched)";
  table.plot.valueLabel = "fps";
  table.plot.logScale = true;
  table.plot.series = {{"RA", false, 0},       {"RA paper", true, 0}, {"OPS", false, 1},
                       {"OPS paper", true, 1}, {"BS", false, 2},      {"BS paper", true, 2}};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Nk3Line& l : lines) {
    const auto& p = l.paper;
    text.addRow({l.dataset, l.size, l.window, formatFps(l.fps[0]), formatFps(l.fps[1]),
                 formatFps(l.fps[2]), formatRatio(l.fps[0] / l.fps[1]), p ? formatFps(p->ra) : "–",
                 p ? formatFps(p->ops) : "–", p ? formatFps(p->bs) : "–",
                 p ? formatRatio(p->raOverOps) : "–", l.check});
    table.plot.groups.push_back(l.dataset + " " + l.window);
    auto measured = [&](int i) { return l.fps[i] > 0 ? l.fps[i] : nan; };
    table.plot.values.push_back({measured(0), p ? p->ra : nan, measured(1), p ? p->ops : nan,
                                 measured(2), p ? p->bs : nan});
  }
  table.text = text.plain();
  table.markdown = text.markdown();
  char method[512];
  std::snprintf(method, sizeof method,
                "method: %d warm-up + %d timed frames per technique, RA/OPS/BS taking turns, orbit "
                "from azimuth %.0f° in "
                "steps of %.1f° at elevation %.0f°, 1 slice per voxel, empty-space skipping on for "
                "RA and OPS alike; frame time = "
                "Renderer::render (slicing + glFinish + readback), fps = 1000 / median; "
                "BS adds broadening to W = %.0f px and composition",
                options.warmup, options.frames, kOrbitStartDeg, kOrbitStepDeg, kElevationDeg,
                kBroadenedWidth);
  table.notes.insert(table.notes.begin(), method);
  return table;
}

}  // namespace vsil::bench
