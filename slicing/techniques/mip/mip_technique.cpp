#include "slicing/techniques/mip/mip_technique.h"

#include <limits>

#include "slicing/gl_state.h"
#include "slicing/illustration_options.h"
#include "slicing/slicer.h"
#include "slicing/techniques/mip/colour_sphere.h"
#include "slicing/techniques/mip/mip_options.h"
#include "slicing/techniques/mip/sphere_legend.h"
#include "slicing/texture_units.h"
#include "slicing/tile_march.h"

namespace vsil {

TechniqueInfo mipTechniqueInfo() {
  return {"mip",
          "maximum intensity projection through a grey window",
          {windowOption(), transferFunctionOption()},
          FrameOutputs{.state = false, .color = true, .depth = false},
          [] { return std::make_unique<MipTechnique>(false); },
          /*usesGradients=*/false,
          /*checkValues=*/checkWindowOrTf,
          /*needsOneTexture=*/{}};
}

// The colour sphere's options with its weight 0 and no legend drawing it change nothing (the
// depth options still shape --depth-out's hits at depth weight 0).
std::vector<std::string> ignoredDemipOptions(const OptionReader& options) {
  std::vector<std::string> ignored;
  if (options.number("sphere-weight") > 0 || options.enabled("legend")) return ignored;
  for (const char* name : {"sphere-map", "sphere-rotate", "sphere-frame"}) {
    if (options.given(name)) {
      ignored.push_back("--" + std::string(name) +
                        ": the colour sphere is off (--sphere-weight 0, no --legend); ignored");
    }
  }
  return ignored;
}

TechniqueInfo demipTechniqueInfo() {
  TechniqueInfo info{"demip",
                     "depth-enhanced MIP: the maximum shaded by the depth of the nearest sample "
                     "of its material, tinted by a colour sphere (Díaz & Vázquez)",
                     demipOptions(),
                     FrameOutputs{.state = false, .color = true, .depth = true},
                     [] { return std::make_unique<MipTechnique>(true); },
                     /*usesGradients=*/false,
                     /*checkValues=*/checkDemipValues,
                     /*needsOneTexture=*/{}};
  info.ignoredOptions = ignoredDemipOptions;
  return info;
}

ResolvedOptions resolveMipFamily(const OptionReader& options) {
  ResolvedOptions resolved;
  // Over black, as in the papers' figures: the window's low end and everything below it (air,
  // noise) is black like the background, so the background does not outline the noise.
  resolved.background = Rgba{0, 0, 0, 255};
  // The window used, given or derived, for the metadata; with --tf the function's points in
  // the data's values (a preset's are mapped per volume: where its ramp landed).
  if (const auto tf = mipTransferFunction(options)) {
    resolved.details["transfer_function"] = tf->toJson();
  } else {
    resolved.details["window"] = windowText(intensityWindow(options));
  }
  return resolved;
}

ResolvedOptions MipTechnique::resolve(const FrameContext& frame) {
  ResolvedOptions resolved = resolveMipFamily(*frame.options);
  if (!depthEnhanced_) return resolved;
  // A map file is read once per name, not once per frame (vsil animate, the bench). Before the
  // first frame the name is empty, which no valid --sphere-map is.
  const std::string sphereMap = frame.options->text("sphere-map");
  if (colourSphere_.name != sphereMap) {
    colourSphere_ = colourSphere(sphereMap);
    sphereMapUploaded_ = false;
  }
  if (const auto& image = colourSphere_.image) {
    resolved.details["sphere_map_file"] = {{"path", colourSphere_.name},
                                           {"size", {image->width, image->height}}};
  }
  return resolved;
}

BrickOccupancy MipTechnique::occupancy(const FrameContext& frame) const {
  // demip's second sweep looks for samples within eps of a shown maximum.
  const float eps = depthEnhanced_ ? float(frame.options->number("material-eps")) : 0.0f;
  const ValueRange range = frame.valueRange;
  if (const auto tf = mipTransferFunction(*frame.options)) {
    // A brick whose values are all transparent, with every value below them, cannot hold a
    // shown maximum, and a ray whose maximum it would hold shows nothing with it or without.
    return [table = tf->table(range, TransferFunctionTexture::kEntries), range,
            eps](ValueRange brick) {
      return TransferFunctionTexture::opaqueSomewhere(table, range, range.min, brick.max + eps);
    };
  }
  // mip shows only maxima above the window's low end; demip's second sweep needs the bricks
  // reaching low - eps.
  const IntensityWindow window = intensityWindow(*frame.options);
  return reachesIso(window.low - eps);
}

namespace {
// One invocation per pixel, as the first-hit march (hit_records.cpp): no pixel reads another's.
constexpr MarchShape kMaxMarchShape{{16, 16}, {16, 16}};
}  // namespace

bool MipTechnique::marches(const FrameContext& frame) {
  return frame.volume->brickCount() == 1 &&
         int(frame.plan->slices.size()) <= frame.uniforms->slicesPerRange();
}

int MipTechnique::sweepCount(const FrameContext& frame) const {
  return depthEnhanced_ && !marches(frame) ? 2 : 1;
}

void MipTechnique::beginFrame(const FrameContext& frame) {
  const glm::ivec2 size = frame.view->viewport;
  const bool marching = marches(frame);
  if (!targets_ || targets_->colour.size() != size || targets_->marching != marching) {
    targets_.reset();
    targets_.emplace(Targets{gl::RenderTarget(size, GL_RGBA32F),
                             marching ? gl::RenderTarget(size, GL_RGBA32F)
                                      : gl::RenderTarget(size, GL_R32F, /*withDepthStencil=*/true),
                             marching});
  }
  if (marching) return;  // the march runs after the (empty) sweep, in endFrame
  maximumPass_ = &frame.programs->get(
      gl::slicePassProgram({}, "techniques/mip/max_sample.frag", {kRaySamplingDefine}));
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  const GLfloat noSample[4] = {kNoSample, 0, 0, 0};
  targets_->values.bindForDrawing();
  VSIL_GL(glClearBufferfv(GL_COLOR, 0, noSample));
  frame.emptySpace->writeEntryDepth(glm::mat4(frame.view->clipFromVoxel()));
}

void MipTechnique::beginSweep(const FrameContext& frame) {
  if (frame.sweep != 1) return;
  hits_.beginFrame(frame, SlicingPipeline::Fast,
                   FirstHitRecorder::MaterialThreshold{
                       targets_->values.texture(), float(frame.options->number("material-eps"))});
}

void MipTechnique::march(const FrameContext& frame) {
  gl::Program& march =
      marchProgram(frame, {}, "techniques/mip/max_march.comp", kMaxMarchShape,
                   depthEnhanced_ ? std::vector<std::string>{"DEMIP"} : std::vector<std::string>{});
  march.use();
  march.set("noSample", kNoSample);
  if (depthEnhanced_) {
    march.set("materialEps", float(frame.options->number("material-eps")));
  }
  runMarch(frame, march, kMaxMarchShape, targets_->values);
}

void MipTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  if (marches(frame)) return;
  if (frame.sweep == 1) {
    hits_.drawSlice(frame, slice);
    return;
  }
  if (slice.vertexCount == 0) return;
  targets_->values.bindForDrawing();
  gl::DepthTest skipEmpty(GL_GREATER, /*write=*/false);
  gl::Blending keepMaximum(GL_MAX, GL_ONE, GL_ONE);
  maximumPass_->use();
  drawSlicePolygon(frame, slice);
}

