#include "slicing/techniques/illustrate/halo_mask.h"

#include "core/error.h"
#include "slicing/empty_space.h"
#include "slicing/gradient_texture.h"
#include "slicing/volume_texture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include <glm/gtc/packing.hpp>

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

// Calls body(zBegin, zEnd) on slabs of z over the hardware's threads.
template <typename Body>
void forSlabs(int depth, Body body) {
  const int threads =
      std::clamp(int(std::thread::hardware_concurrency()), 1, std::max(1, depth / 4));
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) {
    workers.emplace_back([=] { body(depth * t / threads, depth * (t + 1) / threads); });
  }
  body(0, depth / threads);
  for (auto& worker : workers) worker.join();
}

// lo[i], hi[i] = min, max of `samples` over the 3x3x3 voxels around i (clamped): one axis at a
// time.
void neighbourhoodRange(const float* samples, glm::ivec3 dims, std::vector<float>& lo,
                        std::vector<float>& hi) {
  const std::size_t count = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  lo.assign(samples, samples + count);
  hi = lo;
  std::vector<float> lo2(count), hi2(count);
  const glm::ivec3 stride(1, dims.x, dims.x * dims.y);
  for (int axis = 0; axis < 3; ++axis) {
    forSlabs(dims.z, [&](int z0, int z1) {
      for (int z = z0; z < z1; ++z)
        for (int y = 0; y < dims.y; ++y)
          for (int x = 0; x < dims.x; ++x) {
            const glm::ivec3 p(x, y, z);
            const std::size_t i = std::size_t(z) * std::size_t(stride.z) +
                                  std::size_t(y) * std::size_t(stride.y) + std::size_t(x);
            const std::size_t a = p[axis] > 0 ? i - std::size_t(stride[axis]) : i;
            const std::size_t b = p[axis] + 1 < dims[axis] ? i + std::size_t(stride[axis]) : i;
            lo2[i] = std::min({lo[a], lo[i], lo[b]});
            hi2[i] = std::max({hi[a], hi[i], hi[b]});
          }
    });
    lo.swap(lo2);
    hi.swap(hi2);
  }
}

}  // namespace

float haloFieldStrength(std::uint8_t alpha) {
  // As composite.frag: the normalized byte back to 0..255, less the "no halo" level.
  const float level = float(alpha) / 255.0f * 255.0f - 1.0f;
  return std::max(level, 0.0f) / (254.0f * float(kHaloFieldScale));
}

glm::vec3 haloFieldNormal(const std::uint8_t* rgb) {
  return (glm::vec3(rgb[0], rgb[1], rgb[2]) / 255.0f * 255.0f - 128.0f) / 127.0f;
}

std::vector<std::uint8_t> haloFieldVoxels(const GradientTexels& gradients,
                                          const std::vector<std::uint8_t>& mask,
                                          const float* samples,
                                          const std::function<bool(float, float)>& transparentRange,
                                          glm::dvec3 spacing, double radius, double pushExponent) {
  const glm::ivec3 dims = gradients.dims;
  struct Neighbour {
    glm::ivec3 offset;    // voxels: the nearest voxel to kHaloFieldReach·radius along the unit
    glm::vec3 direction;  // physical, unit: from the neighbour towards the voxel
  };
  std::vector<Neighbour> neighbours;
  const double reach = kHaloFieldReach * radius;
  for (int c = -1; c <= 1; ++c)
    for (int b = -1; b <= 1; ++b)
      for (int a = -1; a <= 1; ++a) {
        if (a == 0 && b == 0 && c == 0) continue;
        const glm::dvec3 unit = glm::normalize(glm::dvec3(a, b, c));
        neighbours.push_back({glm::ivec3(glm::floor(unit * reach + 0.5)),
                              glm::vec3(glm::normalize(-unit * spacing))});
      }
  // Half floats to floats by table: the taps read 26 gradients per voxel near a feature.
  std::vector<float> halfToFloat(65536);
  for (std::size_t h = 0; h < halfToFloat.size(); ++h) {
    halfToFloat[h] = glm::unpackHalf1x16(std::uint16_t(h));
  }
  std::vector<float> lo, hi;
  neighbourhoodRange(samples, dims, lo, hi);
  std::vector<std::uint8_t> field(mask.size() * 4, 0);
  const float pushExponentF = float(pushExponent);
  forSlabs(dims.z, [&](int z0, int z1) {
    for (int z = z0; z < z1; ++z)
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x) {
          const glm::ivec3 p(x, y, z);
          const std::size_t i =
              (std::size_t(z) * std::size_t(dims.y) + std::size_t(y)) * std::size_t(dims.x) +
              std::size_t(x);
          std::uint8_t* out = &field[4 * i];
          out[0] = out[1] = out[2] = 128;  // N = 0
          float sum = 0;
          glm::vec3 normalSum(0.0f);
          if (mask[i]) {
            for (const Neighbour& k : neighbours) {
              const glm::ivec3 t = glm::clamp(p + k.offset, glm::ivec3(0), dims - 1);
              const std::uint16_t* h =
                  &gradients
                       .halves[4 * ((std::size_t(t.z) * std::size_t(dims.y) + std::size_t(t.y)) *
                                        std::size_t(dims.x) +
                                    std::size_t(t.x))];
              const glm::vec3 g(halfToFloat[h[0]], halfToFloat[h[1]], halfToFloat[h[2]]);
              const float magnitude = glm::length(g);
              if (!(magnitude > 0)) continue;
              const glm::vec3 n = -g / magnitude;  // outward
              const float towards = std::max(glm::dot(n, k.direction), 0.0f);
              if (!(towards > 0)) continue;
              const float weight =
                  magnitude * (pushExponentF == 1.0f ? towards : std::pow(towards, pushExponentF));
              sum += weight;
              normalSum += weight * n;
            }
          }
          const float strength = sum / float(neighbours.size());
          if (strength >= kHaloFieldFloor) {
            const float length = glm::length(normalSum);
            const glm::vec3 n = length > 0 ? normalSum / length : glm::vec3(0.0f);
            for (int c = 0; c < 3; ++c) {
              out[c] = std::uint8_t(128 + std::lround(n[c] * 127.0f));
            }
            const long level =
                std::lround(std::min(double(strength) * kHaloFieldScale, 1.0) * 254.0);
            out[3] = std::uint8_t(1 + std::clamp(level, 3L, 254L));
          } else {
            out[3] = transparentRange(lo[i], hi[i]) ? 0 : 1;
          }
        }
  });
  return field;
}

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
                             glm::dvec3 spacing, HaloMode mode,
                             const std::function<bool(float)>& visible,
                             const std::function<bool(float, float)>& transparentRange,
                             double radius, double pushExponent, const SlabPart* slab) {
  if (!textures_.empty() && key == key_) return;
  if (slab && mode == HaloMode::Field) {
    GLint bound = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_3D, &bound);
    updateSlab(volume, spacing, *slab, visible, transparentRange, radius, pushExponent);
    VSIL_GL(glBindTexture(GL_TEXTURE_3D, GLuint(bound)));
    key_ = key;
    return;
  }
  const glm::ivec3 dims = volume.dims();
  std::vector<float> samples = volume.readVoxels();
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_3D, &bound);
  std::vector<std::uint8_t> mask = haloMaskVoxels(samples.data(), dims, visible, radius);
  if (mode == HaloMode::Field) {
    const GradientTexels gradients =
        computeGradientTexels(samples.data(), dims, spacing, /*withValues=*/false);
    std::vector<std::uint8_t> field = haloFieldVoxels(
        gradients, mask, samples.data(), transparentRange, spacing, radius, pushExponent);
    samples = {};
    // Halo opacity appears only where F > 0 (a subset of the mask).
    for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = field[4 * i + 3] > 1 ? 1 : 0;
    bricks_ = bricksReading(mask, dims);
    textures_ =
        uploadBricked(volume.layout(), dims, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4, field.data());
  } else {
    samples = {};
    bricks_ = bricksReading(mask, dims);
    for (auto& m : mask) m = m ? 255 : 0;
    textures_.clear();
    textures_.push_back(gl::createTexture());
    VSIL_GL(glBindTexture(GL_TEXTURE_3D, textures_[0].id()));
    VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 1));
    VSIL_GL(glTexImage3D(GL_TEXTURE_3D, 0, GL_R8, dims.x, dims.y, dims.z, 0, GL_RED,
                         GL_UNSIGNED_BYTE, mask.data()));
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, GLuint(bound)));
  key_ = key;
}

