#include "job/render_job.h"

#include "slicing/slab.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <variant>

#include "core/clock.h"
#include "core/depth_image.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/number_pair.h"
#include "core/options.h"
#include "core/upright.h"
#include "core/version.h"
#include "postfx/broaden.h"
#include "slicing/gl_context.h"
#include "slicing/technique_table.h"

namespace vsil {

namespace {

nlohmann::json matrixRowMajor(const glm::dmat4& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int row = 0; row < 4; ++row) {
    rows.push_back({m[0][row], m[1][row], m[2][row], m[3][row]});  // glm is column-major
  }
  return rows;
}

double maxLineWidth(const PostfxOptions& postfx) {
  return std::max(postfx.width.near, postfx.width.far);
}

// Pixel counts by what the technique returns: states, or colour coverage.
nlohmann::json pixelCounts(const FrameBuffers& frame) {
  if (!frame.state.empty()) {
    int counts[4] = {0, 0, 0, 0};
    for (auto it = frame.state.begin(); it != frame.state.end(); ++it) {
      ++counts[std::min<int>(*it, 3)];
    }
    return {{"empty", counts[0]}, {"filled", counts[1]}, {"silhouette", counts[3]}};
  }
  int covered = 0, opaque = 0;
  for (auto it = frame.color.begin(); it != frame.color.end(); ++it) {
    covered += (*it)[3] > 0.0f;
    opaque += (*it)[3] >= 1.0f - 1.0f / 255.0f;
  }
  return {{"covered", covered}, {"opaque", opaque}, {"total", frame.color.total()}};
}

nlohmann::json metadata(const RenderRequest& request, const std::string& input,
                        const Volume& volume, ValueRange range, const RenderResult& result,
                        const gl::ContextInfo& glContext, StageTime postfx) {
  const RenderSettings& settings = request.settings;
  const TechniqueInfo& technique = findTechnique(settings.technique);
  const ResolvedUpright upright = resolveUpright(request.up, volume.orientations);
  nlohmann::json parameters = {{"input", input},
                               {"technique", settings.technique},
                               {"empty_space_skipping", settings.emptySpaceSkipping},
                               {"size", {settings.size.x, settings.size.y}},
                               {"view", {settings.camera.azimuthDeg, settings.camera.elevationDeg}},
                               {"up", request.up},
                               {"orthographic", settings.camera.orthographic},
                               {"zoom", settings.camera.zoom},
                               {"fov_y_deg", settings.camera.fovYDeg},
                               {"sampling", settings.samplesPerVoxel},
                               {"early_ray_termination", settings.earlyRayTermination},
                               {"background", result.background.hex()}};
  parameters.update(result.options);
  if (technique.outputs.state) {
    parameters["width_near"] = request.postfx.width.near;
    parameters["width_far"] = request.postfx.width.far;
    parameters["fill"] = fillModeName(request.postfx.fill);
    if (request.postfx.fill != FillMode::Tone) {  // the tone fill's options shape nothing else
      parameters.erase("param");
      parameters.erase("light");
    }
    if (request.postfx.fill != FillMode::None) {
      parameters["fill_color"] = request.postfx.fillColor.hex();
    }
    parameters["line_color"] = request.postfx.lineColor.hex();
  }
  nlohmann::json meta;
  meta["vsil_version"] = kVsilVersion;
  meta["gl_renderer"] = glContext.renderer;
  meta["gl"] = gl::contextInfoJson(glContext);
  meta["parameters"] = parameters;
  meta["dataset"] = {{"name", volume.name},
                     {"source", volume.source},
                     {"type", sampleTypeName(volume.type())},
                     {"dims", {volume.dims.x, volume.dims.y, volume.dims.z}},
                     {"spacing", {volume.spacing.x, volume.spacing.y, volume.spacing.z}},
                     {"value_range", {range.min, range.max}}};
  meta["slices"] = result.sliceCount;
  meta["slice_step_eye"] = result.sliceStepEye;
  meta["volume_texture"] = {
      {"format", result.textureFormat},
      {"bricks", {result.textureBricks.x, result.textureBricks.y, result.textureBricks.z}}};
  meta["camera"] = {
      {"eye_from_voxel", matrixRowMajor(result.view.eyeFromVoxel)},
      {"clip_from_eye", matrixRowMajor(result.view.clipFromEye)},
      {"viewport", {result.view.viewport.x, result.view.viewport.y}},
      {"depth_range_eye", {result.view.nearEye, result.view.farEye}},
      {"orthographic", result.view.orthographic},
      {"upright", {{"up", upright.up}, {"front", upright.front}, {"from", upright.from}}}};
  meta["pixels"] = pixelCounts(result.frame);
  // The frame's stages in wall time and in the process's CPU time; the caller adds its own
  // (render_command.cpp: start-up, context, read, upload, write, total).
  const RenderTimings& timings = result.timings;
  for (const auto& [key, time] :
       {std::pair{"timings_ms", &StageTime::wallMs}, std::pair{"cpu_ms", &StageTime::cpuMs}}) {
    meta[key] = {{"defaults", timings.defaults.*time},
                 {"programs", timings.programs.*time},
                 {"render", timings.render.*time},
                 {"readback", timings.readback.*time},
                 {"postfx", postfx.*time}};
  }
  return meta;
}

// What rendering `request` takes in memory for a volume of `dims` samples of `type`: its
// textures and the structures beside them (limits::renderVolumeBytes) and the images.
std::uint64_t renderBytes(const RenderRequest& request, glm::ivec3 dims, SampleType type,
                          std::uint64_t maxTextureBytes) {
  const RenderSettings& settings = request.settings;
  const TechniqueInfo& technique = findTechnique(settings.technique);
  return limits::renderVolumeBytes(dims, sampleTypeSize(type), technique.usesGradients,
                                   maxTextureBytes,
                                   technique.needsOneTextureWith(settings.options)) +
         limits::renderImageBytes(settings.size, maxLineWidth(request.postfx));
}

// Once the volume is known: slices per frame and the whole render's memory.
void checkVolumeWork(const Volume& volume, const RenderRequest& request,
                     const VolumeLimits& limits) {
  const RenderSettings& settings = request.settings;
  const double sampling = settings.samplesPerVoxel;
  const glm::dvec3 s = volume.spacing;
  const std::string spacingText =
      formatNumber(s.x) + "," + formatNumber(s.y) + "," + formatNumber(s.z);
  // Every spacing is positive and finite (the readers check), but their extent or ratio can
  // still overflow a double (1e308 along each axis, 1e-320 beside 1).
  const double ratio = std::max({s.x, s.y, s.z}) / std::min({s.x, s.y, s.z});
  if (!std::isfinite(glm::length(glm::dvec3(volume.dims) * s)) || !std::isfinite(ratio)) {
    throw InputError(volume.source + ": spacing " + spacingText +
                     " is out of range (the volume's extent or the ratio of its axes is not a "
                     "finite number); check the spacing's units");
  }
  const std::int64_t slices = limits::sliceCountBound(volume.dims, volume.spacing, sampling);
  if (slices > limits::kMaxSlices) {
    const std::string over =
        " slices per frame, over the limit of " + std::to_string(limits::kMaxSlices);
    if (limits::sliceCountBound(volume.dims, glm::dvec3(1.0), sampling) > limits::kMaxSlices) {
      throw InputError("--sampling " + formatNumber(sampling) + ": " + volume.source +
                       " would need up to " + std::to_string(slices) + over);
    }
    // The samples alone fit: the spacing's axes differ so much that slices one step of the
    // finest axis apart cross the others thousands of times over (a unit mixed up, mm and m).
    const double enough = sampling * double(limits::kMaxSlices - 1) / double(slices);
    const auto twoDigits = [](double number, bool down) {
      const double unit = std::pow(10.0, std::floor(std::log10(number)) - 1);
      std::ostringstream text;
      text << std::setprecision(2)
           << (down ? std::floor(number / unit) : std::round(number / unit)) * unit;
      return text.str();
    };
    throw InputError(volume.source + ": spacing " + spacingText + " (its coarsest axis " +
                     twoDigits(ratio, false) + " times its finest) would need up to " +
                     std::to_string(slices) + over +
                     "; check the spacing's units, or lower --sampling to " +
                     twoDigits(enough, true) + " or less");
  }
  const std::uint64_t bytes =
      renderBytes(request, volume.dims, volume.type(), limits.maxTextureBytes);
  limits::checkMemory("rendering " + volume.source + " at --size " +
                          std::to_string(settings.size.x) + "x" + std::to_string(settings.size.y),
                      bytes, limits.maxBytes);
}

// An iso value outside the data's range finds no surface, and a window that starts above it
// shows no maximum: the frame is empty, which is what was asked, but rarely what was meant (an
// LMIP threshold above it makes lmip a mip).
// `uploadedRange`: the range found when the samples were uploaded, still theirs when the volume
// owns them.
std::vector<std::string> warnings(const RenderRequest& request, const Volume& volume,
                                  ValueRange uploadedRange, int slices) {
  std::vector<std::string> found;
  // A --sampling lowered so far that a few slices remain shows cross-sections, not the volume
  // (a small volume with few slices at the default sampling is what it is).
  constexpr int kFewSlices = 16;
  const double sampling = request.settings.samplesPerVoxel;
  const double defaultSampling = RenderSettings{}.samplesPerVoxel;
  if (sampling < defaultSampling && slices < kFewSlices &&
      slices * defaultSampling / sampling >= kFewSlices) {
    // Without the view's own count: an animation says it once, not once per count.
    found.push_back("--sampling " + formatNumber(sampling) + " leaves fewer than " +
                    std::to_string(kFewSlices) + " slices through " + volume.source +
                    ": the picture shows cross-sections, not the volume");
  }
  const TechniqueInfo& technique = findTechnique(request.settings.technique);
  if (!technique.outputs.state && !request.lineFlagsGiven.empty()) {
    std::string drawers;
    for (const TechniqueInfo& info : techniqueTable()) {
      if (info.outputs.state) drawers += (drawers.empty() ? "" : " and ") + info.name;
    }
    found.push_back(joined(request.lineFlagsGiven, ", ") + ": technique '" + technique.name +
                    "' draws no lines or filled pixels; ignored (the line flags go with " +
                    drawers + ")");
  }
  if (technique.outputs.state && request.postfx.fill == FillMode::None &&
      std::find(request.lineFlagsGiven.begin(), request.lineFlagsGiven.end(), "--fill-color") !=
          request.lineFlagsGiven.end()) {
    found.push_back("--fill-color: there is no --fill; ignored");
  }
  if (technique.ignoredOptions) {
    for (std::string& line :
         technique.ignoredOptions(OptionReader(technique.options, request.settings.options))) {
      found.push_back(std::move(line));
    }
  }
  const auto& options = request.settings.options;
  const auto iso = options.find("iso");
  const std::string* windowText = givenText(options, "window");
  const auto lmipThreshold = options.find("lmip-threshold");
  if (iso == options.end() && !(windowText && !windowText->empty()) &&
      lmipThreshold == options.end()) {
    return found;
  }
  // Borrowed samples as they are now: Python may change an array in place after its upload.
  const ValueRange range = volume.borrowsSamples() ? valueRange(volume) : uploadedRange;
  std::ostringstream line;
  if (iso != options.end()) {
    const double value = std::get<double>(iso->second);
    if (value > range.max || value < range.min) {
      line << "--iso " << value << " is outside the data's range " << range.min << " .. "
           << range.max << " of " << volume.source << ": " << (value > range.max ? "no" : "every")
           << " sample reaches it";
      found.push_back(line.str());
    }
  }
  // The MIP family shows a pixel whose maximum exceeds the window's low end.
  if (windowText && !windowText->empty()) {
    const double low = parseNumberPair("--window", *windowText).x;
    if (low >= range.max) {
      line.str("");
      line << "--window " << *windowText << " starts at or above the data's largest value "
           << range.max << " of " << volume.source << ": no pixel shows anything";
      found.push_back(line.str());
    }
  }
  // LMIP shows a ray's first local maximum at or above the threshold, else its maximum.
  if (lmipThreshold != options.end()) {
    const double value = std::get<double>(lmipThreshold->second);
    if (value > range.max) {
      line.str("");
      line << "--lmip-threshold " << value << " is above the data's largest value " << range.max
           << " of " << volume.source
           << ": no local maximum reaches it, and every pixel shows its ray's maximum (as mip)";
      found.push_back(line.str());
    }
  }
  return found;
}

}  // namespace