gl::Program& useMipFinish(const FrameContext& frame, std::vector<std::string> defines,
                          GLuint values, const gl::RenderTarget& colour,
                          std::optional<TransferFunctionTexture>& transferTable) {
  const std::optional<TransferFunction> tf = mipTransferFunction(*frame.options);
  if (tf) defines.emplace_back("TRANSFER_TABLE");
  gl::Program& finish =
      frame.programs->get(gl::screenPassProgram({}, "techniques/mip/mip_finish.frag", defines));
  colour.bindForDrawing();
  finish.use();
  if (tf) {
    if (!transferTable) transferTable.emplace();
    transferTable->upload(*tf, frame.valueRange);
    gl::bindTexture(gl::TextureUnit::TransferFunction, GL_TEXTURE_1D, transferTable->id());
    finish.set("tableCoordFromValue",
               TransferFunctionTexture::coordinateFromValue(frame.valueRange));
  } else {
    const IntensityWindow window = intensityWindow(*frame.options);
    finish.set("window", glm::vec2(window.low, window.high));
  }
  gl::bindTexture(gl::TextureUnit::Auxiliary0, GL_TEXTURE_2D, values);
  return finish;
}

FrameBuffers colourWithDepth(const gl::RenderTarget& colour, const gl::RenderTarget& record,
                             int depthChannel,
                             const std::function<bool(const cv::Vec4f&)>& hasDepth,
                             bool readDepth) {
  FrameBuffers frame;
  frame.color = readTargetFlipped(colour, 4);
  if (!readDepth) return frame;
  const float none = std::numeric_limits<float>::quiet_NaN();
  if (!hasDepth) {
    // Only the depth channel: every shown pixel has one.
    frame.depth = readChannelFlipped(record, depthChannel);
    for (int y = 0; y < frame.depth.rows; ++y) {
      for (int x = 0; x < frame.depth.cols; ++x) {
        if (!(frame.color(y, x)[3] > 0.0f)) frame.depth(y, x) = none;
      }
    }
    return frame;
  }
  const cv::Mat records = readTargetFlipped(record, 4);
  frame.depth.create(records.rows, records.cols);
  for (int y = 0; y < records.rows; ++y) {
    for (int x = 0; x < records.cols; ++x) {
      const cv::Vec4f& r = records.at<cv::Vec4f>(y, x);
      const bool shown = frame.color(y, x)[3] > 0.0f;
      frame.depth(y, x) = shown && hasDepth(r) ? r[depthChannel] : none;
    }
  }
  return frame;
}

