#pragma once
// The CPU twin of slicing/tone_fill.h (`--fill tone`) for the references of the techniques that
// return pixel states: the first hit's colour from the Ebert–Rheingans formulas written again
// (illustration_formulas.h), in eye space, at the point and with the normal the GL pass uses.
#include <optional>

#include <glm/glm.hpp>

#include "core/illustration.h"
#include "illustration_formulas.h"
#include "reference_frame.h"

namespace vsil::reference {

class SliceSampler;

class ToneFillReference {
 public:
  // Inactive unless `settings` ask for tone fill (RenderSettings::toneFill).
  ToneFillReference(const RenderSettings& settings, const ReferenceSetup& setup);
  ToneFillReference(const ToneFillReference&) = delete;  // the formulas refer to a member
  ToneFillReference& operator=(const ToneFillReference&) = delete;
  bool active() const { return formulas_.has_value(); }
  // The colour of pixel (x, y)'s first hit on the plane at `eyeDistance`, normalized depth
  // `depth`: straight RGB, not clamped.
  glm::vec3 at(const SliceSampler& sampler, int x, int y, float eyeDistance, float depth) const;
  // A NaN image of the frame's size for FrameBuffers::tone when active, else an empty one.
  cv::Mat3f emptyImage(glm::ivec2 size) const;

 private:
  Illustration illustration_;
  glm::vec3 color_{0.0f};
  std::optional<IllustrationFormulas> formulas_;
};

}  // namespace vsil::reference