struct RenderJob::Impl {
  explicit Impl(const gl::ContextOptions& gl) : context(gl) {}
  gl::GlContext context;
  std::optional<Renderer> renderer;
  std::optional<Volume> volume;
  std::string input;  // the spec the volume was loaded from
  FftGaussianBlur blur;
};

RenderJob::RenderJob(const gl::ContextOptions& gl) : impl_(std::make_unique<Impl>(gl)) {
  impl_->renderer.emplace(impl_->context);
}

RenderJob::~RenderJob() = default;

const Volume& RenderJob::load(const std::string& spec, const LoadOptions& options) {
  return setVolume(loadVolume(spec, options), spec, options.limits.maxTextureBytes);
}

const Volume& RenderJob::setVolume(Volume volume, const std::string& input,
                                   std::uint64_t maxTextureBytes) {
  impl_->context.makeCurrent();
  impl_->volume.reset();
  impl_->volume.emplace(std::move(volume));
  impl_->input = input.empty() ? impl_->volume->source : input;
  impl_->renderer->setVolume(*impl_->volume, maxTextureBytes);
  return *impl_->volume;
}

std::uint64_t RenderJob::memoryBytes(const RenderRequest& request, glm::ivec3 dims, SampleType type,
                                     std::uint64_t maxTextureBytes) {
  return renderBytes(request, dims, type, maxTextureBytes);
}

