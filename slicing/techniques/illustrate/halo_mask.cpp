#include "slicing/techniques/illustrate/halo_mask.h"

#include "slicing/empty_space.h"
#include "slicing/volume_texture.h"

#include <algorithm>
#include <cmath>

namespace vsil {

namespace {

// One axis of a box dilation: out[i] = 1 where in[j] is 1 for some |j − i| <= reach along
// `stride` (a run of `count` voxels starting at `first`).
void dilateRun(const std::uint8_t* in, std::uint8_t* out, std::size_t first, std::size_t stride,
               int count, int reach) {
  // The last index with a 1 seen so far (from the front), then from the back.
  int last = -(reach + 1);
  for (int i = 0; i < count; ++i) {
    if (in[first + std::size_t(i) * stride]) last = i;
    out[first + std::size_t(i) * stride] = i - last <= reach;
  }
  last = count + reach + 1;
  for (int i = count - 1; i >= 0; --i) {
    if (in[first + std::size_t(i) * stride]) last = i;
    if (last - i <= reach) out[first + std::size_t(i) * stride] = 1;
  }
}

}  // namespace

int haloMaskReach(double radiusVoxels) {
  return int(std::ceil(radiusVoxels));
}

std::vector<std::uint8_t> haloMaskVoxels(const float* samples, glm::ivec3 dims,
                                         const std::function<bool(float)>& visible, int reach) {
  const std::size_t count = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  std::vector<std::uint8_t> mask(count), other(count);
  for (std::size_t i = 0; i < count; ++i) mask[i] = visible(samples[i]) ? 1 : 0;
  const std::size_t row = std::size_t(dims.x), plane = row * std::size_t(dims.y);
  for (std::size_t z = 0; z < std::size_t(dims.z); ++z) {
    for (std::size_t y = 0; y < std::size_t(dims.y); ++y) {
      dilateRun(mask.data(), other.data(), z * plane + y * row, 1, dims.x, reach);
    }
  }
  for (std::size_t z = 0; z < std::size_t(dims.z); ++z) {
    for (std::size_t x = 0; x < row; ++x) {
      dilateRun(other.data(), mask.data(), z * plane + x, row, dims.y, reach);
    }
  }
  for (std::size_t i = 0; i < plane; ++i) {
    dilateRun(mask.data(), other.data(), i, plane, dims.z, reach);
  }
  return other;
}

void HaloMaskTexture::update(const std::vector<double>& key, const VolumeTexture& volume,
                             const std::function<bool(float)>& visible, int reach) {
  if (texture_ && key == key_) return;
  const glm::ivec3 dims = volume.dims();
  std::vector<float> samples = volume.readVoxels();
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_3D, &bound);
  std::vector<std::uint8_t> mask = haloMaskVoxels(samples.data(), dims, visible, reach);
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
