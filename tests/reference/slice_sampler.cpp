#include "slice_sampler.h"

#include <algorithm>
#include <cmath>

namespace vsil::reference {

std::vector<float> textureTexels(const Volume& volume) {
  return volume.visit(
      [](auto samples) { return std::vector<float>(samples.begin(), samples.end()); });
}

glm::vec3 quantizedVoxel(glm::vec3 voxel) {
  return glm::floor(voxel * 1024.0f + 0.5f) * (1.0f / 1024.0f);
}

namespace {
// The taps of a quantized voxel position along an axis of n voxels: floor and fraction of the
// position, clamped to the edge.
LinearTaps voxelTaps(float voxel, int n) {
  const float base = std::floor(voxel);
  const int i = int(base);
  return {std::clamp(i, 0, n - 1), std::clamp(i + 1, 0, n - 1), voxel - base};
}
}  // namespace

glm::vec4 sampleGradientTexels(const GradientTexels& texels, glm::vec3 voxel) {
  const LinearTaps tx = voxelTaps(voxel.x, texels.dims.x), ty = voxelTaps(voxel.y, texels.dims.y),
                   tz = voxelTaps(voxel.z, texels.dims.z);
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

SplitGradient splitGradient(glm::vec4 texel) {
  const glm::vec3 g(texel);
  const float length2 = glm::dot(g, g);
  if (!(length2 > 0)) return {};
  const float inverseLength = 1.0f / std::sqrt(length2);
  return {g * inverseLength, std::min(length2 * inverseLength, 1.0f), true};
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

glm::vec2 SliceSampler::fragCoord(int x, int y) const {
  // gl_FragCoord has its origin at the bottom-left.
  return {float(x) + 0.5f, float(view_.viewport.y - 1 - y) + 0.5f};
}

glm::vec2 SliceSampler::fragmentNdc(int x, int y) const {
  return fragCoord(x, y) / viewportSize_ * 2.0f - 1.0f;
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

glm::vec3 SliceSampler::sliceVoxel(int x, int y, const SliceVoxelCoords& slice) const {
  const glm::vec2 ndc = fragmentNdc(x, y);
  return quantizedVoxel(ndc.x * slice.perNdcX + ndc.y * slice.perNdcY + slice.atNdcOrigin);
}

VoxelCandidates SliceSampler::sliceVoxelCandidates(int x, int y,
                                                   const SliceVoxelCoords& slice) const {
  const glm::vec2 ndc = fragmentNdc(x, y);
  const glm::vec3 a = ndc.x * slice.perNdcX, b = ndc.y * slice.perNdcY;
  return candidatesNear(a + b + slice.atNdcOrigin,
                        glm::abs(a) + glm::abs(b) + glm::abs(slice.atNdcOrigin));
}

VoxelCandidates SliceSampler::rayVoxelCandidates(int x, int y, const PixelRays& rays, int k) const {
  const glm::vec2 w = fragCoord(x, y);  // pixelCentre in a march
  const glm::vec3 ox = w.x * rays.originPerWindowX, oy = w.y * rays.originPerWindowY;
  const glm::vec3 dx = w.x * rays.directionPerWindowX, dy = w.y * rays.directionPerWindowY;
  const glm::vec3 origin = ox + oy + rays.originAtWindowOrigin;
  const glm::vec3 direction = dx + dy + rays.directionAtWindowOrigin;
  const float t = float(k) * rays.stepEye;
  return candidatesNear(
      origin + t * direction,
      glm::abs(ox) + glm::abs(oy) + glm::abs(rays.originAtWindowOrigin) +
          std::abs(t) * (glm::abs(dx) + glm::abs(dy) + glm::abs(rays.directionAtWindowOrigin)));
}

SliceSampler::BoxAlignedRay SliceSampler::boxAlignedRay(int x, int y, const PixelRays& rays) const {
  const glm::vec2 w = fragCoord(x, y);
  BoxAlignedRay ray;
  ray.origin =
      w.x * rays.originPerWindowX + w.y * rays.originPerWindowY + rays.originAtWindowOrigin;
  ray.direction = w.x * rays.directionPerWindowX + w.y * rays.directionPerWindowY +
                  rays.directionAtWindowOrigin;
  ray.stepEye = rays.stepEye;
  float entry = -INFINITY;
  for (int axis = 0; axis < 3; ++axis) {
    const float inverse = std::clamp(1.0f / ray.direction[axis], -1e30f, 1e30f);
    const float toLow = (-0.5f - ray.origin[axis]) * inverse;
    const float toHigh = (dims_[axis] - 0.5f - ray.origin[axis]) * inverse;
    entry = std::max(entry, std::min(toLow, toHigh));
  }
  const float u = -entry / rays.stepEye - 0.5f;
  ray.phase = u - std::floor(u);
  // The ray's coefficients and the division round differently in GL (fused, reordered): a
  // relative 1e-6 of an entry up to a few hundred steps away.
  const float slack = 1e-3f;
  ray.phaseAmbiguous = ray.phase < slack || ray.phase > 1.0f - slack;
  return ray;
}

glm::vec3 SliceSampler::boxAlignedVoxel(const BoxAlignedRay& ray, int k) {
  return quantizedVoxel(ray.origin + ((float(k) - ray.phase) * ray.stepEye) * ray.direction);
}

VoxelCandidates SliceSampler::candidatesNear(glm::vec3 unrounded, glm::vec3 magnitudes) {
  const glm::vec3 rounded = quantizedVoxel(unrounded);
  // Per axis, the steps (units of 1/1024 voxel) the position may round to, sliceVoxel's first:
  // one or two (the slack is far below half a step).
  float steps[3][2];
  int stepCount[3];
  for (int axis = 0; axis < 3; ++axis) {
    const float magnitude = magnitudes[axis];
    const float ulp = std::nextafter(magnitude, INFINITY) - magnitude;
    const float t = unrounded[axis] * 1024.0f + 0.5f;
    const float step = rounded[axis] * 1024.0f;  // exact: a multiple of 1/1024
    // Four units in the last place of the terms' magnitude, in steps: fused roundings and the
    // sums' own, with room to spare (and the + 0.5's rounding).
    const float slack =
        4.0f * 1024.0f * ulp + (std::nextafter(std::abs(t), INFINITY) - std::abs(t));
    steps[axis][0] = step;
    stepCount[axis] = 1;
    if (t - step < slack) steps[axis][stepCount[axis]++] = step - 1;
    if (step + 1 - t < slack) steps[axis][stepCount[axis]++] = step + 1;
  }
  // Fixed storage: the references ask for every sample of every pixel.
  VoxelCandidates candidates;
  for (int z = 0; z < stepCount[2]; ++z) {
    for (int y = 0; y < stepCount[1]; ++y) {
      for (int x = 0; x < stepCount[0]; ++x) {
        candidates.positions[std::size_t(candidates.count++)] =
            glm::vec3(steps[0][x], steps[1][y], steps[2][z]) * (1.0f / 1024.0f);
      }
    }
  }
  return candidates;
}

bool SliceSampler::insideVolume(glm::vec3 voxel) const {
  return glm::all(glm::greaterThanEqual(voxel, glm::vec3(-0.5f))) &&
         glm::all(glm::lessThanEqual(voxel, dims_ - 0.5f));
}

float SliceSampler::sample(glm::vec3 voxel) const {
  const LinearTaps tx = voxelTaps(voxel.x, volume_.dims.x), ty = voxelTaps(voxel.y, volume_.dims.y),
                   tz = voxelTaps(voxel.z, volume_.dims.z);
  float result = 0.0f;
  for (int dz = 0; dz < 2; ++dz) {
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        const float w = (dx ? tx.f : 1 - tx.f) * (dy ? ty.f : 1 - ty.f) * (dz ? tz.f : 1 - tz.f);
        result += w * volume_.at(dx ? tx.i1 : tx.i0, dy ? ty.i1 : ty.i0, dz ? tz.i1 : tz.i0);
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
