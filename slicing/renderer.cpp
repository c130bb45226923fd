#include "slicing/renderer.h"

#include "slicing/slab.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <optional>

#include "core/clock.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/options.h"
#include "core/transfer_function.h"
#include "slicing/empty_space.h"
#include "slicing/frame_uniforms.h"
#include "slicing/gl_context.h"
#include "slicing/gl_state.h"
#include "slicing/gradient_texture.h"
#include "slicing/technique.h"
#include "slicing/technique_table.h"
#include "slicing/texture_units.h"
#include "slicing/volume_texture.h"

namespace vsil {

namespace {

constexpr int kMaxImageSide = limits::kMaxImageSide;
constexpr double kMaxSamplesPerVoxel = limits::kMaxSamplesPerVoxel;

void validate(const RenderSettings& settings) {
  if (settings.size.x < 1 || settings.size.y < 1 || settings.size.x > kMaxImageSide ||
      settings.size.y > kMaxImageSide) {
    throw InputError("--size: " + std::to_string(settings.size.x) + "x" +
                     std::to_string(settings.size.y) + " is outside 1.." +
                     std::to_string(kMaxImageSide) + " pixels per side");
  }
  if (!(settings.samplesPerVoxel > 0) || settings.samplesPerVoxel > kMaxSamplesPerVoxel) {
    throw InputError("--sampling: must be in (0, 64] slices per voxel");
  }
  if (!(settings.camera.zoom >= limits::kMinZoom && settings.camera.zoom <= limits::kMaxZoom)) {
    throw InputError("--zoom: must be in [" + formatNumber(limits::kMinZoom) + ", " +
                     formatNumber(limits::kMaxZoom) + "]");
  }
  if (!std::isfinite(settings.camera.azimuthDeg) || !std::isfinite(settings.camera.elevationDeg)) {
    throw InputError("--view: angles must be finite");
  }
  const TechniqueInfo& technique = findTechnique(settings.technique);
  checkOptions(technique.options, settings.options, "technique '" + technique.name + "'");
  if (technique.checkValues) technique.checkValues(settings.options);
}

// Whether a frame needs the volume's histogram (derivedDefaults): a technique with an iso
// option needs it only when every value it derives from the histogram is given: each iso
// option, and where the technique shows a window (lmip: its threshold is an iso option, its
// window is not) the window itself or a transfer function in its place; a --tf preset scales
// by the histogram whatever else is given. The others (the MIP family's default window,
// illustrate's and semantic's classification above Otsu's threshold) always do.
bool needsHistogram(const TechniqueInfo& info, const OptionValues& given) {
  bool hasIso = false;
  for (const OptionSpec& spec : info.options) {
    if (spec.derived == OptionSpec::Derived::VolumeIso) {
      hasIso = true;
      if (!given.contains(spec.name)) return true;
    }
    if (spec.name == "window" && !given.contains("window") && !given.contains("tf")) return true;
    if (spec.name == "tf") {
      const std::string* tf = givenText(given, "tf");
      if (tf && !tf->empty() && isTransferFunctionPreset(*tf)) return true;
    }
  }
  return !hasIso;
}

}  // namespace

void Renderer::validateSettings(const RenderSettings& settings) {
  validate(settings);
}

struct Renderer::Impl {
  gl::GlContext* context = nullptr;
  const Volume* volume = nullptr;  // what volumeTexture holds (setVolume)
  std::uint64_t maxTextureBytes = 0;
  BrickLayout::Bricking bricking = BrickLayout::Bricking::Compact;
  std::optional<VolumeTexture> volumeTexture;
  std::optional<BrickRanges> brickRanges;
  std::optional<EmptySpaceSkipping> emptySpace;
  std::optional<FrameUniforms> uniforms;
  GradientTextureCache gradients;
  int volumeGeneration = 0;
  gl::ProgramCache programs;
  glm::ivec3 dims{0};
  glm::dvec3 spacing{1.0};
  ValueRange valueRange;
  std::optional<DerivedDefaults> histogramDefaults;  // on the first frame that needs them
  gl::BufferName sliceBuffer;
  gl::VertexArrayName sliceVertexArray;
  gl::VertexArrayName screenVertexArray;
  std::map<std::string, std::unique_ptr<Technique>> techniques;
  std::optional<SlabPart> slab;  // setSlab

