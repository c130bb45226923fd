// The scaling table: per technique and rank count, mpirun children writing --meta-out; the
// slowest rank's frame, the reduction's share and the per-rank memory from its "mpi" object.
#include "tables/scaling_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <variant>

#include <nlohmann/json.hpp>

#include "harness/child_run.h"
#include "harness/scratch_folder.h"
#include "harness/text_table.h"

#ifndef VSIL_MPIEXEC
#define VSIL_MPIEXEC ""
#endif

namespace vsil::bench {
namespace {

namespace fs = std::filesystem;

constexpr const char* kVolume = "gen:spheres:256";
// The limit each rank runs under: 90 % of what one process needs for the technique (what
// --max-memory counts: 156 MiB for mip, whose limit is then 140; the larger slab of two needs
// 125), read from the single process's refusal under --max-memory 1.
constexpr double kLimitShare = 0.9;
// Two ranks split 256³ into bricks of 256·256·128 R16F texels (16 MiB; the split halves the
// bricks along z until every rank has a layer): a single process with this limit draws the
// same bricks, which separates the cost of bricking from that of the split.
constexpr int kBrickedTextureMiB = 16;
constexpr int kDefaultSize = 256;
constexpr int kDefaultRuns = 3;
const std::vector<std::string> kTechniques = {"silhouette", "rightangle", "firsthit", "illustrate",
                                              "mip",        "demip",      "lmip",     "semantic"};
// mpirun as root needs both; --oversubscribe lets 4 ranks run on 2 cores.
const std::vector<std::string> kRootEnvironment = {"OMPI_ALLOW_RUN_AS_ROOT=1",
                                                   "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"};

struct ScalingCase {
  std::string technique;
  int ranks = 1;
  bool limited = true;  // under --max-memory maxMemoryMiB
  int maxMemoryMiB = 0;
  bool bricked = false;  // N = 1 cut into the bricks two ranks use (--max-texture-mib)
  std::vector<double> frameMs, frameCpuMs, reduceMs, wallSeconds;
  double heldBytes = 0, peakBytes = 0;  // the largest rank's
  std::string problem;                  // empty: rendered
  std::string refusal;                  // N = 1 under the limit: the expected refusal
  double medianFrame() const { return median(frameMs); }
  double medianReduce() const { return median(reduceMs); }
  static double median(std::vector<double> values) {
    if (values.empty()) return std::nan("");
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
  }
};

std::string fixed(double value, int digits) {
  if (!std::isfinite(value)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

std::string firstLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

// One run: `vsil render` (N = 1) or `mpirun --oversubscribe -np N vsil render`; the frame and
// combine times, the memory. Returns the problem, empty when it rendered.
std::string runOnce(ScalingCase& c, int size, const gl::ContextOptions& gl, const fs::path& dir,
                    const fs::path& reference) {
  const fs::path png = dir / "frame.png", meta = dir / "meta.json", err = dir / "stderr";
  fs::remove(png);
  fs::remove(meta);
  const std::string sizeText = std::to_string(size) + "x" + std::to_string(size);
  std::vector<std::string> render = {"render", kVolume, "--technique", c.technique,  "--size",
                                     sizeText, "--out", png.string(),  "--meta-out", meta.string()};
  if (c.limited) render.insert(render.end(), {"--max-memory", std::to_string(c.maxMemoryMiB)});
  if (c.bricked) {
    render.insert(render.end(), {"--max-texture-mib", std::to_string(kBrickedTextureMiB)});
  }
  const std::vector<std::string> glChoice = glArguments(gl);
  render.insert(render.end(), glChoice.begin(), glChoice.end());
  ChildRun run;
  if (c.ranks == 1) {
    run = runVsilChild(render, err);
  } else {
    if (std::string(VSIL_MPIEXEC).empty()) return "this vsil was built without MPI";
    std::vector<std::string> args = {"--oversubscribe", "-np", std::to_string(c.ranks),
                                     vsilBinary()};
    args.insert(args.end(), render.begin(), render.end());
    run = runChild(VSIL_MPIEXEC, args, err, kRootEnvironment);
  }
  if (run.exitCode != 0) {
    if (c.ranks == 1 && c.limited) {
      c.refusal = firstLine(err);
      return c.refusal.find("--max-memory") != std::string::npos ? "" : "N = 1: " + run.error;
    }
    return run.error;
  }
  if (c.ranks == 1 && c.limited) return "one process met --max-memory: the table needs it not to";
  try {
    const nlohmann::json document = nlohmann::json::parse(std::ifstream(meta));
    if (c.ranks == 1) {
      // The iso default's histogram (timings_ms.defaults) is left out: the ranks agree on it
      // while reading, before the frame.
      double wall = 0, cpu = 0;
      for (const char* stage : {"render", "readback", "postfx"}) {
        wall += document.at("timings_ms").value(stage, 0.0);
        cpu += document.at("cpu_ms").value(stage, 0.0);
      }
      c.frameMs.push_back(wall);
      c.frameCpuMs.push_back(cpu);
      c.reduceMs.push_back(0.0);
      c.peakBytes = std::max(c.peakBytes, run.peakResidentBytes);
    } else {
      double frame = 0, frameCpu = 0, reduce = 0;
      const nlohmann::json& ranks = document.at("mpi").at("per_rank");
      if (int(ranks.size()) != c.ranks) throw std::runtime_error("per_rank has the wrong size");
      for (const nlohmann::json& r : ranks) {
        frame = std::max(frame, r.at("frame_ms").get<double>());
        frameCpu = std::max(frameCpu, r.at("frame_cpu_ms").get<double>());
        reduce = std::max(reduce, r.at("reduce_ms").get<double>());
        c.heldBytes = std::max(c.heldBytes, r.at("held_bytes").get<double>());
        c.peakBytes = std::max(c.peakBytes, r.at("peak_rss_bytes").get<double>());
      }
      c.frameMs.push_back(frame);
      c.frameCpuMs.push_back(frameCpu);
      c.reduceMs.push_back(reduce);
    }
  } catch (const std::exception& e) {
    return std::string("--meta-out: ") + e.what();
  }
  c.wallSeconds.push_back(run.seconds);
  if (c.ranks == 1) {
    fs::copy_file(png, reference, fs::copy_options::overwrite_existing);
  } else if (fs::exists(reference)) {
    auto bytes = [](const fs::path& p) {
      std::ifstream in(p, std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    if (bytes(png) != bytes(reference)) return "the PNG differs from the single process's";
  }
  return "";
}

// What one process needs for `technique`, from its refusal ("gen:spheres:256: rendering
// 256x256x256 float32 samples at --size 256x256 needs 156 MiB, over the --max-memory limit
// ..."), or what went wrong. The frame's images are checked first ("--size 256x256 needs 10
// MiB"): the probe's limit rises past them.
std::variant<int, std::string> singleProcessMiB(const std::string& technique, int size,
                                                const gl::ContextOptions& gl, const fs::path& dir) {
  int probe = 1;
  std::string line;
  for (int attempt = 0; attempt < 3; ++attempt) {
    std::vector<std::string> args = {
        "render",       kVolume,
        "--technique",  technique,
        "--size",       std::to_string(size) + "x" + std::to_string(size),
        "--out",        (dir / "probe.png").string(),
        "--max-memory", std::to_string(probe)};
    const std::vector<std::string> glChoice = glArguments(gl);
    args.insert(args.end(), glChoice.begin(), glChoice.end());
    runVsilChild(args, dir / "probe.err");
    line = firstLine(dir / "probe.err");
    const std::size_t at = line.find(" needs ");
    if (at == std::string::npos) break;
    int need = 0;
    try {
      need = std::stoi(line.substr(at + 7));
    } catch (const std::exception&) {
      break;
    }
    if (line.find(" samples at ") != std::string::npos) return need;
    probe = need + 1;
  }
  return "no --max-memory refusal to read the volume's need from: " + line;
}

ScalingCase measureCase(const std::string& technique, int ranks, bool limited, bool bricked,
                        int maxMemoryMiB, int size, int runs, const gl::ContextOptions& gl,
                        const fs::path& dir, Progress& progress) {
  ScalingCase c;
  c.technique = technique;
  c.ranks = ranks;
  c.limited = limited;
  c.maxMemoryMiB = maxMemoryMiB;
  c.bricked = bricked;
  progress.startCase(technique + " N=" + std::to_string(ranks) + (limited ? "" : " (no limit)") +
                     (bricked ? " bricked" : ""));
  const fs::path reference =
      dir / (technique + (bricked ? ".bricked" : ".reference") + std::string(".png"));
  // A refused run is refused alike every time: once is enough.
  const int count = ranks == 1 && limited ? 1 : runs;
  for (int i = 0; i < count && c.problem.empty(); ++i) {
    progress.step("run " + std::to_string(i + 1) + "/" + std::to_string(count));
    c.problem = runOnce(c, size, gl, dir, reference);
  }
  return c;
}

}  // namespace

std::vector<std::string> scalingTechniqueNames() {
  return kTechniques;
}

TableResult runScalingTable(const BenchOptions& options, Progress& progress) {
  const std::vector<std::string> techniques =
      options.only.empty() ? std::vector<std::string>{"mip"} : options.only;
  const int size = options.sizes.empty() ? kDefaultSize : options.sizes.front();
  const int runs = options.frames == 10 ? kDefaultRuns : std::max(1, options.frames);
  const ScratchFolder scratch("scaling");

  TableResult table;
  table.name = "scaling";
  table.title = "slab-parallel render across MPI ranks: frame, reduction share, memory per rank";
  progress.setTotalCases(int(techniques.size()) * 6);
  std::vector<ScalingCase> cases;
  for (const std::string& technique : techniques) {
    // The single process without the limit first: the reference bytes and the speed-up's base.
    const auto need = singleProcessMiB(technique, size, options.gl, scratch.path());
    if (const auto* problem = std::get_if<std::string>(&need)) {
      table.failures.push_back(technique + ": " + *problem);
      continue;
    }
    const int limit = int(kLimitShare * std::get<int>(need));
    cases.push_back(measureCase(technique, 1, false, false, limit, size, runs, options.gl,
                                scratch.path(), progress));
    cases.push_back(measureCase(technique, 1, false, true, limit, size, runs, options.gl,
                                scratch.path(), progress));
    for (int ranks = 1; ranks <= 4; ++ranks) {
      cases.push_back(measureCase(technique, ranks, true, false, limit, size, runs, options.gl,
                                  scratch.path(), progress));
    }
  }
  progress.finish();

  TextTable text({"technique", "ranks", "--max-memory", "frame ms", "speed-up", "frame CPU ms",
                  "CPU vs 1", "reduce ms", "reduce share", "held MiB/rank", "peak RSS MiB/rank",
                  "mpirun s", "check"});
  table.plot.title = "scaling: " + std::string(kVolume) + ", frame (ms) against ranks";
  table.plot.valueLabel = "ms (median)";
  table.plot.logScale = false;
  table.plot.series = {{"frame"}, {"of it: reduce"}, {"frame CPU (busiest rank)"}};
  const double mib = double(1 << 20);
  for (const ScalingCase& c : cases) {
    double base = std::nan(""), baseCpu = std::nan("");
    for (const ScalingCase& b : cases) {
      if (b.technique == c.technique && b.ranks == 1 && !b.limited && !b.bricked) {
        base = b.medianFrame();
        baseCpu = ScalingCase::median(b.frameCpuMs);
      }
    }
    const bool rendered = c.problem.empty() && !c.frameMs.empty();
    const double frame = rendered ? c.medianFrame() : std::nan("");
    const double frameCpu = rendered ? ScalingCase::median(c.frameCpuMs) : std::nan("");
    const double reduce = rendered ? c.medianReduce() : std::nan("");
    const double share = rendered && frame > 0 ? reduce / frame : std::nan("");
    const std::string limit = c.limited   ? std::to_string(c.maxMemoryMiB) + " MiB"
                              : c.bricked ? "none, bricked"
                                          : "none";
    std::string check = c.problem.empty() ? "ok" : "FAILED: " + c.problem;
    if (c.problem.empty() && !c.refusal.empty()) check = "refused: over --max-memory";
    nlohmann::json row = {
        {"table", "scaling"},
        {"volume", kVolume},
        {"technique", c.technique},
        {"ranks", c.ranks},
        {"max_memory_mib", c.limited ? nlohmann::json(c.maxMemoryMiB) : nullptr},
        {"max_texture_mib", c.bricked ? nlohmann::json(kBrickedTextureMiB) : nullptr},
        {"width", size},
        {"height", size},
        {"runs", c.frameMs.size()},
        {"frame_ms", rendered ? nlohmann::json(frame) : nullptr},
        {"frame_ms_runs", c.frameMs},
        {"speedup", rendered ? nlohmann::json(base / frame) : nullptr},
        {"frame_cpu_ms", rendered ? nlohmann::json(frameCpu) : nullptr},
        {"frame_cpu_ms_runs", c.frameCpuMs},
        {"cpu_speedup", rendered ? nlohmann::json(baseCpu / frameCpu) : nullptr},
        {"reduce_ms", rendered ? nlohmann::json(reduce) : nullptr},
        {"reduce_share", rendered ? nlohmann::json(share) : nullptr},
        {"held_bytes_max_rank", c.ranks > 1 ? nlohmann::json(c.heldBytes) : nullptr},
        {"peak_rss_bytes_max_rank", rendered ? nlohmann::json(c.peakBytes) : nullptr},
        {"wall_s_runs", c.wallSeconds},
        {"check", check}};
    if (!c.refusal.empty()) row["refusal"] = c.refusal;
    table.rows.push_back(row);
    if (!c.problem.empty()) {
      table.failures.push_back(c.technique + " N=" + std::to_string(c.ranks) + ": " + c.problem);
    }
    text.addRow({c.technique, std::to_string(c.ranks), limit, fixed(frame, 0),
                 rendered ? fixed(base / frame, 2) + "x" : "–", fixed(frameCpu, 0),
                 rendered ? fixed(baseCpu / frameCpu, 2) + "x" : "–", fixed(reduce, 1),
                 rendered ? fixed(100.0 * share, 1) + " %" : "–",
                 c.ranks > 1 && rendered ? fixed(c.heldBytes / mib, 0) : "–",
                 rendered ? fixed(c.peakBytes / mib, 0) : "–",
                 c.wallSeconds.empty() ? "–" : fixed(ScalingCase::median(c.wallSeconds), 1),
                 check});
    table.plot.groups.push_back(c.technique + " N=" + std::to_string(c.ranks) +
                                (c.bricked            ? " bricked"
                                 : !c.limited         ? " no limit"
                                 : !c.refusal.empty() ? " refused"
                                                      : ""));
    table.plot.values.push_back({frame, reduce, frameCpu});
  }
  table.notes.push_back(
      std::string(kVolume) + " (256³ float), --size " + std::to_string(size) + "x" +
      std::to_string(size) +
      "; N = 1 is `vsil render`, N >= 2 `mpirun --oversubscribe -np N "
      "vsil render`, " +
      std::to_string(runs) +
      " runs each (one frame per process), medians. "
      "frame ms: the slowest rank's RenderJob::render less program builds (--meta-out "
      "mpi.per_rank[].frame_ms; N = 1: timings_ms render + readback + postfx); frame CPU ms: the "
      "same in the busiest rank's process CPU time (mpi.per_rank[].frame_cpu_ms; N = 1: cpu_ms), "
      "which a loaded machine disturbs less, and its ratio to one process's; "
      "reduce ms: the slowest rank's combining (mpi.per_rank[].reduce_ms: Technique::combineSlabs "
      "and the relay's calls, incl. waiting for the other ranks); held: the largest slab's samples "
      "+ volume textures; peak RSS: getrusage per rank (N = 1: wait4 of the process)");
  table.notes.push_back(
      "ranks share this machine's cores (oversubscribed where N exceeds them): the ratios "
      "matter, not the absolute times. The split bricks the volume along z (one brick layer per "
      "rank at least), and a bricked frame costs more on llvmpipe than one texture (each slice "
      "draws a piece per brick): N = 1 renders 256³ as one texture, N = 1 bricked in the bricks of "
      "two ranks (--max-texture-mib " +
      std::to_string(kBrickedTextureMiB) + ")");
  table.text = text.plain();
  table.markdown = text.markdown();
  return table;
}

}  // namespace vsil::bench