int haloFieldReachVoxels(double radius) {
  // The mask's radius (the neighbours lie within kHaloFieldReach·radius, rounded), one voxel
  // for their gradients' central differences and one for rounding.
  return int(std::ceil(radius)) + 2;
}

void HaloMaskTexture::updateSlab(const VolumeTexture& volume, glm::dvec3 spacing,
                                 const SlabPart& slab, const std::function<bool(float)>& visible,
                                 const std::function<bool(float, float)>& transparentRange,
                                 double radius, double pushExponent) {
  const glm::ivec3 dims = volume.dims();
  const auto [read0, read1] = slab.heldVoxels();
  const auto [own0, own1] = slab.ownedVoxels();
  // The field is the whole volume's from `reach` voxels inside the held ones (or at the
  // volume's own faces), where everything it reads lies in them.
  const int reach = haloFieldReachVoxels(radius);
  const int valid0 = read0 == 0 ? 0 : read0 + reach;
  const int valid1 = read1 == dims.z ? dims.z : read1 - reach;
  for (std::size_t b = 0; b < slab.layout.bricks().size(); ++b) {
    const Brick& brick = slab.layout.bricks()[b];
    if (slab.owns(b) && (std::max(brick.origin.z, 0) < valid0 ||
                         std::min(brick.origin.z + brick.size.z, dims.z) > valid1)) {
      throw UnavailableError("--param k_hr: a halo radius of " + std::to_string(radius) +
                             " voxels reaches beyond the slab's ghost layers; run one rank");
    }
  }
  const glm::ivec3 readDims(dims.x, dims.y, read1 - read0);
  const std::vector<float> samples = volume.readVoxels(read0, read1);
  std::vector<std::uint8_t> mask = haloMaskVoxels(samples.data(), readDims, visible, radius);
  // The gradients divided by the whole volume's M (agreed over the processes, as
  // GradientTexture's slab constructor does).
  if (slab.relay == nullptr) throw std::logic_error("HaloMaskTexture: a slab without a relay");
  const float largest = slab.relay->maxOverProcesses(
      maxSquaredGradient(samples.data(), readDims, spacing, own0 - read0, own1 - read0));
  const GradientTexels gradients = computeGradientTexels(
      samples.data(), readDims, spacing, std::sqrt(largest), 0, readDims.z, /*withValues=*/false);
  const std::vector<std::uint8_t> field = haloFieldVoxels(
      gradients, mask, samples.data(), transparentRange, spacing, radius, pushExponent);
  // Empty-space skipping stays off for slabs (Renderer::render): every brick counts.
  bricks_.assign(slab.layout.bricks().size(), true);
  const std::size_t plane = std::size_t(dims.x) * std::size_t(dims.y);
  textures_ = uploadBricked(slab.layout, dims, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4,
                            field.data() + 4 * plane * std::size_t(valid0 - read0), slab, valid0,
                            valid1 - valid0);
}

}  // namespace vsil