const Volume& RenderJob::setSlab(Volume slabVolume, const SlabPart& part,
                                 const std::string& input) {
  impl_->context.makeCurrent();
  impl_->volume.reset();
  impl_->volume.emplace(std::move(slabVolume));
  impl_->input = input;
  impl_->renderer->setSlab(*impl_->volume, part);
  return *impl_->volume;
}

const Volume& RenderJob::volume() const {
  if (!impl_->volume) throw std::logic_error("RenderJob: no volume loaded");
  return *impl_->volume;
}

gl::GlContext& RenderJob::context() {
  return impl_->context;
}

Renderer& RenderJob::renderer() {
  return *impl_->renderer;
}

namespace {

// The render settings as the renderer needs them: the background (what distance colour
// blending blends towards) and the tone fill are composition flags the technique reads.
RenderSettings settingsFor(const RenderRequest& request, const Volume& volume) {
  RenderSettings settings = request.settings;
  settings.camera = cameraFor(request, volume);
  if (request.postfx.background) settings.background = request.postfx.background;
  if (request.postfx.fill == FillMode::Tone) settings.toneFill = request.postfx.fillColor;
  return settings;
}

}  // namespace

CameraSpec cameraFor(const RenderRequest& request, const Volume& volume) {
  CameraSpec camera = request.settings.camera;
  camera.upright = resolveUpright(request.up, volume.orientations).upright;
  return camera;
}

