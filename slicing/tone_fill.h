#pragma once
// `--fill tone` for the techniques that return pixel states (silhouette, rightangle): after the
// last slice one screen pass (shaders/tone_fill.frag) colours each pixel's first iso-surface hit
// with Ebert–Rheingans tone shading and distance colour blending, the formulas of
// shaders/illustration.glsl that illustrate applies per sample:
//   I = (k_ta·I_G + Σ_lights (t·(k_ty, k_ty, 0) + (1 − t)·(0, 0, k_tb) + k_td·c_o·max(n·L, 0)))
//       / max(1, P),
//   c = (1 − k_ds·d^k_de)·I + k_ds·d^k_de·c_b,
// with I_G = c_o·(k_a + k_d·Σ max(n·L, 0)), t = (1 + n·L)/2, P the sum's peak for a white
// object (core/illustration.h toneShadingPeak: I stays within [0, 1]), c_o the fill colour
// (RenderSettings::toneFill), n the outward normal at the hit (common.glsl outwardNormalEye: the
// gradient `--fill shaded` takes its |n·v| from), d the hit's normalized depth, c_b the frame's
// background. Parameters come from --param with the paper's names (only these eight), lights
// from --light, both declared by the technique (toneFillOptions); toneFillIllustration's
// defaults otherwise. The pass runs only when the render asks for tone fill.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/illustration.h"
#include "core/options.h"
#include "slicing/technique.h"

namespace vsil {

// The parameters the tone fill reads: tone shading's, distance blending's and the lit colour's.
const std::vector<std::string>& toneFillParameterNames();

// --param and --light, for the techniques that offer tone fill.
std::vector<OptionSpec> toneFillOptions();
// Their TechniqueInfo::checkValues: --param takes only toneFillParameterNames(); InputError
// "--param: 'k_gc' is not a parameter of --fill tone (known: ...)".
void checkToneFillValues(const OptionValues& given);
// A technique's own options followed by toneFillOptions().
std::vector<OptionSpec> withToneFillOptions(std::vector<OptionSpec> own);
// The tone fill's parameters and lights from --param and --light: illustrate's defaults, except
// k_ds = 0 (distance blending off until asked for: at illustrate's k_ds = 1, k_de = 0.5 an
// iso-surface a third of the way in is blended 58 % towards the background and its tones fade).
Illustration toneFillIllustration(const OptionReader& options);

class ToneFill {
 public:
  // Reads --param and --light when the frame asks for tone fill (FrameContext::settings
  // toneFill); what the metadata records ("tone_fill": colour, parameters, lights), else nothing.
  nlohmann::json resolve(const FrameContext& frame);
  bool active() const { return active_; }
  // After the last slice, when active: shades every pixel with a hit in `record` (RGBA32F,
  // shaders/hit_records.glsl: state, depth, first-hit eye distance) into its own target.
  void draw(const FrameContext& frame, const gl::RenderTarget& record);
  // When active: FrameBuffers::tone at the frame's Filled pixels (its state image), NaN elsewhere.
  void readBack(FrameBuffers& frame) const;

 private:
  bool active_ = false;
  Rgba color_;
  Illustration illustration_;
  std::optional<gl::RenderTarget> target_;  // RGBA32F (r, g, b, 1) at hits
};

}  // namespace vsil
