#include "slicing/techniques/illustrate/halo_mask.h"

#include "slicing/empty_space.h"
#include "slicing/volume_texture.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vsil {

namespace {

// Squared distances saturate here: farther than any halo radius (k_hr <= 32) from a visible voxel.
constexpr std::uint16_t kFar = 0xFFFF;

struct Envelope {
  std::vector<std::uint16_t> values;
  std::vector<int> roots;      // the parabolas on the lower envelope, left to right
  std::vector<double> starts;  // where each begins to be the lowest
};

// One axis of the squared distance transform: along the run of `count` values from `first` by
// `stride`, d[i] = min over j of d[j] + (i − j)², kFar where no d[j] is finite. The lower
// envelope of the parabolas rooted at the finite d[j] (Felzenszwalb and Huttenlocher, 2012):
// time linear in the run, whatever the radius.
void nearestAlong(std::uint16_t* d, std::size_t first, std::size_t stride, int count, Envelope& e) {
  e.values.resize(std::size_t(count));
  e.roots.resize(std::size_t(count));
  e.starts.resize(std::size_t(count));
  for (int i = 0; i < count; ++i) e.values[std::size_t(i)] = d[first + std::size_t(i) * stride];
  auto height = [&](int j) { return double(e.values[std::size_t(j)]) + double(j) * j; };
  int top = -1;
  for (int q = 0; q < count; ++q) {
    if (e.values[std::size_t(q)] == kFar) continue;
    double start = -std::numeric_limits<double>::infinity();
    while (top >= 0) {
      const int root = e.roots[std::size_t(top)];
      start = (height(q) - height(root)) / (2.0 * (q - root));
      if (start > e.starts[std::size_t(top)]) break;
      start = -std::numeric_limits<double>::infinity();
      --top;
    }
    ++top;
    e.roots[std::size_t(top)] = q;
    e.starts[std::size_t(top)] = start;
  }
  if (top < 0) return;  // nothing visible along the run: it stays kFar
  for (int i = 0, k = 0; i < count; ++i) {
    while (k < top && e.starts[std::size_t(k) + 1] < i) ++k;
    const int root = e.roots[std::size_t(k)];
    const double value = double(e.values[std::size_t(root)]) + double(i - root) * (i - root);
    d[first + std::size_t(i) * stride] = std::uint16_t(std::min(value, double(kFar)));
  }
}

}  // namespace

std::vector<std::uint8_t> haloMaskVoxels(const float* samples, glm::ivec3 dims,
                                         const std::function<bool(float)>& visible, double radius) {
  const std::size_t count = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  // Squared distances in voxels to the nearest visible voxel, one axis at a time (exact: the
  // squared Euclidean distance separates into the axes' squares).
  std::vector<std::uint16_t> distance2(count);
  for (std::size_t i = 0; i < count; ++i) distance2[i] = visible(samples[i]) ? 0 : kFar;
  const std::size_t row = std::size_t(dims.x), plane = row * std::size_t(dims.y);
  Envelope envelope;
  for (std::size_t z = 0; z < std::size_t(dims.z); ++z) {
    for (std::size_t y = 0; y < std::size_t(dims.y); ++y) {
      nearestAlong(distance2.data(), z * plane + y * row, 1, dims.x, envelope);
    }
    for (std::size_t x = 0; x < row; ++x) {
      nearestAlong(distance2.data(), z * plane + x, row, dims.y, envelope);
    }
  }
  for (std::size_t i = 0; i < plane; ++i) {
    nearestAlong(distance2.data(), i, plane, dims.z, envelope);
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
