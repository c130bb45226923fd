#include "slicing/gradient_texture.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <glm/gtc/packing.hpp>

#include "core/clock.h"
#include "slicing/volume_texture.h"

namespace vsil {

namespace {

// Calls body(zBegin, zEnd) on slabs of z over the hardware's threads.
template <typename Body>
void forSlabs(int depth, Body body) {
  const int threads =
      std::clamp(int(std::thread::hardware_concurrency()), 1, std::max(1, depth / 4));
  if (threads <= 1) {
    body(0, depth);
    return;
  }
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t) {
    const int z0 = depth * t / threads, z1 = depth * (t + 1) / threads;
    workers.emplace_back([=] { body(z0, z1); });
  }
  for (auto& worker : workers) worker.join();
}

// The physical gradient at voxel (x, y, z): central differences with clamped neighbours.
struct GradientAt {
  const float* samples;
  glm::ivec3 dims;
  glm::dvec3 halfPerSpacing;  // 0.5 / spacing

  glm::vec3 operator()(int x, int y, int z) const {
    const std::size_t row = std::size_t(dims.x);
    const std::size_t plane = row * std::size_t(dims.y);
    const float* p = samples + std::size_t(z) * plane + std::size_t(y) * row + std::size_t(x);
    const float dx = (x + 1 < dims.x ? p[1] : p[0]) - (x > 0 ? p[-1] : p[0]);
    const float dy = (y + 1 < dims.y ? p[row] : p[0]) - (y > 0 ? p[-std::ptrdiff_t(row)] : p[0]);
    const float dz =
        (z + 1 < dims.z ? p[plane] : p[0]) - (z > 0 ? p[-std::ptrdiff_t(plane)] : p[0]);
    return glm::vec3(dx * halfPerSpacing.x, dy * halfPerSpacing.y, dz * halfPerSpacing.z);
  }
};

}  // namespace

glm::vec4 GradientTexels::at(int x, int y, int z) const {
  const std::size_t i =
      4 * ((std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) +
           std::size_t(x));
  return {glm::unpackHalf1x16(halves[i]), glm::unpackHalf1x16(halves[i + 1]),
          glm::unpackHalf1x16(halves[i + 2]), glm::unpackHalf1x16(halves[i + 3])};
}

float maxSquaredGradient(const float* samples, glm::ivec3 dims, glm::dvec3 spacing, int zBegin,
                         int zEnd) {
  const GradientAt gradient{samples, dims, 0.5 / spacing};
  std::vector<float> slabMax(std::size_t(std::max(1, zEnd - zBegin)), 0.0f);
  forSlabs(zEnd - zBegin, [&](int s0, int s1) {
    for (int z = zBegin + s0; z < zBegin + s1; ++z) {
      float largest = 0;
      for (int y = 0; y < dims.y; ++y) {
        for (int x = 0; x < dims.x; ++x) {
          const glm::vec3 g = gradient(x, y, z);
          largest = std::max(largest, glm::dot(g, g));
        }
      }
      slabMax[std::size_t(z - zBegin)] = largest;
    }
  });
  return *std::max_element(slabMax.begin(), slabMax.end());
}

float maxGradientMagnitude(const float* samples, glm::ivec3 dims, glm::dvec3 spacing) {
  return std::sqrt(maxSquaredGradient(samples, dims, spacing, 0, dims.z));
}

GradientTexels computeGradientTexels(const float* samples, glm::ivec3 dims, glm::dvec3 spacing,
                                     float maxMagnitude, int zBegin, int zEnd, bool withValues) {
  GradientTexels texels;
  texels.dims = glm::ivec3(dims.x, dims.y, zEnd - zBegin);
  texels.maxMagnitude = maxMagnitude;
  texels.holdsValues = withValues;
  texels.halves.resize(4 * std::size_t(dims.x) * std::size_t(dims.y) *
                       std::size_t(std::max(0, zEnd - zBegin)));
  const GradientAt gradient{samples, dims, 0.5 / spacing};
  const float toNormalized = maxMagnitude > 0 ? 1.0f / maxMagnitude : 0.0f;
  forSlabs(zEnd - zBegin, [&](int s0, int s1) {
    std::uint16_t* out =
        texels.halves.data() + 4 * std::size_t(s0) * std::size_t(dims.x) * std::size_t(dims.y);
    for (int z = zBegin + s0; z < zBegin + s1; ++z) {
      for (int y = 0; y < dims.y; ++y) {
        const float* row =
            samples + (std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x);
        for (int x = 0; x < dims.x; ++x, out += 4) {
          const glm::vec3 g = gradient(x, y, z) * toNormalized;
          out[0] = glm::packHalf1x16(g.x);
          out[1] = glm::packHalf1x16(g.y);
          out[2] = glm::packHalf1x16(g.z);
          out[3] = glm::packHalf1x16(withValues ? row[x] : 0.0f);
        }
      }
    }
  });
  return texels;
}

