// The semantic table in the illustrate table's steps: what is measured (datasets, the procedural
// rule bases), measuring (the cases of a window take turns frame by frame and check their own
// output), rows and formatting. runSemanticTable at the end calls them in that order.
#include "tables/semantic_table.h"
#include "core/clock.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include <unistd.h>

#include "harness/dataset_choice.h"
#include "harness/format.h"
#include "harness/text_table.h"
#include "harness/timing_stats.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"

namespace vsil::bench {
namespace {

// ---- What is measured -------------------------------------------------------------------------

struct SemanticDataset {
  const char* name;
  const char* file;
  bool byDefault;  // measured without --only
};

const SemanticDataset kDatasets[] = {
    {"bonsai", "bonsai.vti", true},
    {"neghip", "neghip_64x64x64_uint8.nhdr", false},
};

// The procedural rule bases. Rule 0 shows all material (data ≥ 0.12 of the range) in style s0,
// so every base shows the same voxels and empty-space skipping skips the same bricks; rule k ≥ 1
// combines a density band with a gradient band and, from the fourth rule on, the view angle,
// under and/or/not in four forms, no two rules alike (up to 37). A base of n rules has
// min(n, 4) styles (built-in ramps, priorities 0..3) and only the attributes its rules read.
const char* const kDensityValues[] = {"soft", "medium", "hard"};
const char* const kEdgeValues[] = {"flat", "some", "strong"};
const char* const kFacingValues[] = {"front", "edge"};
const char* const kStyleValues[] = {"faint", "medium", "opaque"};
const char* const kRamps[] = {"gray", "ivory", "skin", "red"};
constexpr int kMaxStyles = 4;

int styleCountOf(int rules) {
  return std::min(rules, kMaxStyles);
}

// Rule k of a base with `styles` styles; `valueOffset` moves its consequent's value (the rule
// change).
std::string ruleLine(int k, int styles, int valueOffset = 0) {
  std::string antecedent = "density is material";
  int style = 0, value = 1;
  if (k > 0) {
    const int i = k - 1;
    const std::string d = std::string("density is ") + kDensityValues[(i / 4) % 3];
    const std::string e = std::string("edge is ") + kEdgeValues[(i / 12) % 3];
    const std::string f = std::string("facing is ") + kFacingValues[k % 2];
    switch (i % 4) {
      case 0:
        antecedent = d + " and " + e;
        break;
      case 1:
        antecedent = d + " and not " + e;
        break;
      case 2:
        antecedent = d + " and (" + e + " or " + f + ")";
        break;
      default:
        antecedent = d + " and " + e + " and not " + f;
        break;
    }
    style = k % styles;
    value = (k / styles) % 3;
  }
  return "rule if " + antecedent + " then s" + std::to_string(style) + " is " +
         kStyleValues[(value + valueOffset) % 3];
}

// The text of an n-rule base. `materialEdge` is where the `material` value reaches 1 (the
// membership change moves it); rule 1 + b, for each bit b set in `editedRules`, has its
// consequent's value moved to the next one (the rule change). Line numbers do not depend on
// either (the generated GLSL names them in comments).
std::string ruleBaseText(int rules, double materialEdge = 0.2, unsigned editedRules = 0) {
  const int styles = styleCountOf(rules);
  std::ostringstream text;
  text << "# vsil bench --table semantic: " << rules << " rules, " << styles << " styles\n";
  char material[96];
  std::snprintf(material, sizeof material, "  material = trapezoid(0.12, %.4f, 1, 1)\n",
                materialEdge);
  text << "attribute density from data {\n"
       << material
       << "  soft = trapezoid(0.12, 0.2, 0.35, 0.5)\n"
          "  medium = trapezoid(0.3, 0.45, 0.6, 0.75)\n"
          "  hard = trapezoid(0.55, 0.7, 1, 1)\n"
          "}\n";
  if (rules >= 2) {
    text << "attribute edge from gradient {\n"
            "  flat = trapezoid(0, 0, 0.05, 0.15)\n"
            "  some = triangle(0.05, 0.2, 0.4)\n"
            "  strong = trapezoid(0.25, 0.5, 1, 1)\n"
            "}\n";
  }
  if (rules >= 4) {
    text << "attribute facing from view_angle {\n"
            "  front = trapezoid(0, 0, 0.3, 0.45)\n"
            "  edge = gauss(0.5, 0.08)\n"
            "}\n";
  }
  for (int s = 0; s < styles; ++s) {
    text << "style s" << s << " priority " << s << " { spheres = \"" << kRamps[s]
         << "\"  faint = triangle(0, 0, 0.3)  medium = triangle(0.2, 0.5, 0.8)  opaque = "
            "trapezoid(0.6, 0.9, 1, 1) }\n";
  }
  for (int k = 0; k < rules; ++k) {
    const bool edited = k >= 1 && ((editedRules >> unsigned(k - 1)) & 1u) != 0;
    text << ruleLine(k, styles, edited ? 1 : 0) << "\n";
  }
  return text.str();
}

// The columns: the plain composite, each rule base, and the two changes of the 16-rule base.
struct SemanticCase {
  std::string key;  // JSON "case" and the table
  int rules = 0;    // 0: the plain composite
  enum class Kind { Plain, Base, MembershipChange, RuleChange } kind = Kind::Base;
  double target = 0;  // the largest frame-time ratio to the plain composite allowed (0: none)
};

constexpr int kChangedRules = 16;
constexpr double kTarget16 = 2.0;

const std::vector<SemanticCase>& semanticCases() {
  using Kind = SemanticCase::Kind;
  static const std::vector<SemanticCase> cases = {
      {"plain", 0, Kind::Plain, 0},
      {"rules_1", 1, Kind::Base, 0},
      {"rules_4", 4, Kind::Base, 0},
      {"rules_32", 32, Kind::Base, 0},
      // The 16-rule base just before its two changes: each change is measured against the
      // frame before it.
      {"rules_16", 16, Kind::Base, kTarget16},
      {"membership_change", kChangedRules, Kind::MembershipChange, 0},
      {"rule_change", kChangedRules, Kind::RuleChange, 0},
  };
  return cases;
}
constexpr std::size_t kPlain = 0;
constexpr std::size_t kUnchanged = 4;  // rules_16, rendered just before the changes

// The order the rows are printed in: by rule count, then the changes.
const std::size_t kRowOrder[] = {0, 1, 2, 4, 3, 5, 6};

// The same orbit as nk3 and illustrate: timed frame i from azimuth 30° + 3.6°·i at elevation 20°.
constexpr double kOrbitStartDeg = 30.0;
constexpr double kOrbitStepDeg = 3.6;
constexpr double kElevationDeg = 20.0;

// Frame k's text of a case's rule file (all the 16-rule cases share one file, as an editor
// would: the generated GLSL names the file, so another file would be another program).
// Membership change k: `material` reaches 1 a little earlier each time (a new membership row,
// the same code). Rule change k: the rules given by the bits of k + 1 get the next consequent
// value: rule 1, then rule 2, then both, then rule 3, … (new code every frame, for 2^15 − 1
// frames; after that earlier programs would come back from the cache and the self-check say so).
std::string caseRuleText(const SemanticCase& c, int k) {
  switch (c.kind) {
    case SemanticCase::Kind::MembershipChange:
      return ruleBaseText(c.rules, 0.2 - 0.002 * (1 + k % 30));
    case SemanticCase::Kind::RuleChange:
      return ruleBaseText(c.rules, 0.2, 1u + unsigned(k) % ((1u << unsigned(c.rules - 1)) - 1u));
    default:
      return ruleBaseText(c.rules);
  }
}

// ---- Choosing ---------------------------------------------------------------------------------

using Choice = DatasetChoice<SemanticDataset>;

// ---- Measuring --------------------------------------------------------------------------------

struct CaseResult {
  const SemanticCase* column = nullptr;
  std::vector<double> ms;
  std::vector<double> cpuMs;    // the process's CPU time over the frame (all of llvmpipe's threads)
  std::vector<double> extraMs;  // the changes: ms − the unchanged 16-rule frame's of the same view
  std::vector<double> buildMs;  // timed frames: ProgramCache::get (compiling when it builds)
  int programsBuilt = 0;        // timed frames that compiled a program
  TimingStats stats;
  double coveredMean = 0;
  int sliceCount = 0;
  std::vector<std::string> problems;
};

struct Measured {
  const SemanticDataset& dataset;
  std::string missing;
  glm::ivec3 dims{0};
  double firstMs = 0;  // the untimed first frames: gradient texture, every case's program
  struct Window {
    int size = 0;
    std::vector<CaseResult> cases;
  };
  std::vector<Window> windows;
  std::string glBackend;  // the back end its frames ran on ("osmesa", "egl"): the JSON rows say it
};

// CPU time of the whole process (every llvmpipe thread): steadier than wall time on a loaded
// machine, since it counts work, not waiting.
double processCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << text;
  if (!file.flush()) throw std::runtime_error("cannot write " + path.string());
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

class CaseRenderer {
 public:
  CaseRenderer(Renderer& renderer, std::filesystem::path dir) : renderer_(renderer), dir_(dir) {}
  CaseRenderer(const CaseRenderer&) = delete;
  CaseRenderer& operator=(const CaseRenderer&) = delete;
  ~CaseRenderer() {
    std::error_code ignored;
    for (const auto& path : written_) std::filesystem::remove(path, ignored);
  }

