#include "slicing/techniques/rightangle/rightangle_technique.h"

namespace vsil {

TechniqueInfo rightAngleTechniqueInfo() {
  return {"rightangle",
          "the right-angle line test on the first iso-surface hit (RA, the Nagy–Klein baseline)",
          withToneFillOptions(
              {isoOption(),
               OptionSpec::number("ra-exponent", 8.0,
                                  "exponent k of the line test (1 - |n.v|)^k > threshold")
                   .above(0)
                   .atMost(1000),  // beyond, (1 - |n.v|)^k underflows: no line anywhere
               // The pair only sets the largest |n.v| drawn, c = 1 - threshold^(1/k): 0.33 with
               // the defaults (0.04^(1/8) = 0.669). Where the surface's radial curvature radius is
               // r pixels, |n.v| < c holds in a band about r·c²/2 px wide inside the outline: a
               // line continuous for r >= ~9 px (band >= ~0.5 px; the first hit lies up to a
               // slice behind the surface, where n is nearer the perpendicular) and at most
               // ~3 px wide up to r = 6/c² = 54 px. The old 0.3 drew |n.v| < 0.14: dashed below
               // r = 50 px (the analytic torus). README "Right-angle line width".
               OptionSpec::number("ra-threshold", 0.04,
                                  "a first hit is a line pixel where (1 - |n.v|)^k exceeds this "
                                  "(the defaults draw |n.v| < 0.33)")
                   .atLeast(0)  // below 0 every hit is a line,
                   .below(1),   // from 1 on none is
               pipelineOption(SlicingPipeline::Tiles)}),
          FrameOutputs{.state = true, .color = false, .depth = true},
          [] { return std::make_unique<RightAngleTechnique>(); },
          /*usesGradients=*/false,
          /*checkValues=*/checkToneFillValues,
          /*needsOneTexture=*/tilesNeedOneTexture};
}

ResolvedOptions RightAngleTechnique::resolve(const FrameContext& frame) {
  ResolvedOptions resolved;
  resolved.details = toneFill_.resolve(frame);
  return resolved;
}

BrickOccupancy RightAngleTechnique::occupancy(const FrameContext& frame) const {
  return reachesIso(float(frame.options->number("iso")));
}

void RightAngleTechnique::beginFrame(const FrameContext& frame) {
  if (!finished_ || finished_->size() != frame.view->viewport) {
    finished_.reset();
    finished_.emplace(frame.view->viewport, GL_RGBA32F);
  }
  finish_ = &finishProgram(frame, {"techniques/rightangle/rightangle.glsl"});
  finish_->use();
  finish_->set("rightAngleExponent", float(frame.options->number("ra-exponent")));
  finish_->set("rightAngleThreshold", float(frame.options->number("ra-threshold")));
  // A slab's default is fast (technique_table.h optionsForSlab).
  hits_.beginFrame(frame, pipelineOf(*frame.options));
}

void RightAngleTechnique::drawSlice(const FrameContext& frame, const SliceContext& slice) {
  hits_.drawSlice(frame, slice);
}

void RightAngleTechnique::endFrame(const FrameContext& frame) {
  hits_.endSlices(frame);
  relayScreenPass(frame, {&*finished_},
                  [&] { finishRecords(frame, *finish_, hits_.record(), *finished_); });
  toneFill_.draw(frame, hits_.record());
}

FrameBuffers RightAngleTechnique::readBack(const FrameContext&) {
  FrameBuffers frame = frameFromStateImage(readTargetFlipped(*finished_, 4));
  toneFill_.readBack(frame);
  return frame;
}

}  // namespace vsil
