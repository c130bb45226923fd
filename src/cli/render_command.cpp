// vsil render: one frame of a technique to PNG, with optional state, depth and metadata files.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>

#include <nlohmann/json.hpp>

#include "cli/cli_gl_options.h"
#include "cli/cli_parse.h"
#include "cli/cli_postfx_options.h"
#include "cli/cli_volume_options.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_file.h"
#include "core/limits.h"
#include "io/volume_loader.h"
#include "postfx/compose.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"

namespace vsil::cli {
namespace {

// The embedded default volume the demo renders when no INPUT is given.
constexpr const char* kDefaultInput = "gen:spheres:128";

struct RenderOptions {
  std::string input = kDefaultInput;
  std::string technique = "silhouette";
  std::string pipeline = "fast";
  std::string size = "512x512";
  std::optional<double> iso;
  std::string view = "30,20";
  bool orthographic = false;
  double zoom = 1.0;
  double sampling = 1.0;
  double raExponent = 8.0;
  double raThreshold = 0.3;
  bool noEmptySpaceSkipping = false;
  std::string out = "vsil.png";
  std::string stateOut, depthOut, metaOut;
};

nlohmann::json matrixRowMajor(const glm::dmat4& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int row = 0; row < 4; ++row) {
    rows.push_back({m[0][row], m[1][row], m[2][row], m[3][row]});  // glm is column-major
  }
  return rows;
}

cv::Mat1b stateImage(const FrameBuffers& frame) {
  cv::Mat1b image(frame.state.size());
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image(y, x) = stateGrey(PixelState(frame.state(y, x)));
  }
  return image;
}

// 16-bit: silhouette pixels hold 1 + round(d·65534), every other pixel 0.
cv::Mat1w depthImage(const FrameBuffers& frame) {
  cv::Mat1w image(frame.state.size(), 0);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      if (PixelState(frame.state(y, x)) != PixelState::Silhouette) continue;
      const double d = std::clamp(double(frame.depth(y, x)), 0.0, 1.0);
      image(y, x) = std::uint16_t(1 + std::lround(d * 65534.0));
    }
  }
  return image;
}

// The flags checked together, before any file is read: what render() would refuse, the image's
// share of the memory limit.
RenderSettings checkedSettings(const RenderOptions& options, const LoadOptions& loadOptions,
                               const PostfxOptions& postfx) {
  RenderSettings settings;
  settings.technique = options.technique;
  settings.size = parseSize("--size", options.size);
  const glm::dvec2 view = parsePair("--view", options.view);
  settings.camera.azimuthDeg = view.x;
  settings.camera.elevationDeg = view.y;
  settings.camera.orthographic = options.orthographic;
  settings.camera.zoom = options.zoom;
  settings.samplesPerVoxel = options.sampling;
  if (options.pipeline != "fast" && options.pipeline != "paper") {
    throw InputError("--pipeline: unknown pipeline '" + options.pipeline +
                     "' (known: fast, paper)");
  }
  settings.silhouettePipeline =
      options.pipeline == "paper" ? SilhouettePipeline::Paper : SilhouettePipeline::Fast;
  settings.rightAngleExponent = options.raExponent;
  settings.rightAngleThreshold = options.raThreshold;
  settings.emptySpaceSkipping = !options.noEmptySpaceSkipping;
  const auto names = Renderer::techniqueNames();
  if (std::find(names.begin(), names.end(), settings.technique) == names.end()) {
    throw InputError("--technique: unknown technique '" + settings.technique +
                     "' (known: silhouette, rightangle)");
  }
  if (options.iso && !std::isfinite(*options.iso))
    throw InputError("--iso: must be a finite number");
  settings.iso = float(options.iso.value_or(0.0));  // the real default needs the volume
  Renderer::validateSettings(settings);
  const double maxWidth = std::max(postfx.width.near, postfx.width.far);
  if (maxWidth > limits::kMaxLineWidth) {
    throw InputError("--width: " + std::to_string(int(std::min(maxWidth, 1e9))) +
                     " pixels is over the limit of " + std::to_string(int(limits::kMaxLineWidth)));
  }
  limits::checkMemory("--size " + options.size, limits::renderImageBytes(settings.size, maxWidth),
                      loadOptions.limits.maxBytes);
  return settings;
}