  // Writes the case's rule file for frame k (not timed), then renders it.
  RenderResult render(const SemanticCase& c, int k, int window, double azimuthDeg,
                      double* ms = nullptr, double* cpuMs = nullptr) {
    RenderSettings settings;
    settings.size = {window, window};
    settings.camera.azimuthDeg = azimuthDeg;
    settings.camera.elevationDeg = kElevationDeg;
    settings.samplesPerVoxel = 1.0;
    if (c.kind == SemanticCase::Kind::Plain) {
      settings.technique = "illustrate";
      settings.options["effects"] = std::string("none");
    } else {
      const std::filesystem::path path = rulesPath(c.rules);
      writeText(path, caseRuleText(c, k));
      settings.technique = "semantic";
      settings.options["rules"] = path.string();
    }
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = processCpuMs();
    RenderResult frame = renderer_.render(settings);
    if (ms) *ms = millisecondsSince(start);
    if (cpuMs) *cpuMs = processCpuMs() - cpuStart;
    return frame;
  }

 private:
  std::filesystem::path rulesPath(int rules) {
    const std::filesystem::path path = dir_ / ("vsil-bench-semantic-" + std::to_string(::getpid()) +
                                               "-" + std::to_string(rules) + ".rules");
    if (std::find(written_.begin(), written_.end(), path) == written_.end())
      written_.push_back(path);
    return path;
  }

