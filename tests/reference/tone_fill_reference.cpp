#include "tone_fill_reference.h"

#include <limits>

#include "slice_sampler.h"
#include "slicing/illustration_options.h"
#include "slicing/tone_fill.h"

namespace vsil::reference {

ToneFillReference::ToneFillReference(const RenderSettings& settings, const ReferenceSetup& setup) {
  if (!settings.toneFill) return;
  illustration_ = toneFillIllustration(setup.options);
  color_ = settings.toneFill->rgb01();
  const Rgba background = settings.background.value_or(kDefaultBackground);
  formulas_.emplace(IllustrationFormulas{illustration_, {}, glm::vec3(0.0f), background.rgb01()});
  for (const Light& light : illustration_.lights) {
    formulas_->lights.emplace_back(light.directionEye());  // eye space
  }
}

glm::vec3 ToneFillReference::at(const SliceSampler& sampler, int x, int y, float eyeDistance,
                                float depth) const {
  const glm::vec3 eye = sampler.eyePoint(x, y, eyeDistance);
  const glm::vec3 n = sampler.outwardNormalEye(quantizedVoxel(sampler.voxelFromEyePoint(eye)));
  const IllustrationFormulas& f = *formulas_;
  return f.distance(f.tone(f.lit(color_, n), color_, n), depth);
}

cv::Mat3f ToneFillReference::emptyImage(glm::ivec2 size) const {
  if (!active()) return {};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  return cv::Mat3f(size.y, size.x, cv::Vec3f(nan, nan, nan));
}

}  // namespace vsil::reference
