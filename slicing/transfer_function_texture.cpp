#include "slicing/transfer_function_texture.h"

#include <algorithm>
#include <cmath>

namespace vsil {

TransferFunctionTexture::TransferFunctionTexture() : texture_(gl::createTexture()) {
  VSIL_GL(glBindTexture(GL_TEXTURE_1D, texture_.id()));
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  VSIL_GL(glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, kEntries, 0, GL_RGBA, GL_FLOAT, nullptr));
  VSIL_GL(glBindTexture(GL_TEXTURE_1D, 0));
}

void TransferFunctionTexture::upload(const TransferFunction& tf, ValueRange range) {
  table_ = tf.table(range, kEntries);
  VSIL_GL(glBindTexture(GL_TEXTURE_1D, texture_.id()));
  VSIL_GL(glTexSubImage1D(GL_TEXTURE_1D, 0, 0, kEntries, GL_RGBA, GL_FLOAT, table_.data()));
  VSIL_GL(glBindTexture(GL_TEXTURE_1D, 0));
}

glm::vec2 TransferFunctionTexture::coordinateFromValue(ValueRange range) {
  const double n = kEntries;
  const double span = double(range.max) - double(range.min);
  if (!(span > 0)) return {0.0f, float(0.5 / n)};
  const double perValue = (n - 1.0) / (n * span);
  return {float(perValue), float(0.5 / n - double(range.min) * perValue)};
}

bool TransferFunctionTexture::opaqueSomewhere(const std::vector<glm::vec4>& table, ValueRange range,
                                              float low, float high) {
  const double span = double(range.max) - double(range.min);
  const int last = int(table.size()) - 1;
  const auto entry = [&](double value) {
    return span > 0 ? (value - double(range.min)) / span * last : 0.0;
  };
  // One entry of slack on each side for the rounding of the texture coordinate.
  const int first = std::clamp(int(std::floor(entry(low))) - 1, 0, last);
  const int end = std::clamp(int(std::ceil(entry(high))) + 1, 0, last);
  for (int i = first; i <= end; ++i) {
    if (table[std::size_t(i)].a > 0.0f) return true;
  }
  return false;
}

}  // namespace vsil
