// vsil animate: a sequence of frames from one render job — one GL context, one renderer, one
// volume upload, the FFT plans kept — as numbered PNGs with a JSON of every frame, and/or a
// video. What changes from frame to frame is job/animation.h's AnimationPlan; this file reads
// flags, runs the frames and writes the files.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli/cli_parse.h"
#include "cli/cli_progress.h"
#include "cli/cli_render_options.h"
#include "cli/cli_report.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/image_file.h"
#include "core/json_input.h"
#include "core/limits.h"
#include "core/number_pair.h"
#include "core/options.h"
#include "core/progress_line.h"
#include "core/version.h"
#include "job/animation.h"
#include "video/video_file.h"

namespace vsil::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct AnimateFlags {
  long long frames = 0;
  double orbit = 0;
  std::string viewFrom, viewTo;
  std::vector<std::string> sweeps;
  std::string outDir, video;
  double fps = 25;
  bool quiet = false;
};

AnimationSpec animationSpec(const AnimateFlags& flags) {
  AnimationSpec spec;
  spec.frames = flags.frames;
  spec.orbitDeg = flags.orbit;
  if (!flags.viewFrom.empty()) spec.viewFrom = parseNumberPair("--view-from", flags.viewFrom);
  if (!flags.viewTo.empty()) spec.viewTo = parseNumberPair("--view-to", flags.viewTo);
  for (const auto& text : flags.sweeps) spec.sweeps.push_back(parseSweep(text));
  return spec;
}

// The checks of the outputs that create nothing (validate-only mode stops after them).
void checkOutputs(const AnimateFlags& flags, glm::ivec2 size) {
  if (flags.outDir.empty() && flags.video.empty()) {
    throw InputError("animate: nothing to write (give --out-dir DIR and/or --video FILE)");
  }
  if (!flags.outDir.empty()) refuseOutputFolder("--out-dir " + flags.outDir, flags.outDir);
  if (flags.video.empty() && !VideoFile::validFps(flags.fps)) {
    throwInputError("--fps " + formatNumber(flags.fps),
                    std::string("must be in ") + VideoFile::kFpsRange);
  }
  if (!flags.video.empty()) {
    VideoFile::checkTarget("--video", flags.video, size, flags.fps, flags.outDir);
  }
}

// Creates the frames' folder when missing and makes sure files can be written into it, before
// the first frame is rendered.
void prepareOutDir(const fs::path& dir) {
  std::error_code error;
  if (!fs::exists(dir, error) && !fs::create_directory(dir.lexically_normal(), error)) {
    throwInputError("--out-dir " + dir.string(), "cannot create the folder: " + error.message());
  }
  try {
    const AtomicOutputFile probe(dir / "frames.json");  // removed as it leaves scope
  } catch (const InputError& e) {
    throwInputError("--out-dir " + dir.string(),
                    std::string("cannot write into the folder (") + e.what() + ")");
  }
}

// frame_0000.png ... (five digits beyond 10000 frames).
std::string frameFileName(int frame, int frames) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%0*d.png", frames > 10000 ? 5 : 4, frame);
  return name;
}

