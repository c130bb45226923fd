#pragma once
// The lit-sphere ramps of technique `semantic`'s styles (Bruckner & Gröller's style transfer
// functions, as Rautek et al. use them): per style a strip of images of shaded spheres, the
// style's parameter in [0, 1] running along the strip, the eye-space normal indexing each sphere.
// Built in: gray, ivory, skin, red, green, blue — kBuiltinSpheres spheres shaded from the base
// colour by one light from the upper left, from transparent (the first) to opaque (the last).
// A .png strip holds N square spheres side by side (read with OpenCV; grey, RGB or RGBA, 8 or
// 16 bit), its alpha the opacity per voxel.
//
// All styles' spheres go into one RGBA32F 3D texture, one sphere per layer, each resampled to
// kSphereCell² texels; the shader reads it with GL_LINEAR at
//   (0.5 + 0.5·n_eye.x, 0.5 + 0.5·n_eye.y, (firstLayer + t·(count − 1) + 0.5) / depth),
// so one lookup blends the two spheres around t and the texels around the normal. No GL here:
// the CPU reference samples the same texels.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/rules.h"

namespace vsil {

inline constexpr int kSphereCell = 64;
inline constexpr int kBuiltinSpheres = 8;
inline constexpr int kMaxSpheresPerStrip = 64;

struct SphereAtlas {
  int cell = kSphereCell;
  int depth = 0;                 // layers: the spheres of every style
  std::vector<int> firstLayer;   // per style
  std::vector<int> sphereCount;  // per style
  // cell × cell × depth straight RGBA in [0, 1], x fastest, rows bottom-up (GL's order: row
  // cell − 1 is the top of the image, where n_eye.y = 1).
  std::vector<glm::vec4> texels;

  const glm::vec4& at(int x, int y, int layer) const {
    return texels[(std::size_t(layer) * std::size_t(cell) + std::size_t(y)) * std::size_t(cell) +
                  std::size_t(x)];
  }
};

// The base colour of a built-in ramp (sRGB in [0, 1]); throws std::out_of_range for others.
glm::vec3 builtinSphereColor(const std::string& name);

// The spheres of one ramp, each cell × cell (rows bottom-up). A file that cannot be read or is
// no strip of square spheres: InputError "FILE: ..." naming `where` (the rule file's position).
std::vector<std::vector<glm::vec4>> sphereRamp(const Spheres& spheres, const std::string& where,
                                               int cell = kSphereCell);

SphereAtlas buildSphereAtlas(const RuleBase& rules, int cell = kSphereCell);

}  // namespace vsil