  // Uploads `volume` in the layout `bricking` asks for; gradients and halo masks follow
  // (volumeGeneration).
  void uploadVolume(BrickLayout::Bricking how) {
    gradients.reset(nullptr, volume->spacing);
    volumeTexture.reset();
    volumeTexture.emplace(*volume, maxTextureBytes, limits::kUploadSlabBytes, how);
    bricking = how;
    gradients.reset(&*volumeTexture, volume->spacing);
    if (!uniforms) uniforms.emplace();
    uniforms->uploadBricks(volumeTexture->layout());
    ++volumeGeneration;
  }

  Technique& technique(const TechniqueInfo& info) {
    auto it = techniques.find(info.name);
    if (it == techniques.end()) it = techniques.emplace(info.name, info.create()).first;
    return *it->second;
  }
};

Renderer::Renderer(gl::GlContext& context) : impl_(std::make_unique<Impl>()) {
  impl_->context = &context;
  context.makeCurrent();
  impl_->sliceBuffer = gl::createBuffer();
  impl_->sliceVertexArray = gl::createVertexArray();
  impl_->screenVertexArray = gl::createVertexArray();
  VSIL_GL(glBindVertexArray(impl_->sliceVertexArray.id()));
  VSIL_GL(glBindBuffer(GL_ARRAY_BUFFER, impl_->sliceBuffer.id()));
  VSIL_GL(glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr));
  VSIL_GL(glEnableVertexAttribArray(0));
  glBindVertexArray(0);
}

Renderer::~Renderer() {
  // GL deletes objects by name in the current context: with another renderer's context current
  // (two vsil.Renderer in one Python process), this one's names would delete that one's
  // buffers and textures.
  if (!impl_ || !impl_->context) return;
  try {
    impl_->context->makeCurrent();
  } catch (const std::exception&) {
    // Nothing can be made current any more: the objects go with the context.
  }
}

std::size_t Renderer::brickCount() const {
  return impl_->volumeTexture ? impl_->volumeTexture->brickCount() : 0;
}

ValueRange Renderer::valueRange() const {
  return impl_->valueRange;
}

const gl::ProgramCache& Renderer::programs() const {
  return impl_->programs;
}

void Renderer::setSlab(const Volume& slabVolume, const SlabPart& part) {
  impl_->slab = part;
  impl_->volume = &slabVolume;
  impl_->gradients.reset(nullptr, slabVolume.spacing);
  impl_->volumeTexture.reset();
  impl_->volumeTexture.emplace(slabVolume, part);
  impl_->gradients.reset(&*impl_->volumeTexture, slabVolume.spacing, &*impl_->slab);
  if (!impl_->uniforms) impl_->uniforms.emplace();
  impl_->uniforms->uploadBricks(impl_->volumeTexture->layout());
  ++impl_->volumeGeneration;
  // Empty-space skipping stays off for slabs (render()): its ranges are never read.
  impl_->brickRanges.emplace(slabVolume);
  impl_->dims = part.dims;
  impl_->spacing = slabVolume.spacing;
  impl_->valueRange = part.valueRange;
  impl_->histogramDefaults = part.derived;
}

void Renderer::setVolume(const Volume& volume, std::uint64_t maxTextureBytes) {
  impl_->slab.reset();
  impl_->volume = &volume;
  impl_->maxTextureBytes = maxTextureBytes;
  impl_->uploadVolume(BrickLayout::Bricking::Compact);
  impl_->brickRanges.emplace(volume);
  impl_->dims = volume.dims;
  impl_->spacing = volume.spacing;
  impl_->valueRange = impl_->brickRanges->whole();  // vsil::valueRange's, from the bricks
  impl_->histogramDefaults.reset();
}