void MipTechnique::combineSlabs(const FrameContext& frame, SlabRelay& relay) {
  if (depthEnhanced_ || marches(frame)) {
    Technique::combineSlabs(frame, relay);
    return;
  }
  relay.maxReduce(targets_->values);
}

void MipTechnique::endFrame(const FrameContext& frame) {
  const OptionReader& options = *frame.options;
  const bool marching = marches(frame);
  if (marching) march(frame);
  // The march's record holds the maximum (.r) and the hit (.g, .b) where the passes per slice
  // leave them in two targets.
  const GLuint values = targets_->values.texture();
  const GLuint hitRecord = marching ? targets_->values.texture() : hits_.record().texture();
  std::vector<std::string> defines;
  const bool withSphere = depthEnhanced_ && options.number("sphere-weight") > 0;
  if (depthEnhanced_) {
    defines.push_back("DEMIP");
    const DepthMode mode = depthMode(options);
    if (mode == DepthMode::Steps) defines.push_back("DEPTH_STEPS");
    if (mode == DepthMode::EntryPlusSteps) defines.push_back("DEPTH_ENTRY_PLUS_STEPS");
    if (withSphere) defines.push_back("COLOUR_SPHERE");
    if (withSphere && colourSphere_.image) {
      defines.push_back("SPHERE_MAP_IMAGE");
      if (!sphereMapUploaded_) uploadSphereMap();
    }
  }
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  gl::Program& finish = useMipFinish(frame, defines, values, targets_->colour, transferTable_);
  if (depthEnhanced_) {
    const View& view = *frame.view;
    finish.set("depthWeight", float(options.number("depth-weight")));
    if (withSphere) {
      finish.set("sphereWeight", float(options.number("sphere-weight")));
      if (colourSphere_.image) {
        finish.set("sphereFromEye", glm::transpose(sphereFrameEye(options, view)));
        gl::bindTexture(gl::TextureUnit::Auxiliary1, GL_TEXTURE_2D, sphereMapTexture_.id());
      } else {
        finish.set("sphereFrontEye", sphereFrontEye(options, view));
        finish.set("sphereFrontColour", colourSphere_.front);
        finish.set("sphereBackColour", colourSphere_.back);
      }
      finish.set("volumeCentreEye", glm::vec3(view.eyeFromWorld * glm::dvec4(0, 0, 0, 1)));
    }
    finish.set("depthRangeEye", glm::vec2(float(view.nearEye), float(view.farEye)));
    gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D, hitRecord);
  }
  drawScreen(frame);
}

void MipTechnique::uploadSphereMap() {
  const SphereMapImage& image = *colourSphere_.image;
  if (!sphereMapTexture_) sphereMapTexture_ = gl::createTexture();
  VSIL_GL(glBindTexture(GL_TEXTURE_2D, sphereMapTexture_.id()));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);         // longitude goes round
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);  // latitude ends
  VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 4));
  // Rows top-down as the image stores them: texture coordinate v = 0 is the top row.
  VSIL_GL(glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, image.width, image.height, 0, GL_RGB, GL_FLOAT,
                       image.texels.data()));
  VSIL_GL(glBindTexture(GL_TEXTURE_2D, 0));
  sphereMapUploaded_ = true;
}

FrameBuffers MipTechnique::readBack(const FrameContext& frame) {
  if (!depthEnhanced_) {
    FrameBuffers frame;
    frame.color = readTargetFlipped(targets_->colour, 4);
    return frame;
  }
  // Every shown pixel has its hit: its maximum's own sample qualifies.
  FrameBuffers result =
      colourWithDepth(targets_->colour, marches(frame) ? targets_->values : hits_.record(), 1, {},
                      frame.settings->readDepth);
  const OptionReader& options = *frame.options;
  if (options.enabled("legend")) {
    drawSphereLegend(result.color, colourSphere_, sphereFrameEye(options, *frame.view));
  }
  return result;
}

}  // namespace vsil
