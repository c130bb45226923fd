#include "slicing/tone_fill.h"

#include <algorithm>
#include <limits>
#include <variant>

#include "slicing/gl_state.h"
#include "slicing/hit_records.h"
#include "slicing/illustration_options.h"
#include "slicing/texture_units.h"

namespace vsil {

const std::vector<std::string>& toneFillParameterNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> found;
    for (const ParameterSpec& spec : illustrationParameters()) {
      const bool lit = spec.name == "k_a" || spec.name == "k_d";  // I_G
      if (lit || spec.effect == Effect::Tone || spec.effect == Effect::Distance) {
        found.push_back(spec.name);
      }
    }
    return found;
  }();
  return names;
}

std::vector<OptionSpec> toneFillOptions() {
  // The same flags as illustrate's (one flag means the same for every technique); the names
  // --param takes are limited by checkToneFillValues.
  return {parameterOption(), lightOption()};
}

void checkToneFillValues(const OptionValues& given) {
  const auto param = given.find("param");
  if (param == given.end()) return;
  ParameterValues ignored;
  for (const auto& text : std::get<std::vector<std::string>>(param->second)) {
    parseParameterList(text, "--param", toneFillParameterNames(), "--fill tone", ignored);
  }
}

std::vector<OptionSpec> withToneFillOptions(std::vector<OptionSpec> own) {
  for (OptionSpec& spec : toneFillOptions()) own.push_back(std::move(spec));
  return own;
}

Illustration toneFillIllustration(const OptionReader& options) {
  IllustrationStyle defaults;
  defaults.parameters["k_ds"] = 0.0;
  return illustrationFromOptions(toneFillOptions(), options, defaults);
}

nlohmann::json ToneFill::resolve(const FrameContext& frame) {
  active_ = frame.settings->toneFill.has_value();
  if (!active_) return nlohmann::json::object();
  color_ = *frame.settings->toneFill;
  illustration_ = toneFillIllustration(*frame.options);
  nlohmann::json parameters = nlohmann::json::object();
  for (const auto& name : toneFillParameterNames()) parameters[name] = illustration_[name];
  nlohmann::json lights = nlohmann::json::array();
  for (const Light& light : illustration_.lights) {
    lights.push_back({light.azimuthDeg, light.elevationDeg});
  }
  return {{"tone_fill", {{"color", color_.hex()}, {"parameters", parameters}, {"lights", lights}}}};
}

void ToneFill::draw(const FrameContext& frame, const gl::RenderTarget& record) {
  if (!active_) return;
  const glm::ivec2 size = frame.view->viewport;
  if (!target_ || target_->size() != size) {
    target_.reset();
    target_.emplace(size, GL_RGBA32F);
  }
  std::vector<std::string> sources = hitRecordSources();
  sources.emplace_back("shaders/illustration.glsl");
  gl::Program& program = frame.programs->get(
      gl::screenPassProgram(sources, "shaders/tone_fill.frag", {lightCountDefine(illustration_)}));
  program.use();
  for (const auto& name : toneFillParameterNames()) {
    program.set(name.c_str(), float(illustration_[name]));
  }
  program.set("toneScale", float(1.0 / std::max(1.0, toneShadingPeak(illustration_))));
  std::vector<glm::vec3> lights;
  for (const Light& light : illustration_.lights) lights.emplace_back(light.directionEye());
  program.set("lightDirections", lights.data(), int(lights.size()));
  program.set("backgroundColor", frame.background.rgb01());
  program.set("fillColor", color_.rgb01());
  target_->bindForDrawing();
  gl::Capability noScissor(GL_SCISSOR_TEST, false);
  gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D, record.texture());
  // The hit's brick shades it (tone_fill.frag); across slabs, its slab's rank.
  relayScreenPass(frame, {&*target_}, [&] {
    target_->bindForDrawing();
    program.use();
    gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D, record.texture());
    drawScreenPerBrick(frame);
  });
}

void ToneFill::readBack(FrameBuffers& frame) const {
  if (!active_) return;
  const cv::Mat4f colour = readTargetFlipped(*target_, 4);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  frame.tone.create(colour.rows, colour.cols);
  for (int y = 0; y < colour.rows; ++y) {
    for (int x = 0; x < colour.cols; ++x) {
      const cv::Vec4f& c = colour(y, x);
      frame.tone(y, x) = frame.state(y, x) == std::uint8_t(PixelState::Filled)
                             ? cv::Vec3f(c[0], c[1], c[2])
                             : cv::Vec3f(nan, nan, nan);
    }
  }
}

}  // namespace vsil