// Once the volume is known: slices per frame and the whole render's memory.
void checkVolumeWork(const Volume& volume, const RenderSettings& settings,
                     const RenderOptions& options, const LoadOptions& loadOptions,
                     const PostfxOptions& postfx) {
  const std::int64_t slices = limits::sliceCountBound(volume.dims, settings.samplesPerVoxel);
  if (slices > limits::kMaxSlices) {
    throw InputError("--sampling " + std::to_string(settings.samplesPerVoxel) + ": " +
                     volume.source + " would need up to " + std::to_string(slices) +
                     " slices per frame, over the limit of " + std::to_string(limits::kMaxSlices));
  }
  const double maxWidth = std::max(postfx.width.near, postfx.width.far);
  const std::uint64_t bytes =
      limits::renderVolumeBytes(volume.dims) + limits::renderImageBytes(settings.size, maxWidth);
  limits::checkMemory("rendering " + volume.source + " at --size " + options.size, bytes,
                      loadOptions.limits.maxBytes);
}

void run(const RenderOptions& options, const LoadOptions& loadOptions, const PostfxOptions& postfx,
         const gl::ContextOptions& glOptions) {
  const auto start = std::chrono::steady_clock::now();
  RenderSettings settings = checkedSettings(options, loadOptions, postfx);
  if (validateOnly()) return;
  const glm::dvec2 view{settings.camera.azimuthDeg, settings.camera.elevationDeg};

  const Volume volume = loadVolume(options.input, loadOptions);
  checkVolumeWork(volume, settings, options, loadOptions, postfx);
  const ValueRange range = valueRange(volume);
  settings.iso = float(options.iso.value_or(0.5 * (double(range.min) + double(range.max))));

  gl::GlContext context(glOptions);
  Renderer renderer(context);
  renderer.setVolume(volume);
  const RenderResult result = renderer.render(settings);

  const auto postStart = std::chrono::steady_clock::now();
  FftGaussianBlur blur;
  const cv::Mat image = composeIllustration(result.frame, postfx, blur);
  const double postfxMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - postStart)
          .count();

  writePng(options.out, image);
  if (!options.stateOut.empty()) writePng(options.stateOut, stateImage(result.frame));
  if (!options.depthOut.empty()) writePng(options.depthOut, depthImage(result.frame));
  const double totalMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  if (!options.metaOut.empty()) {
    nlohmann::json meta;
    meta["vsil_version"] = "0.1.0";
    meta["gl_renderer"] = context.renderer();
    meta["gl"] = contextInfoJson(context.info());
    meta["parameters"] = {{"input", options.input},
                          {"technique", settings.technique},
                          {"pipeline", options.pipeline},
                          {"empty_space_skipping", settings.emptySpaceSkipping},
                          {"size", {settings.size.x, settings.size.y}},
                          {"iso", settings.iso},
                          {"view", {view.x, view.y}},
                          {"orthographic", settings.camera.orthographic},
                          {"zoom", settings.camera.zoom},
                          {"fov_y_deg", settings.camera.fovYDeg},
                          {"sampling", settings.samplesPerVoxel},
                          {"ra_exponent", settings.rightAngleExponent},
                          {"ra_threshold", settings.rightAngleThreshold},
                          {"out", options.out},
                          {"width_near", postfx.width.near},
                          {"width_far", postfx.width.far},
                          {"fill", postfx.fill == FillMode::None   ? "none"
                                   : postfx.fill == FillMode::Flat ? "flat"
                                                                   : "shaded"}};
    meta["dataset"] = {{"name", volume.name},
                       {"source", volume.source},
                       {"type", sampleTypeName(volume.type)},
                       {"dims", {volume.dims.x, volume.dims.y, volume.dims.z}},
                       {"spacing", {volume.spacing.x, volume.spacing.y, volume.spacing.z}},
                       {"value_range", {range.min, range.max}}};
    meta["slices"] = result.sliceCount;
    meta["slice_step_eye"] = result.sliceStepEye;
    meta["camera"] = {{"eye_from_voxel", matrixRowMajor(result.view.eyeFromVoxel)},
                      {"clip_from_eye", matrixRowMajor(result.view.clipFromEye)},
                      {"viewport", {result.view.viewport.x, result.view.viewport.y}},
                      {"depth_range_eye", {result.view.nearEye, result.view.farEye}},
                      {"orthographic", result.view.orthographic}};
    int counts[4] = {0, 0, 0, 0};
    for (auto it = result.frame.state.begin(); it != result.frame.state.end(); ++it) {
      ++counts[std::min<int>(*it, 3)];
    }
    meta["pixels"] = {{"empty", counts[0]}, {"filled", counts[1]}, {"silhouette", counts[3]}};
    meta["timings_ms"] = {{"render", result.timings.renderMs},
                          {"readback", result.timings.readbackMs},
                          {"postfx", postfxMs},
                          {"total", totalMs}};
    writeFileAtomically(options.metaOut, meta.dump(2) + "\n");
  }
  std::cout << options.out << "\n";
}