  Renderer& renderer_;
  std::filesystem::path dir_;
  std::vector<std::filesystem::path> written_;
};

void checkFrame(const SemanticCase& c, const RenderResult& frame, int window,
                const std::string& label, bool timed, CaseResult& result) {
  const cv::Mat4f& color = frame.frame.color;
  if (color.cols != window || color.rows != window) {
    result.problems.push_back(label + ": the frame is " + std::to_string(color.cols) + "x" +
                              std::to_string(color.rows));
    return;
  }
  if (const std::string problem = colorProblem(color); !problem.empty()) {
    result.problems.push_back(label + ": " + problem);
  }
  int covered = 0;
  for (auto it = color.begin(); it != color.end(); ++it) covered += (*it)[3] > 0.0f;
  if (covered < window * window / 100) {
    result.problems.push_back(label + " shows only " + std::to_string(covered) + " pixels");
  }
  if (timed) result.coveredMean += covered;
  if (c.kind == SemanticCase::Kind::Plain) return;
  const nlohmann::json& details = frame.options["semantic"];
  if (!details.contains("program_compiled")) {
    result.problems.push_back(label + ": no \"program_compiled\" in the technique's details");
    return;
  }
  const bool compiled = details["program_compiled"].get<bool>();
  if (timed) {
    result.programsBuilt += compiled;
    result.buildMs.push_back(details.value("program_build_ms", 0.0));
  }
  // Every base's program is built before the timed frames; a membership change builds none, a
  // rule change one.
  const bool expected = c.kind == SemanticCase::Kind::RuleChange;
  if (compiled != expected) {
    result.problems.push_back(label + (compiled ? " compiled a program" : " compiled no program"));
  }
}

std::vector<CaseResult> measureWindow(CaseRenderer& renderer, const SemanticDataset& d, int window,
                                      const BenchOptions& options, Progress& progress) {
  const auto& columns = semanticCases();
  std::vector<CaseResult> results(columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) results[c].column = &columns[c];
  progress.startCase(std::string(d.name) + " " + std::to_string(window) + "²");
  const int total = options.warmup + options.frames;
  // The cases take turns frame by frame, so that load from other processes falls on all alike;
  // each change follows the unchanged 16-rule frame of the same view.
  for (int k = 0; k < total; ++k) {
    const bool warm = k < options.warmup;
    const int timedIndex = k - options.warmup;
    const double azimuth = kOrbitStartDeg + kOrbitStepDeg * std::max(timedIndex, 0);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string label =
          (warm ? "warm-up " : "frame ") + std::to_string((warm ? k : timedIndex) + 1);
      progress.step(columns[c].key + " " + label);
      double ms = 0, cpuMs = 0;
      const RenderResult frame = renderer.render(columns[c], k, window, azimuth, &ms, &cpuMs);
      results[c].sliceCount = frame.sliceCount;
      checkFrame(columns[c], frame, window, label, !warm, results[c]);
      if (warm) continue;
      results[c].ms.push_back(ms);
      results[c].cpuMs.push_back(cpuMs);
      if (columns[c].kind == SemanticCase::Kind::MembershipChange ||
          columns[c].kind == SemanticCase::Kind::RuleChange) {
        results[c].extraMs.push_back(ms - results[kUnchanged].ms.back());
      }
    }
  }
  for (CaseResult& r : results) {
    r.stats = summarize(r.ms);
    if (!r.ms.empty()) r.coveredMean /= double(r.ms.size());
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
  gl::GlContext context(options.gl);
  measured.glBackend = gl::backendName(context.info().backend);
  Renderer renderer(context);
  renderer.setVolume(*volume);
  CaseRenderer cases(renderer, std::filesystem::temp_directory_path());
  {
    // Not timed: the gradient texture (the first frame that shades) and each base's program,
    // so that no timed frame but a rule change's compiles anything, even with --warmup 0.
    const auto start = std::chrono::steady_clock::now();
    for (const SemanticCase& c : semanticCases()) {
      if (c.kind == SemanticCase::Kind::Plain || c.kind == SemanticCase::Kind::Base) {
        cases.render(c, 0, 16, kOrbitStartDeg);
      }
    }
    measured.firstMs = millisecondsSince(start);
  }
  for (auto& window : measured.windows) {
    window.cases = measureWindow(cases, chosen.dataset, window.size, options, progress);
  }
  return measured;
}

// ---- Rows -------------------------------------------------------------------------------------

// The frame-time ratio to the plain composite (in CPU time too); for the changes also to the
// unchanged 16-rule frame before them. From paired frames (pairedRatio).
struct Verdict {
  double ratio = std::numeric_limits<double>::quiet_NaN();
  double cpuRatio = std::numeric_limits<double>::quiet_NaN();
  double ratioTo16 = std::numeric_limits<double>::quiet_NaN();
  bool met = true;
};

Verdict verdictOf(const std::vector<CaseResult>& cases, std::size_t c) {
  Verdict v;
  const SemanticCase& column = *cases[c].column;
  if (c != kPlain) {
    v.ratio = pairedRatio(cases[c].ms, cases[kPlain].ms);
    v.cpuRatio = pairedRatio(cases[c].cpuMs, cases[kPlain].cpuMs);
  }
  if (column.kind == SemanticCase::Kind::MembershipChange ||
      column.kind == SemanticCase::Kind::RuleChange) {
    v.ratioTo16 = pairedRatio(cases[c].ms, cases[kUnchanged].ms);
  }
  v.met = !(column.target > 0) || !std::isfinite(v.ratio) || v.ratio <= column.target;
  return v;
}

nlohmann::json finiteOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

nlohmann::json jsonRow(const Measured& m, int window, const std::vector<CaseResult>& cases,
                       std::size_t c, const BenchOptions& options) {
  const CaseResult& r = cases[c];
  const Verdict v = verdictOf(cases, c);
  const SemanticCase& column = *r.column;
  const bool plain = column.kind == SemanticCase::Kind::Plain;
  nlohmann::json row = {
      {"table", "semantic"},
      {"dataset", m.dataset.name},
      {"width", window},
      {"height", window},
      {"case", column.key},
      {"technique", plain ? "illustrate" : "semantic"},
      {"rules", column.rules},
      {"styles", plain ? 0 : styleCountOf(column.rules)},
      {"frames", r.stats.frames},
      {"warmup", options.warmup},
      {"ms_median", r.stats.msMedian},
      {"ms_min", r.stats.msMin},
      {"ms_max", r.stats.msMax},
      {"fps", r.stats.fps()},
      {"cpu_ms_median", median(r.cpuMs)},
      {"ms", r.ms},
      {"cpu_ms", r.cpuMs},
      {"cpu_ratio", finiteOrNull(v.cpuRatio)},
      {"plain_fps", cases[kPlain].stats.fps()},
      {"ratio", finiteOrNull(v.ratio)},
      {"ratio_to", plain ? "" : "plain"},
      {"target", column.target > 0 ? nlohmann::json(column.target) : nlohmann::json()},
      {"target_met", v.met},
      {"covered_pixels_mean", r.coveredMean},
      {"slices", r.sliceCount},
      {"dims", {m.dims.x, m.dims.y, m.dims.z}},
      {"gl_backend", m.glBackend},
      {"first_frames_ms", m.firstMs},
      {"check", checkText(r.problems)}};
  if (!plain) {
    row["programs_compiled"] = r.programsBuilt;
    row["program_build_ms_median"] = median(r.buildMs);
  }
  if (column.kind == SemanticCase::Kind::MembershipChange ||
      column.kind == SemanticCase::Kind::RuleChange) {
    row["ratio_to_rules_16"] = finiteOrNull(v.ratioTo16);
    row["extra_ms_median"] = median(r.extraMs);
  }
  return row;
}

nlohmann::json missingRow(const Measured& m, int window, const SemanticCase& c) {
  return {
      {"table", "semantic"}, {"dataset", m.dataset.name}, {"width", window}, {"height", window},
      {"case", c.key},       {"rules", c.rules},          {"frames", 0},     {"ms_median", nullptr},
      {"fps", nullptr},      {"missing", m.missing},      {"check", nullptr}};
}

std::string formatMs(double ms) {
  if (!(ms > 0) || !std::isfinite(ms)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, ms >= 100 ? "%.0f" : "%.1f", ms);
  return text;
}

// "+312", "−14": the changes' extra milliseconds over the unchanged frame.
std::string formatSignedMs(double ms) {
  if (!std::isfinite(ms)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, "%.0f", std::abs(ms));
  return (ms < 0 ? "−" : "+") + std::string(text);
}

}  // namespace

std::optional<std::string> semanticDatasetFile(const std::string& name) {
  return datasetFileOf(kDatasets, name);
}

std::vector<std::string> semanticDatasetNames() {
  std::vector<std::string> names;
  for (const auto& d : kDatasets) names.push_back(d.name);
  return names;
}

TableResult runSemanticTable(const BenchOptions& options, Progress& progress) {
  const std::vector<int> sizes = options.sizes.empty() ? std::vector<int>{512} : options.sizes;
  const std::vector<Choice> chosen =
      chooseDatasets(std::span<const SemanticDataset>(kDatasets), options);
  int cases = 0;
  for (const auto& c : chosen) cases += c.missing.empty() ? int(sizes.size()) : 0;
  progress.setTotalCases(cases);
  std::vector<Measured> measured;
  for (const Choice& c : chosen) measured.push_back(measureDataset(c, sizes, options, progress));
  progress.finish();

  TableResult table;
  table.name = "semantic";
  table.title =
      "Rautek et al. semantic rendering: fps of rule bases of 1, 4, 16 and 32 rules against the "
      "plain composite, and the frame after a membership change against one after a rule change";
  TextTable text({"dataset", "size", "window", "case", "rules", "fps", "ms", "ratio", "target",
                  "cpu ms", "cpu ratio", "×16 rules", "+ms", "compiled", "build ms", "check"});
  const auto& columns = semanticCases();
  PlotSpec plot;
  plot.title = "semantic: frames per second";
  plot.valueLabel = "fps";
  plot.logScale = false;
  for (std::size_t c : kRowOrder) plot.series.push_back({columns[c].key, false, int(c)});
  for (const Measured& m : measured) {
    for (const auto& window : m.windows) {
      if (!m.missing.empty()) {
        for (std::size_t c : kRowOrder) {
          table.rows.push_back(missingRow(m, window.size, columns[c]));
        }
        continue;
      }
      std::vector<double> fps;
      for (std::size_t c : kRowOrder) {
        const CaseResult& r = window.cases[c];
        const SemanticCase& column = *r.column;
        const bool plain = column.kind == SemanticCase::Kind::Plain;
        table.rows.push_back(jsonRow(m, window.size, window.cases, c, options));
        const Verdict v = verdictOf(window.cases, c);
        std::string check = r.problems.empty() ? "ok" : "FAILED";
        if (!v.met) check += " (over target)";
        text.addRow(
            {m.dataset.name, dimsLabel(m.dims), std::to_string(window.size) + "²", column.key,
             plain ? "–" : std::to_string(column.rules), formatFps(r.stats.fps()),
             formatMs(r.stats.msMedian), plain ? "–" : formatRatio(v.ratio),
             column.target > 0 ? "≤ " + formatRatio(column.target) : "–", formatMs(median(r.cpuMs)),
             plain ? "–" : formatRatio(v.cpuRatio),
             std::isfinite(v.ratioTo16) ? formatRatio(v.ratioTo16) : "–",
             r.extraMs.empty() ? "–" : formatSignedMs(median(r.extraMs)),
             plain ? "–" : std::to_string(r.programsBuilt) + "/" + std::to_string(r.stats.frames),
             plain ? "–" : formatMs(median(r.buildMs)), check});
        fps.push_back(r.stats.fps() > 0 ? r.stats.fps() : std::nan(""));
        if (!r.problems.empty()) {
          table.failures.push_back(std::string(m.dataset.name) + " " + std::to_string(window.size) +
                                   "² " + column.key + ": " + joinedProblems(r.problems));
        }
      }
      char covered[256];
      std::snprintf(
          covered, sizeof covered,
          "%s %d²: the plain composite covers %.0f pixels on average, the rule bases %.0f "
          "(they leave data below 0.12 of the value range empty, the composite's power "
          "opacity does not)",
          m.dataset.name, window.size, window.cases[kPlain].coveredMean,
          window.cases[kUnchanged].coveredMean);
      table.notes.push_back(covered);
      plot.groups.push_back(std::string(m.dataset.name) + " " + std::to_string(window.size) + "²");
      plot.values.push_back(fps);
    }
    char note[256];
    if (m.missing.empty()) {
      std::snprintf(note, sizeof note,
                    "%s: the untimed first frames (gradient texture, each rule base's program, "
                    "at 16²) took %.0f ms",
                    m.dataset.name, m.firstMs);
    } else {
      std::snprintf(note, sizeof note, "%s: %s", m.dataset.name, m.missing.c_str());
    }
    table.notes.push_back(note);
  }
  char method[2048];
  std::snprintf(
      method, sizeof method,
      "method: %d warm-up + %d timed frames per case, the cases taking turns frame by frame, "
      "orbit from azimuth %.0f° in steps of %.1f° at elevation %.0f°, 1 slice per voxel; plain = "
      "illustrate --effects none (the dv1 table's DVR); rules_N = semantic with a procedural base "
      "of N rules (rule 0: all material in style s0; the others: density band and gradient band "
      "and, from the 4th, view angle, under and/or/not), min(N, 4) styles with built-in ramps; "
      "membership_change = the 16-rule base with one membership function moved (new table rows, "
      "no program compiled), rule_change = rules' consequents changed (rule 1, then rule 2, then "
      "both, …: one program compiled every frame), "
      "both right after the unchanged 16-rule frame of the same view, in that order; frame time = "
      "Renderer::render (reading the rule file, compiling the rules, uploading tables, building "
      "the program when new, slicing, glFinish, readback), fps = 1000 / median; ratio = the "
      "median over frames of the frame's time / the plain composite's in the same turn; cpu ms = "
      "the process's CPU time over the frame (every "
      "llvmpipe "
      "thread; steadier than wall time under load), cpu ratio = the same over the plain "
      "composite's; ×16 rules = the same ratio to the unchanged 16-rule frame's, +ms = the median "
      "of "
      "frame time − that of the unchanged 16-rule frame of the same view; "
      "build ms = ProgramCache::get per frame (compile + link when it builds; llvmpipe "
      "compiles the shader's machine code at its first draw, inside the frame, not in build ms); "
      "target: rules_16 "
      "≤ %.0f × plain",
      options.warmup, options.frames, kOrbitStartDeg, kOrbitStepDeg, kElevationDeg, kTarget16);
  table.notes.insert(table.notes.begin(), method);
  table.text = text.plain();
  table.markdown = text.markdown();
  table.plot = plot;
  return table;
}

}  // namespace vsil::bench
