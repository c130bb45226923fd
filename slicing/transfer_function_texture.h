#pragma once
// A transfer function (core/transfer_function.h) as a 1D RGBA32F texture over the volume's
// value range, linear filtering, clamped: entry i holds the function at
// min + i·(max − min)/(kEntries − 1), and a sample value maps to its texture coordinate by
// one multiply-add (coordinateFromValue). Shared by the techniques that classify samples
// (illustrate; mip and semantic next); TextureUnit::TransferFunction is its unit.
#include <vector>

#include <glm/glm.hpp>

#include "core/transfer_function.h"
#include "core/volume.h"
#include "slicing/gl_objects.h"

namespace vsil {

class TransferFunctionTexture {
 public:
  static constexpr int kEntries = 4096;

  TransferFunctionTexture();
  // Uploads the table of `tf` over `range` (kEntries entries, TransferFunction::table).
  void upload(const TransferFunction& tf, ValueRange range);
  GLuint id() const { return texture_.id(); }
  const std::vector<glm::vec4>& table() const { return table_; }

  // (x, y) with texture coordinate = value·x + y: the value range's ends at the first and the
  // last entry's centre.
  static glm::vec2 coordinateFromValue(ValueRange range);
  // Whether any entry a value in [low, high] may interpolate between has an opacity above 0.
  static bool opaqueSomewhere(const std::vector<glm::vec4>& table, ValueRange range, float low,
                              float high);

 private:
  gl::TextureName texture_;
  std::vector<glm::vec4> table_;
};

}  // namespace vsil