void RenderJob::checkRequest(const RenderRequest& request, const VolumeLimits& limits) {
  Renderer::validateSettings(request.settings);
  // The tone fill's parameters and lights shape nothing else (tone_fill.h).
  if (request.postfx.fill != FillMode::Tone &&
      findTechnique(request.settings.technique).outputs.state) {
    for (const char* option : {"param", "light"}) {
      if (request.settings.options.contains(option)) {
        throwInputError(std::string("--") + option,
                        "only with --fill tone (it shapes the tone fill of technique '" +
                            request.settings.technique + "')");
      }
    }
  }
  const WidthLaw& law = request.postfx.width;
  if (law.isFixed()) {
    law.validate("--width");
  } else {
    WidthLaw::fixed(law.near).validate("--width-near");
    WidthLaw::fixed(law.far).validate("--width-far");
  }
  const double width = maxLineWidth(request.postfx);
  if (width > limits::kMaxLineWidth) {
    const char* flag = law.isFixed()         ? "--width"
                       : law.near >= law.far ? "--width-near"
                                             : "--width-far";
    throwInputError(flag, formatNumber(width) + " pixels is over the limit of " +
                              std::to_string(int(limits::kMaxLineWidth)));
  }
  const glm::ivec2 size = request.settings.size;
  limits::checkMemory("--size " + std::to_string(size.x) + "x" + std::to_string(size.y),
                      limits::renderImageBytes(size, width), limits.maxBytes);
}

LoadOptions RenderJob::loadOptionsFor(const RenderRequest& request, LoadOptions load) {
  const glm::ivec2 size = request.settings.size;
  // The same sum as checkVolumeWork's, before reading (the loader calls it with the header's
  // dims and type).
  load.limits.taskBytes = [request, maxTextureBytes = load.limits.maxTextureBytes](
                              glm::ivec3 dims, SampleType type) {
    return renderBytes(request, dims, type, maxTextureBytes);
  };
  load.limits.task = "rendering";
  load.limits.taskDetail = " at --size " + std::to_string(size.x) + "x" + std::to_string(size.y);
  return load;
}

RenderOutput RenderJob::render(const RenderRequest& request, const VolumeLimits& limits) {
  checkRequest(request, limits);
  const Volume& volume = this->volume();
  checkVolumeWork(volume, request, limits);
  impl_->context.makeCurrent();

  RenderOutput output;
  output.result = impl_->renderer->render(settingsFor(request, volume));
  StageClock postfxClock;
  PostfxOptions postfx = request.postfx;
  postfx.background = output.result.background;
  output.image = composeIllustration(output.result.frame, postfx, impl_->blur);
  output.postfx = postfxClock.lap();
  // The value range of the samples the frame rendered, found once when they were uploaded.
  const ValueRange range = impl_->renderer->valueRange();
  output.metadata = metadata(request, impl_->input, volume, range, output.result,
                             impl_->context.info(), output.postfx);
  output.warnings = warnings(request, volume, range, output.result.sliceCount);
  return output;
}

cv::Mat1b stateImage(const FrameBuffers& frame) {
  cv::Mat1b image(frame.state.size());
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image(y, x) = stateGrey(PixelState(frame.state(y, x)));
  }
  return image;
}

cv::Mat1w depthImage(const FrameBuffers& frame) {
  if (frame.state.empty()) return encodeDepthImage(frame.depth);
  cv::Mat1f lineDepth(frame.depth.size(), std::numeric_limits<float>::quiet_NaN());
  frame.depth.copyTo(lineDepth, frame.state == std::uint8_t(PixelState::Silhouette));
  return encodeDepthImage(lineDepth);
}

}  // namespace vsil
