#pragma once
// semantic: Rautek, Bruckner & Gröller, interaction-dependent semantics (EuroVis 2008). A fuzzy
// rule base (core/rules.h; --rules) maps data and interaction sources (the cursor, a plane, the
// image-space cursor, the view angle, time) to style weights and values; the rule compiler
// (rule_compiler.h) turns it into GLSL that the slice shader's template (semantic.frag) calls
// per sample. Styles are lit-sphere ramps (sphere_atlas.h) layered by priority; the samples are
// composited front to back (compositing.h: opacity correction, early ray termination,
// empty-space skipping from what the rules can make visible).
//
// The flat rendering mode (--flatness, or rules whose consequent is the flatness): per pixel the
// highest priority met so far is kept beside the colour, both updated in place by the slice pass
// (image load/store, a memory barrier between slices); on entering a region of higher priority
// the colour so far is scaled by 1 − p_f. There, early ray termination retires a pixel only once
// it is opaque and has met the top priority (the shader leaves first), since a higher priority
// behind an opaque pixel still shows.
//
// One program per rule base (and mode), cached by its text: changing a membership function, a
// priority, a sphere ramp or the interaction inputs uploads textures and uniforms only.
#include <optional>
#include <string>

#include "slicing/compositing.h"
#include "slicing/gradient_texture.h"
#include "slicing/technique_table.h"
#include "slicing/techniques/semantic/semantic_scene.h"

namespace vsil {

TechniqueInfo semanticTechniqueInfo();

// The program for a compiled rule base and mode.
gl::ProgramSpec semanticProgram(const CompiledRules& compiled, bool flat, bool planeShow,
                                const GradientTexture& gradients);

class SemanticTechnique : public Technique {
 public:
  ResolvedOptions resolve(const FrameContext& frame) override;
  BrickOccupancy occupancy(const FrameContext& frame) const override;
  void beginFrame(const FrameContext& frame) override;
  void drawSlice(const FrameContext& frame, const SliceContext& slice) override;
  void endFrame(const FrameContext&) override {}
  FrameBuffers readBack(const FrameContext& frame) override;
  // Across ranks (slab.h): the accumulated colour (flat mode: with the priorities) and the
  // retired pixels travel in depth order.
  std::vector<const gl::RenderTarget*> relayTargets(const FrameContext&) const override {
    if (flat_) return {&flatTargets_->color, &flatTargets_->priority};
    return {&compositor_.target()};
  }
  const gl::RenderTarget* relayDeadMarks(const FrameContext&) const override {
    return flat_ ? &flatTargets_->color : &compositor_.target();
  }

 private:
  void uploadTables();
  void setUniforms(const FrameContext& frame);

  RuleBase rules_;
  CompiledRules compiled_;
  SemanticInteraction interaction_;
  bool flat_ = false;
  std::vector<std::uint8_t> visible_;  // visibleDataIntervals
  gl::Program* program_ = nullptr;

  // Tables and atlas, rebuilt only when what they hold changes (keys: the functions' texts).
  std::string membershipKey_, defuzzKey_, atlasKey_;
  MembershipTables membership_;
  std::optional<SphereAtlas> atlas_;
  gl::TextureName membershipTexture_, defuzzTexture_, atlasTexture_, visibleTexture_;

  FrontToBackCompositor compositor_;
  struct FlatTargets {
    gl::RenderTarget color;     // RGBA32F premultiplied, with the depth-stencil buffer
    gl::RenderTarget priority;  // R32F: the highest priority met so far
    gl::EmptyFramebuffer draw;  // the depth buffer alone: slice passes write images only
  };
  std::optional<FlatTargets> flatTargets_;
};

}  // namespace vsil