RenderResult Renderer::render(const RenderSettings& givenSettings) {
  if (!impl_->volumeTexture) throw std::logic_error("Renderer::render before setVolume");
  validate(givenSettings);
  const SlabPart* slab = impl_->slab ? &*impl_->slab : nullptr;
  RenderSettings settings = givenSettings;
  // A slab's brick ranges are its own: skipping (which changes no pixel) stays off.
  if (slab) settings.emptySpaceSkipping = false;
  const TechniqueInfo& info = findTechnique(settings.technique);
  Technique& technique = impl_->technique(info);
  RenderResult result;
  OptionValues given = optionsForBricks(info, settings.options, impl_->volumeTexture->brickCount());
  if (slab) given = optionsForSlab(info, std::move(given));
  // The histogram's defaults take a pass over every sample: only for frames that need them.
  DerivedDefaults derived{
      .valueRangeWidth = double(impl_->valueRange.max) - double(impl_->valueRange.min),
      .valueMin = impl_->valueRange.min};
  if (needsHistogram(info, given)) {
    if (!impl_->histogramDefaults) {
      StageClock clock;
      impl_->histogramDefaults = derivedDefaults(*impl_->volume, impl_->valueRange);
      result.timings.defaults = clock.lap();
    }
    derived = *impl_->histogramDefaults;
  }
  const OptionReader options(info.options, given, derived);
  // Bricks the frame cannot follow: the volume in one texture when it fits (else the
  // technique refuses). It stays so for later frames (the same bytes either way).
  if (slab && info.needsOneTextureInSlab(given)) {
    throw UnavailableError("--technique " + info.name +
                           ": these options need the volume in one texture, which a slab "
                           "rendered across MPI ranks is not");
  }
  if (!slab && impl_->volumeTexture->brickCount() > 1 &&
      impl_->bricking == BrickLayout::Bricking::Compact && info.needsOneTextureWith(given)) {
    impl_->bricking = BrickLayout::Bricking::OneIfItFits;  // asked once per volume
    if (fitsOneTexture(impl_->dims, impl_->volumeTexture->internalFormat(),
                       impl_->maxTextureBytes)) {
      impl_->uploadVolume(BrickLayout::Bricking::OneIfItFits);
    }
  }

  result.view = makeView(settings.camera, impl_->dims, impl_->spacing, settings.size);
  result.options = options.toJson();
  const SlicePlan plan =
      planSlices(result.view, impl_->dims, impl_->spacing, settings.samplesPerVoxel);
  result.sliceCount = int(plan.slices.size());
  result.sliceStepEye = plan.stepEye;
  result.textureFormat = impl_->volumeTexture->internalFormat() == GL_R16F ? "R16F" : "R32F";
  result.textureBricks = impl_->volumeTexture->layout().counts();

  // All slice pieces (slicer.h slicePieces) as triangle fans in one buffer, uploaded once per
  // frame.
  const BrickLayout& layout = impl_->volumeTexture->layout();
  std::vector<glm::vec3> vertices;
  std::vector<SliceContext> slices(plan.slices.size());
  const double margin = info.samplesOffPlanes ? pieceMargin(plan) : kPieceMargin;
  const double overlap = info.samplesOffPlanes ? margin : 0.0;
  for (std::size_t k = 0; k < plan.slices.size(); ++k) {
    SliceContext& slice = slices[k];
    slice.index = int(k);
    slice.slice = &plan.slices[k];
    slice.firstVertex = GLint(vertices.size());
    if (!plan.slices[k].polygonVoxel.empty()) {
      for (const SlicePiece& piece :
           slicePieces(result.view, layout, plan.slices[k].eyeDistance, margin, overlap)) {
        // Bounds from every piece, so that screen passes cover what a single process covers.
        slice.recentBounds[0] =
            slice.recentBounds[0].united(polygonPixelBounds(result.view, piece.polygonVoxel));
        if (slab && !slab->holds(piece.brick)) continue;
        const bool ghost = slab && !slab->owns(piece.brick);
        (ghost ? slice.ghostPieces : slice.pieces)
            .push_back({GLint(vertices.size()), GLsizei(piece.polygonVoxel.size()), piece.brick});
        if (!ghost) slice.vertexCount += GLsizei(piece.polygonVoxel.size());
        for (const auto& p : piece.polygonVoxel) vertices.emplace_back(p);
      }
    }
    for (std::size_t back = 1; back <= 2 && back <= k; ++back) {
      slice.recentBounds[back] = slices[k - back].recentBounds[0];
    }
  }

  gl::ScopedState restoreState;
  StageClock clock;
  const StageTime programsBefore = gl::programBuildTime();
  VSIL_GL(glBindBuffer(GL_ARRAY_BUFFER, impl_->sliceBuffer.id()));
  VSIL_GL(glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(glm::vec3)),
                       vertices.data(), GL_STREAM_DRAW));
  if (!impl_->uniforms) impl_->uniforms.emplace();
  impl_->uniforms->upload(result.view, impl_->dims, plan);
  glViewport(0, 0, settings.size.x, settings.size.y);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  // One brick: bound for the whole frame (drawSlicePolygon binds each piece's brick otherwise).
  gl::bindTexture(gl::TextureUnit::Volume, GL_TEXTURE_3D, impl_->volumeTexture->brickTexture(0));
  impl_->uniforms->bindBrick(0);

  FrameContext frame;
  frame.settings = &settings;
  frame.options = &options;
  frame.view = &result.view;
  frame.plan = &plan;
  frame.dims = impl_->dims;
  frame.spacing = impl_->spacing;
  frame.valueRange = impl_->valueRange;
  frame.volume = &*impl_->volumeTexture;
  frame.sliceVertexArray = impl_->sliceVertexArray.id();
  frame.screenVertexArray = impl_->screenVertexArray.id();
  frame.programs = &impl_->programs;
  frame.uniforms = &*impl_->uniforms;
  frame.gradients = &impl_->gradients;
  frame.volumeGeneration = impl_->volumeGeneration;
  frame.slab = slab;
  const ResolvedOptions resolved = technique.resolve(frame);
  result.background =
      settings.background.value_or(resolved.background.value_or(kDefaultBackground));
  frame.background = result.background;
  result.options.update(resolved.details);
  if (!impl_->emptySpace) impl_->emptySpace.emplace();
  impl_->emptySpace->prepare(*impl_->brickRanges, technique.occupancy(frame), result.view,
                             settings.emptySpaceSkipping, technique.alsoOccupied(frame));
  frame.emptySpace = &*impl_->emptySpace;

  // A relayed frame (Composition::Relay, slab.h): the processes take turns in the view's depth
  // order, each continuing every sweep from the targets of the slab in front, so that each pixel
  // blends the single process's samples in its order; the last slab's targets go to all.
  const bool relayed = slab && info.composition == Composition::Relay;
  if (relayed) {
    if (slab->relay == nullptr) throw std::logic_error("Renderer: a slab without a relay");
    slab->relay->orderByDepth(frameZDirection(result.view));
  }
  // The relay's time in this frame (slab.h SlabRelay::busyMs), for timings.combine.
  const double relayBefore = slab && slab->relay ? slab->relay->busyMs() : 0.0;
  technique.beginFrame(frame);
  const int sweeps = technique.sweepCount(frame);
  for (frame.sweep = 0; frame.sweep < sweeps; ++frame.sweep) {
    technique.beginSweep(frame);
    if (relayed) {
      slab->relay->receive(technique.relayTargets(frame));
      if (const gl::RenderTarget* dead = technique.relayDeadMarks(frame)) {
        slab->relay->receiveDepthStencil(*dead);
      }
    }
    for (const SliceContext& slice : slices) {
      impl_->uniforms->bindSlice(slice.index);
      technique.drawSlice(frame, slice);
    }
    if (relayed) {
      VSIL_GL(glFinish());  // the slab's own draws end here, not in the relay's read-back
      const std::vector<const gl::RenderTarget*> targets = technique.relayTargets(frame);
      slab->relay->send(targets);
      if (const gl::RenderTarget* dead = technique.relayDeadMarks(frame)) {
        slab->relay->sendDepthStencil(*dead);
      }
      slab->relay->shareLast(targets);
    }
  }
  frame.sweep = sweeps - 1;
  double relayInCombine = 0;
  if (slab && !relayed) {
    if (slab->relay == nullptr) throw std::logic_error("Renderer: a slab without a relay");
    // The slab's own slicing ends here: llvmpipe runs the queued draws at the first read-back,
    // which would otherwise count as combining.
    VSIL_GL(glFinish());
    const double relayAtCombine = slab->relay->busyMs();
    StageClock combineClock;
    technique.combineSlabs(frame, *slab->relay);
    result.timings.combine = combineClock.elapsed();
    relayInCombine = slab->relay->busyMs() - relayAtCombine;
  }
  technique.endFrame(frame);
  VSIL_GL(glFinish());
  if (slab) {
    // The relay's calls outside combineSlabs (a relay technique receives before its slices).
    result.timings.combine.wallMs += slab->relay->busyMs() - relayBefore - relayInCombine;
  }
  result.timings.programs = gl::programBuildTime() - programsBefore;
  result.timings.render = clock.lap() - result.timings.programs - result.timings.combine;

  result.frame = technique.readBack(frame);
  result.timings.readback = clock.lap();
  gl::checkGlError("Renderer::render", __FILE__, __LINE__);
  return result;
}

}  // namespace vsil
