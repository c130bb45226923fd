#include "slicing/techniques/illustrate/halo_mask.h"

#include "slicing/empty_space.h"
#include "slicing/volume_texture.h"

#include <algorithm>
#include <cmath>

namespace vsil {

namespace {

constexpr std::uint16_t kFar = 0xFFFF;  // farther than any radius from a visible voxel

// One axis of the squared distance transform, truncated to `reach` voxels: along the run of
// `count` values from `first` by `stride`, d[i] = min over |k| <= reach of d[i + k] + k².
// `scratch` holds a copy of the run.
void nearestAlong(std::uint16_t* d, std::size_t first, std::size_t stride, int count, int reach,
                  std::vector<std::uint16_t>& scratch) {
  scratch.resize(std::size_t(count));
  for (int i = 0; i < count; ++i) scratch[std::size_t(i)] = d[first + std::size_t(i) * stride];
  for (int i = 0; i < count; ++i) {
    int best = scratch[std::size_t(i)];
    const int lo = std::max(0, i - reach), hi = std::min(count - 1, i + reach);
    for (int j = lo; j <= hi; ++j) {
      if (scratch[std::size_t(j)] == kFar) continue;
      best = std::min(best, int(scratch[std::size_t(j)]) + (j - i) * (j - i));
    }
    d[first + std::size_t(i) * stride] = std::uint16_t(std::min(best, int(kFar)));
  }
}

}  // namespace

std::vector<std::uint8_t> haloMaskVoxels(const float* samples, glm::ivec3 dims,
                                         const std::function<bool(float)>& visible, double radius) {
  const std::size_t count = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  // Squared distances in voxels to the nearest visible voxel, one axis at a time (exact: the
  // squared Euclidean distance separates into the axes' squares), looking no farther than the
  // radius.
  const int reach = int(std::floor(radius));
  std::vector<std::uint16_t> distance2(count);
  for (std::size_t i = 0; i < count; ++i) distance2[i] = visible(samples[i]) ? 0 : kFar;
  const std::size_t row = std::size_t(dims.x), plane = row * std::size_t(dims.y);
  std::vector<std::uint16_t> scratch;
  for (std::size_t z = 0; z < std::size_t(dims.z); ++z) {
    for (std::size_t y = 0; y < std::size_t(dims.y); ++y) {
      nearestAlong(distance2.data(), z * plane + y * row, 1, dims.x, reach, scratch);
    }
    for (std::size_t x = 0; x < row; ++x) {
      nearestAlong(distance2.data(), z * plane + x, row, dims.y, reach, scratch);
    }
  }
  for (std::size_t i = 0; i < plane; ++i) {
    nearestAlong(distance2.data(), i, plane, dims.z, reach, scratch);
  }
  std::vector<std::uint8_t> mask(count);
  const double limit = radius * radius;
  for (std::size_t i = 0; i < count; ++i) mask[i] = double(distance2[i]) <= limit ? 1 : 0;
  return mask;
}

void HaloMaskTexture::update(const std::vector<double>& key, const VolumeTexture& volume,
                             const std::function<bool(float)>& visible, double radius) {
  if (texture_ && key == key_) return;
  const glm::ivec3 dims = volume.dims();
  std::vector<float> samples = volume.readVoxels();
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_3D, &bound);
  std::vector<std::uint8_t> mask = haloMaskVoxels(samples.data(), dims, visible, radius);
  samples = {};
  bricks_ = bricksReading(mask, dims);
  for (auto& m : mask) m = m ? 255 : 0;
  if (!texture_) texture_ = gl::createTexture();
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, texture_.id()));
  VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 1));
  VSIL_GL(glTexImage3D(GL_TEXTURE_3D, 0, GL_R8, dims.x, dims.y, dims.z, 0, GL_RED, GL_UNSIGNED_BYTE,
                       mask.data()));
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, GLuint(bound)));
  key_ = key;
}

}  // namespace vsil
