#include "slice_sampler.h"

#include <algorithm>
#include <cmath>

namespace vsil::reference {

std::vector<float> textureTexels(const Volume& volume) {
  return volume.visit(
      [](auto samples) { return std::vector<float>(samples.begin(), samples.end()); });
}

glm::vec4 sampleGradientTexels(const GradientTexels& texels, glm::vec3 tex) {
  const LinearTaps tx = linearTaps(tex.x, texels.dims.x), ty = linearTaps(tex.y, texels.dims.y),
                   tz = linearTaps(tex.z, texels.dims.z);
  glm::vec4 result(0.0f);
  for (int dz = 0; dz < 2; ++dz) {
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        const float w = (dx ? tx.f : 1 - tx.f) * (dy ? ty.f : 1 - ty.f) * (dz ? tz.f : 1 - tz.f);
        result += w * texels.at(dx ? tx.i1 : tx.i0, dy ? ty.i1 : ty.i0, dz ? tz.i1 : tz.i0);
      }
    }
  }
  return result;
}

LinearTaps linearTaps(float u, int n) {
  const float t = u * float(n) - 0.5f;
  const float base = std::floor(t);
  const int i = int(base);
  return {std::clamp(i, 0, n - 1), std::clamp(i + 1, 0, n - 1), t - base};
}

glm::vec4 sampleTable(const std::vector<glm::vec4>& table, float u) {
  const LinearTaps t = linearTaps(u, int(table.size()));
  return table[std::size_t(t.i0)] * (1 - t.f) + table[std::size_t(t.i1)] * t.f;
}

SliceSampler::SliceSampler(const Volume& volume, const View& view)
    : volume_(volume),
      view_(view),
      voxelFromEye_(glm::inverse(view.eyeFromVoxel)),
      eyeFromVoxelGradient_(glm::transpose(glm::inverse(glm::dmat3(view.eyeFromVoxel)))),
      viewportSize_(view.viewport),
      halfExtent_(view.halfExtent),
      dims_(volume.dims) {}

glm::vec2 SliceSampler::fragmentNdc(int x, int y) const {
  // gl_FragCoord has its origin at the bottom-left.
  const glm::vec2 fragCoord(float(x) + 0.5f, float(view_.viewport.y - 1 - y) + 0.5f);
  return fragCoord / viewportSize_ * 2.0f - 1.0f;
}

glm::vec3 SliceSampler::eyePoint(int x, int y, float eyeDistance) const {
  const glm::vec2 ndc = fragmentNdc(x, y);
  const float scale = view_.orthographic ? 1.0f : eyeDistance;
  const glm::vec2 xy = ndc * halfExtent_ * scale;
  return {xy.x, xy.y, -eyeDistance};
}

glm::vec3 SliceSampler::voxelFromEyePoint(glm::vec3 eye) const {
  return glm::vec3(voxelFromEye_ * glm::vec4(eye, 1.0f));
}

glm::vec3 SliceSampler::sliceTexCoord(int x, int y, const SliceTexCoords& slice) const {
  const glm::vec2 ndc = fragmentNdc(x, y);
  return ndc.x * slice.perNdcX + ndc.y * slice.perNdcY + slice.atNdcOrigin;
}

bool SliceSampler::insideTexture(glm::vec3 tex) const {
  return glm::all(glm::greaterThanEqual(tex, glm::vec3(0.0f))) &&
         glm::all(glm::lessThanEqual(tex, glm::vec3(1.0f)));
}

float SliceSampler::sample(glm::vec3 voxel) const {
  // OpenGL: texture coordinate u = (voxel + 0.5) / dims.
  return sampleTexture((voxel + 0.5f) / dims_);
}

float SliceSampler::sampleTexture(glm::vec3 u) const {
  // OpenGL: texel space u * dims - 0.5, clamped to the edge.
  const glm::vec3 t = u * dims_ - 0.5f;
  const glm::vec3 base = glm::floor(t);
  const glm::vec3 f = t - base;
  auto at = [&](int x, int y, int z) {
    x = std::clamp(x, 0, volume_.dims.x - 1);
    y = std::clamp(y, 0, volume_.dims.y - 1);
    z = std::clamp(z, 0, volume_.dims.z - 1);
    return volume_.at(x, y, z);
  };
  const int x0 = int(base.x), y0 = int(base.y), z0 = int(base.z);
  float result = 0.0f;
  for (int dz = 0; dz < 2; ++dz) {
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        const float w = (dx ? f.x : 1 - f.x) * (dy ? f.y : 1 - f.y) * (dz ? f.z : 1 - f.z);
        result += w * at(x0 + dx, y0 + dy, z0 + dz);
      }
    }
  }
  return result;
}

glm::vec3 SliceSampler::gradientVoxel(glm::vec3 voxel) const {
  return glm::vec3(sample(voxel + glm::vec3(1, 0, 0)) - sample(voxel - glm::vec3(1, 0, 0)),
                   sample(voxel + glm::vec3(0, 1, 0)) - sample(voxel - glm::vec3(0, 1, 0)),
                   sample(voxel + glm::vec3(0, 0, 1)) - sample(voxel - glm::vec3(0, 0, 1))) *
         0.5f;
}

glm::vec3 SliceSampler::outwardNormalEye(glm::vec3 voxel) const {
  const glm::vec3 gradientEye = eyeFromVoxelGradient_ * gradientVoxel(voxel);
  const float length2 = glm::dot(gradientEye, gradientEye);
  return length2 > 0.0f ? -gradientEye / std::sqrt(length2) : glm::vec3(0.0f);
}

float SliceSampler::facingRatio(glm::vec3 voxel, glm::vec3 eye) const {
  const glm::vec3 n = outwardNormalEye(voxel);
  if (n == glm::vec3(0.0f)) return 1.0f;
  const glm::vec3 toEye = view_.orthographic ? glm::vec3(0, 0, 1) : -glm::normalize(eye);
  return std::abs(glm::dot(n, toEye));
}

}  // namespace vsil::reference