GradientTexels computeGradientTexels(const float* samples, glm::ivec3 dims, glm::dvec3 spacing,
                                     bool withValues) {
  return computeGradientTexels(samples, dims, spacing, maxGradientMagnitude(samples, dims, spacing),
                               0, dims.z, withValues);
}

bool gradientsCanHoldValues(GLenum volumeInternalFormat) {
  return volumeInternalFormat == GL_R16F;
}

GradientTexture::GradientTexture(const VolumeTexture& volume, glm::dvec3 spacing) {
  const auto start = std::chrono::steady_clock::now();
  const glm::ivec3 dims = volume.dims();
  holdsValues_ = gradientsCanHoldValues(volume.internalFormat());
  GradientTexels texels;
  {
    const std::vector<float> samples = volume.readVoxels();
    texels = computeGradientTexels(samples.data(), dims, spacing, holdsValues_);
  }
  textures_ = uploadBricked(volume.layout(), dims, GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT,
                            4 * sizeof(std::uint16_t), texels.halves.data());
  buildMs_ = millisecondsSince(start);
}

GradientTexture::GradientTexture(const VolumeTexture& volume, glm::dvec3 spacing,
                                 const SlabPart& slab) {
  const auto start = std::chrono::steady_clock::now();
  const glm::ivec3 dims = volume.dims();
  holdsValues_ = gradientsCanHoldValues(volume.internalFormat());
  // The voxels the held bricks own, [read0, read1); central differences are the whole volume's
  // from one voxel inside them (or at the volume's own faces), [valid0, valid1).
  const auto [read0, read1] = slab.heldVoxels();
  const int valid0 = read0 == 0 ? 0 : read0 + 1;
  const int valid1 = read1 == dims.z ? dims.z : read1 - 1;
  const auto [own0, own1] = slab.ownedVoxels();
  // Every texel of an owned brick (its apron included) needs a whole-volume gradient.
  for (std::size_t b = 0; b < slab.layout.bricks().size(); ++b) {
    const Brick& brick = slab.layout.bricks()[b];
    if (slab.owns(b) && (std::max(brick.origin.z, 0) < valid0 ||
                         std::min(brick.origin.z + brick.size.z, dims.z) > valid1)) {
      throw std::logic_error("GradientTexture: the slab's ghost layers are too thin");
    }
  }
  const glm::ivec3 readDims(dims.x, dims.y, read1 - read0);
  const std::vector<float> samples = volume.readVoxels(read0, read1);
  // M over the whole volume: each process's owned voxels, the largest over all (float max is
  // exact, and sqrt is monotonic, so M is the single process's to the bit).
  if (slab.relay == nullptr) throw std::logic_error("GradientTexture: a slab without a relay");
  const float largest = slab.relay->maxOverProcesses(
      maxSquaredGradient(samples.data(), readDims, spacing, own0 - read0, own1 - read0));
  const GradientTexels texels =
      computeGradientTexels(samples.data(), readDims, spacing, std::sqrt(largest), valid0 - read0,
                            valid1 - read0, holdsValues_);
  textures_ =
      uploadBricked(slab.layout, dims, GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT,
                    4 * sizeof(std::uint16_t), texels.halves.data(), slab, valid0, valid1 - valid0);
  buildMs_ = millisecondsSince(start);
}

void GradientTexture::addDefines(std::vector<std::string>& defines) const {
  if (holdsValues_) defines.emplace_back("GRADIENTS_HOLD_VALUES");
}

void GradientTextureCache::reset(const VolumeTexture* volume, glm::dvec3 spacing,
                                 const SlabPart* slab) {
  texture_.reset();
  volume_ = volume;
  spacing_ = spacing;
  slab_ = slab;
}

const GradientTexture& GradientTextureCache::texture() {
  if (!texture_ && slab_) texture_.emplace(*volume_, spacing_, *slab_);
  if (!texture_) texture_.emplace(*volume_, spacing_);
  return *texture_;
}

}  // namespace vsil