void run(const RenderFlags& renderFlags, const AnimateFlags& flags) {
  const auto start = Clock::now();
  const LoadOptions loadOptions = toLoadOptions(renderFlags.volume);
  RenderRequest base = toRenderRequest(renderFlags);
  base.settings.readDepth = false;  // frames are images only
  RenderJob::checkRequest(base, loadOptions.limits);
  const AnimationPlan plan(base, animationSpec(flags), loadOptions.limits);
  checkOutputs(flags, base.settings.size);
  const gl::ContextOptions glOptions = toContextOptions(renderFlags.gl);
  if (validateOnly()) return;

  RenderJob job(glOptions);
  // The render's memory is checked from the file's header, before any payload is read.
  printVolumeWarnings(job.load(renderFlags.input, RenderJob::loadOptionsFor(base, loadOptions)));
  const fs::path outDir = flags.outDir;
  if (!flags.outDir.empty()) prepareOutDir(outDir);
  std::optional<VideoFile> video;
  if (!flags.video.empty()) video.emplace(flags.video, base.settings.size, flags.fps);
  const double setupMs = millisecondsSince(start);

  const int frames = plan.frames();
  vsil::ProgressLine progress(std::cerr, isatty(STDERR_FILENO) == 1);
  AnimationWarnings warnings;
  nlohmann::ordered_json frameList = nlohmann::ordered_json::array();
  nlohmann::json dataset, upright, glInfo;
  std::string glRenderer;
  double renderMs = 0, readbackMs = 0, postfxMs = 0, writeMs = 0;
  const auto loopStart = Clock::now();
  int milestone = 0;  // tenths of the sequence reported in logs
  for (int i = 0; i < frames; ++i) {
    const auto frameStart = Clock::now();
    RenderOutput output = job.render(plan.request(i), loadOptions.limits);
    if (const auto now = warnings.add(output.warnings); !now.empty()) {
      progress.finish();
      printWarnings(now);
    }
    const auto writeStart = Clock::now();
    const std::string file = outDir.empty() ? "" : frameFileName(i, frames);
    if (!file.empty()) writePng(outDir / file, output.image);
    if (video) video->write(output.image);
    const double frameWriteMs = millisecondsSince(writeStart);

    nlohmann::json& meta = output.metadata;
    const nlohmann::json& timings = meta["timings_ms"];
    renderMs += timings["render"].get<double>();
    readbackMs += timings["readback"].get<double>();
    postfxMs += timings["postfx"].get<double>();
    writeMs += frameWriteMs;
    if (i == 0) {
      dataset = meta["dataset"];
      upright = meta["camera"]["upright"];  // the volume's: the same for every frame
      glRenderer = meta["gl_renderer"];
      glInfo = meta["gl"];
    }
    nlohmann::ordered_json entry = {{"index", i}, {"t", plan.t(i)}};
    if (!file.empty()) entry["file"] = file;
    entry["swept"] = plan.sweptValues(i);
    for (const char* key : {"parameters", "slices", "slice_step_eye", "pixels"}) {
      entry[key] = meta[key];
    }
    entry["timings_ms"] = timings;
    entry["timings_ms"]["write"] = frameWriteMs;
    entry["timings_ms"]["total"] = millisecondsSince(frameStart);
    frameList.push_back(std::move(entry));

    if (!flags.quiet) {
      const double seconds = millisecondsSince(loopStart) / 1000.0;
      const std::string text = progressText(i + 1, frames, seconds, {"frame", "fps"});
      if ((i + 1) * 10 / frames > milestone) {
        milestone = (i + 1) * 10 / frames;
        progress.milestone(text);
      } else {
        progress.update(text);
      }
    }
  }
  progress.finish();
  printWarnings(warnings.finish(frames));
  if (video) video->finish();
  const double framesMs = millisecondsSince(loopStart);
  const double fps = frames / (framesMs / 1000.0);

  if (!outDir.empty()) {
    nlohmann::ordered_json document;
    document["vsil_version"] = kVsilVersion;
    document["gl_renderer"] = glRenderer;
    document["gl"] = glInfo;
    document["input"] = renderFlags.input;
    document["technique"] = base.settings.technique;
    document["animation"] = plan.describe();
    document["dataset"] = dataset;
    document["upright"] = upright;
    if (video) {
      document["video"] = flags.video;
      document["video_fps"] = flags.fps;
    }
    document["frames"] = std::move(frameList);
    document["timings_ms"] = {{"setup", setupMs},
                              {"frames", framesMs},
                              {"render", renderMs},
                              {"readback", readbackMs},
                              {"postfx", postfxMs},
                              {"write", writeMs},
                              {"total", millisecondsSince(start)}};
    document["fps"] = fps;
    writeFileAtomically(outDir / "frames.json", jsonText(document, 1) + "\n");
  }
  // A video into standard output (--video /dev/stdout | ffplay -) comes there alone.
  std::ostream& report = reportStream({video ? flags.video : ""});
  if (!outDir.empty()) report << (outDir / "frames.json").string() << "\n";
  if (video && !namesStandardOutput(flags.video)) report << flags.video << "\n";
  char summary[160];
  std::snprintf(summary, sizeof summary, "%d frames in %.2f s: %.2f fps (set-up %.2f s)", frames,
                framesMs / 1000.0, fps, setupMs / 1000.0);
  report << summary << "\n";
}

const CommandRegistration registerAnimateCommand(20, [](CLI::App& app) {
  auto renderFlags = std::make_shared<RenderFlags>();
  auto flags = std::make_shared<AnimateFlags>();
  CLI::App* command = app.add_subcommand(
      "animate", "Render a sequence of frames (orbit, moving view, parameter sweeps) in one job");
  addRenderOptions(*command, *renderFlags);
  const std::string group = "Animation";
  command
      ->add_option("--frames", flags->frames,
                   "Number of frames (1.." + std::to_string(limits::kMaxFrames) + ")")
      ->required()
      ->group(group);
  command
      ->add_option("--orbit", flags->orbit,
                   "Degrees of azimuth over the sequence: frame i adds DEG*i/N (360: a loop)")
      ->group(group);
  CLI::Option* from =
      command
          ->add_option("--view-from", flags->viewFrom,
                       "View AZ,EL of the first frame, moving linearly to --view-to")
          ->group(group);
  CLI::Option* to =
      command->add_option("--view-to", flags->viewTo, "View AZ,EL of the last frame")->group(group);
  from->needs(to);
  to->needs(from);
  from->excludes(command->get_option("--view"));
  command
      ->add_option("--sweep", flags->sweeps,
                   "NAME=A:B: a numeric option from A (first frame) to B (last frame), e.g. "
                   "iso=30:50, zoom=1:2, width=2:8; given again for more")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->group(group);
  nonEmpty(
      command->add_option("--out-dir", flags->outDir,
                          "Folder for frame_0000.png ... and frames.json (created if missing)"))
      ->group(group);
  nonEmpty(
      command->add_option("--video", flags->video, "Video file: .mp4 (mp4v) or .avi (Motion JPEG)"))
      ->group(group);
  command->add_option("--fps", flags->fps, "Frames per second of the video")
      ->capture_default_str()
      ->group(group);
  command->add_flag("--quiet", flags->quiet, "No progress line on stderr")->group(group);
  command->callback([command, renderFlags, flags] {
    // A swept option sets its value on every frame: given as a flag too, one would be lost.
    for (const auto& text : flags->sweeps) {
      const std::string flag = "--" + parseSweep(text).name;
      const CLI::Option* option = command->get_option_no_throw(flag);
      if (option && option->count() > 0) {
        throwInputError("--sweep " + text, flag +
                                               " is given too, and the sweep sets it on every "
                                               "frame: give one of them");
      }
    }
    run(*renderFlags, *flags);
  });
});

}  // namespace
}  // namespace vsil::cli