const CommandRegistration registration(10, [](CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  auto load = std::make_shared<VolumeOptions>();
  auto postfx = std::make_shared<PostfxOptions>();
  auto glFlags = std::make_shared<GlOptions>();
  CLI::App* command = app.add_subcommand("render", "Render one frame of a technique to PNG");
  command->add_option("input", options->input,
                      "Volume file (.nrrd .nhdr .vti .vtk, raw with --dims/--type) or "
                      "gen:NAME[:N]; default " +
                          std::string(kDefaultInput));
  command->add_option("--technique", options->technique, "silhouette | rightangle")
      ->capture_default_str();
  command
      ->add_option("--pipeline", options->pipeline,
                   "silhouette: fast (fused in-place passes) or paper (the paper's three "
                   "passes); same pixels")
      ->capture_default_str();
  command->add_flag("--no-empty-space-skipping", options->noEmptySpaceSkipping,
                    "sample every pixel of every slice (slower; the same pixels)");
  command->add_option("--size", options->size, "Image size WxH")->capture_default_str();
  command->add_option("--iso", options->iso,
                      "Iso value in the data's own units (default: middle of the value range)");
  command->add_option("--view", options->view, "Orbit angles AZ,EL in degrees")
      ->capture_default_str();
  command->add_flag("--ortho", options->orthographic, "Orthographic instead of perspective");
  command->add_option("--zoom", options->zoom, "Magnification (> 0)")->capture_default_str();
  command->add_option("--sampling", options->sampling, "Slices per voxel along the view")
      ->capture_default_str();
  command
      ->add_option("--ra-exponent", options->raExponent, "rightangle: exponent k of (1 - |n.v|)^k")
      ->capture_default_str();
  command
      ->add_option("--ra-threshold", options->raThreshold,
                   "rightangle: line where (1 - |n.v|)^k exceeds this")
      ->capture_default_str();
  command->add_option("--out", options->out, "Output PNG")->capture_default_str();
  command->add_option("--state-out", options->stateOut,
                      "8-bit PNG of pixel states: 0 Empty, 85 Filled, 170 Contour, 255 Silhouette");
  command->add_option("--depth-out", options->depthOut,
                      "16-bit PNG: silhouette pixels 1 + round(d*65534), others 0");
  command->add_option("--meta-out", options->metaOut, "JSON with parameters, camera, timings");
  addVolumeOptions(*command, *load);
  addPostfxOptions(*command, *postfx);
  addGlOptions(*command, *glFlags);
  command->callback([options, load, postfx, glFlags] {
    run(*options, toLoadOptions(*load), *postfx, toContextOptions(*glFlags));
  });
});

}  // namespace
}  // namespace vsil::cli
