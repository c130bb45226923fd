#include "slicing/volume_texture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "core/error.h"
#include "core/limits.h"

namespace vsil {

namespace {

constexpr int kMaxExactHalfInteger = 2048;

// Half-float bits of the integers -2048 .. 2048 (all exact in half precision).
const std::array<std::uint16_t, 2 * kMaxExactHalfInteger + 1>& halfOfInteger() {
  static const auto table = [] {
    std::array<std::uint16_t, 2 * kMaxExactHalfInteger + 1> bits{};
    for (int i = -kMaxExactHalfInteger; i <= kMaxExactHalfInteger; ++i) {
      bits[std::size_t(i + kMaxExactHalfInteger)] = glm::packHalf1x16(float(i));
    }
    return bits;
  }();
  return table;
}

}  // namespace

// Half floats hold every integer up to 2048 exactly; sampling R16F costs llvmpipe about a
// quarter less than R32F (bonsai, 512², single thread: 620 -> 450 ms per OPS frame) and
// filters the same values in float, so the result is unchanged.
GLenum textureFormatFor(const Volume& volume) {
  const bool exact = volume.visit([](auto samples) {
    using C = typename decltype(samples)::value_type;
    if constexpr (std::is_integral_v<C> && sizeof(C) == 1) {
      return true;
    } else if constexpr (std::is_integral_v<C>) {
      if (samples.empty()) return true;
      const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
      return *lo >= -kMaxExactHalfInteger && *hi <= kMaxExactHalfInteger;
    } else {
      for (float v : samples) {
        if (v != std::nearbyint(v) || std::abs(v) > float(kMaxExactHalfInteger)) return false;
      }
      return true;
    }
  });
  return exact ? GL_R16F : GL_R32F;
}

std::size_t texelSize(GLenum internalFormat) {
  return internalFormat == GL_R16F ? 2 : 4;
}

bool textureFits(glm::ivec3 dims, GLenum internalFormat) {
  const GLenum type = internalFormat == GL_R16F ? GL_HALF_FLOAT : GL_FLOAT;
  VSIL_GL(glTexImage3D(GL_PROXY_TEXTURE_3D, 0, GLint(internalFormat), dims.x, dims.y, dims.z, 0,
                       GL_RED, type, nullptr));
  GLint width = 0;
  VSIL_GL(glGetTexLevelParameteriv(GL_PROXY_TEXTURE_3D, 0, GL_TEXTURE_WIDTH, &width));
  return width != 0;
}

void convertTexels(const Volume& volume, glm::ivec3 origin, glm::ivec3 size, GLenum internalFormat,
                   std::span<std::byte> out) {
  const std::size_t rowTexels = std::size_t(size.x);
  if (out.size() !=
      rowTexels * std::size_t(size.y) * std::size_t(size.z) * texelSize(internalFormat)) {
    throw std::logic_error("convertTexels: output size does not match the box");
  }
  // Texels past the volume's far sides repeat its last voxel along that axis.
  const std::size_t inside = std::size_t(std::clamp(volume.dims.x - origin.x, 1, size.x));
  volume.visit([&](auto samples) {
    using C = typename decltype(samples)::value_type;
    std::size_t at = 0;  // texels written
    for (int z = origin.z; z < origin.z + size.z; ++z) {
      for (int y = origin.y; y < origin.y + size.y; ++y, at += rowTexels) {
        const C* row = samples.data() + volume.index(origin.x, std::min(y, volume.dims.y - 1),
                                                     std::min(z, volume.dims.z - 1));
        if (internalFormat == GL_R32F) {
          float* texels = reinterpret_cast<float*>(out.data()) + at;
          for (std::size_t x = 0; x < inside; ++x) texels[x] = float(row[x]);
          std::fill(texels + inside, texels + rowTexels, texels[inside - 1]);
          continue;
        }
        std::uint16_t* texels = reinterpret_cast<std::uint16_t*>(out.data()) + at;
        const std::uint16_t* half = halfOfInteger().data() + kMaxExactHalfInteger;
        if constexpr (std::is_integral_v<C> && sizeof(C) == 1) {
          for (std::size_t x = 0; x < inside; ++x) texels[x] = half[row[x]];
        } else if constexpr (std::is_integral_v<C>) {
          // Clamped only so that a misuse cannot read outside the table.
          for (std::size_t x = 0; x < inside; ++x) {
            texels[x] = half[std::clamp(int(row[x]), -kMaxExactHalfInteger, kMaxExactHalfInteger)];
          }
        } else {
          for (std::size_t x = 0; x < inside; ++x) texels[x] = glm::packHalf1x16(row[x]);
        }
        std::fill(texels + inside, texels + rowTexels, texels[inside - 1]);
      }
    }
  });
}

namespace {

void setSampling(GLenum filter) {
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GLint(filter));
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GLint(filter));
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  }
}

std::string dimsText(glm::ivec3 d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

}  // namespace

bool fitsOneTexture(glm::ivec3 dims, GLenum internalFormat, std::uint64_t maxTextureBytes) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  const BrickLayout layout = BrickLayout::choose(dims, texelSize(internalFormat), maxTextureBytes,
                                                 maxSize, BrickLayout::Bricking::OneIfItFits);
  return layout.size() == 1 && textureFits(layout.bricks()[0].size, internalFormat);
}

VolumeTexture::VolumeTexture(const Volume& volume, std::uint64_t maxTextureBytes,
                             std::size_t slabBytes, BrickLayout::Bricking bricking)
    : dims_(volume.dims), internalFormat_(textureFormatFor(volume)) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  if (volume.sampleCount() != volume.voxelCount()) {
    throw std::logic_error("VolumeTexture: sample count does not match the dimensions");
  }
  const std::size_t texel = texelSize(internalFormat_);
  try {
    layout_ = BrickLayout::choose(dims_, texel, maxTextureBytes, maxSize, bricking);
  } catch (const std::invalid_argument&) {
    throwInputError(volume.source, "no 8x8x8 brick fits the texture limit of " +
                                       std::to_string(maxTextureBytes >> 20) + " MiB");
  }
  for (const Brick& brick : layout_.bricks()) {
    if (!textureFits(brick.size, internalFormat_)) {
      const double mib =
          double(brick.size.x) * brick.size.y * brick.size.z * double(texel) / double(1 << 20);
      throwInputError(volume.source,
                      "its " + dimsText(brick.size) + " brick texture (" +
                          (internalFormat_ == GL_R16F ? "R16F, " : "R32F, ") +
                          std::to_string(std::llround(mib)) +
                          " MiB) is more than one 3D texture can hold here; give a smaller "
                          "--max-texture-mib, or read less with --crop X0:X1,Y0:Y1,Z0:Z1 or "
                          "--stride N");
    }
  }
  upload(volume, slabBytes, 0, nullptr);
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, 0));
}

void VolumeTexture::upload(const Volume& volume, std::size_t slabBytes, int zShift,
                           const SlabPart* part) {
  const std::size_t texel = texelSize(internalFormat_);
  const GLenum type = internalFormat_ == GL_R16F ? GL_HALF_FLOAT : GL_FLOAT;
  VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 1));
  for (std::size_t b = 0; b < layout_.size(); ++b) {
    const Brick& brick = layout_.bricks()[b];
    if (part != nullptr && !part->holds(b)) {
      textures_.emplace_back();  // another process holds it
      continue;
    }
    const glm::ivec3 size = brick.size;
    gl::TextureName texture = gl::createTexture();
    VSIL_GL(glBindTexture(GL_TEXTURE_3D, texture.id()));
    VSIL_GL(glTexImage3D(GL_TEXTURE_3D, 0, GLint(internalFormat_), size.x, size.y, size.z, 0,
                         GL_RED, type, nullptr));
    // Slabs of z of about slabBytes: the next slab is converted on a second thread while this
    // one is uploaded (GL calls stay on this thread).
    const std::size_t sliceBytes = std::size_t(size.x) * std::size_t(size.y) * texel;
    const int depth = int(std::clamp<std::size_t>(slabBytes / sliceBytes, 1, std::size_t(size.z)));
    std::vector<std::byte> slabs[2];
    auto convert = [&](int slab) {
      const int z = slab * depth, slabDepth = std::min(depth, size.z - z);
      std::vector<std::byte>& texels = slabs[slab % 2];
      texels.resize(sliceBytes * std::size_t(slabDepth));
      convertTexels(volume, brick.origin + glm::ivec3(0, 0, z - zShift),
                    {size.x, size.y, slabDepth}, internalFormat_, texels);
    };
    const int slabCount = (size.z + depth - 1) / depth;
    convert(0);
    for (int slab = 0; slab < slabCount; ++slab) {
      std::exception_ptr failed;  // from the worker (out of memory), rethrown here
      {
        std::jthread next;
        if (slab + 1 < slabCount) {
          next = std::jthread([&, slab] {
            try {
              convert(slab + 1);
            } catch (...) {
              failed = std::current_exception();
            }
          });
        }
        const int z = slab * depth;
        VSIL_GL(glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z, size.x, size.y,
                                std::min(depth, size.z - z), GL_RED, type, slabs[slab % 2].data()));
      }
      if (failed) std::rethrow_exception(failed);
    }
    setSampling(GL_LINEAR);
    textures_.push_back(std::move(texture));
  }
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, 0));
}

VolumeTexture::VolumeTexture(const Volume& slabVolume, const SlabPart& slab, std::size_t slabBytes)
    : layout_(slab.layout), dims_(slab.dims), internalFormat_(slab.internalFormat) {
  if (slabVolume.sampleCount() != slabVolume.voxelCount()) {
    throw std::logic_error("VolumeTexture: sample count does not match the dimensions");
  }
  for (std::size_t b = 0; b < layout_.size(); ++b) {
    const Brick& brick = layout_.bricks()[b];
    if (!slab.holds(b)) continue;
    if (!textureFits(brick.size, internalFormat_)) {
      throwInputError(slabVolume.source, "its " + dimsText(brick.size) +
                                             " brick texture is more than one 3D texture can "
                                             "hold here; give a smaller --max-texture-mib");
    }
    // The brick's voxels (its power-of-two padding past the volume's end repeats the last
    // voxel, as convertTexels does for the whole volume) must lie in the slab.
    const int z1 = std::min(brick.origin.z + brick.size.z, slab.dims.z);
    if (brick.origin.z < slab.voxelZ0 || z1 > slab.voxelZ0 + slabVolume.dims.z) {
      throw std::logic_error("VolumeTexture: a held brick reaches beyond the slab read");
    }
  }
  upload(slabVolume, slabBytes, slab.voxelZ0, &slab);
}

// uploadBricked's work: every brick, or a slab's held ones.
std::vector<gl::TextureName> uploadBrickedPart(const BrickLayout& layout, glm::ivec3 dims,
                                               GLenum internalFormat, GLenum format, GLenum type,
                                               std::size_t bytesPerVoxel, const void* texels,
                                               const SlabPart* slab, int zFirst, int zCount);

std::vector<float> VolumeTexture::readVoxels() const {
  return readVoxels(0, dims_.z);
}

std::vector<float> VolumeTexture::readVoxels(int zBegin, int zEnd) const {
  const glm::ivec3 d = dims_;
  std::vector<float> voxels(std::size_t(d.x) * std::size_t(d.y) * std::size_t(zEnd - zBegin));
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_3D, &bound);
  VSIL_GL(glPixelStorei(GL_PACK_ALIGNMENT, 1));
  std::vector<float> texels;
  for (std::size_t b = 0; b < textures_.size(); ++b) {
    const Brick& brick = layout_.bricks()[b];
    // The voxels this brick owns (its overlap belongs to its neighbours).
    glm::ivec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = int(std::ceil(std::clamp(brick.low[a], 0.0, double(d[a]))));
      hi[a] = int(std::ceil(std::clamp(brick.high[a], 0.0, double(d[a]))));
    }
    lo.z = std::max(lo.z, zBegin);
    hi.z = std::min(hi.z, zEnd);
    if (lo.z >= hi.z) continue;
    if (textures_[b].id() == 0)
      throw std::logic_error("VolumeTexture::readVoxels: a brick not held");
    texels.resize(std::size_t(brick.size.x) * brick.size.y * brick.size.z);
    VSIL_GL(glBindTexture(GL_TEXTURE_3D, textures_[b].id()));
    VSIL_GL(glGetTexImage(GL_TEXTURE_3D, 0, GL_RED, GL_FLOAT, texels.data()));
    for (int z = lo.z; z < hi.z; ++z) {
      for (int y = lo.y; y < hi.y; ++y) {
        const float* from =
            texels.data() +
            ((std::size_t(z - brick.origin.z) * brick.size.y + std::size_t(y - brick.origin.y)) *
                 brick.size.x +
             std::size_t(lo.x - brick.origin.x));
        std::copy(from, from + (hi.x - lo.x),
                  voxels.data() + (std::size_t(z - zBegin) * d.y + std::size_t(y)) * d.x + lo.x);
      }
    }
  }
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, GLuint(bound)));
  return voxels;
}

std::vector<gl::TextureName> uploadBricked(const BrickLayout& layout, glm::ivec3 dims,
                                           GLenum internalFormat, GLenum format, GLenum type,
                                           std::size_t bytesPerVoxel, const void* texels) {
  return uploadBrickedPart(layout, dims, internalFormat, format, type, bytesPerVoxel, texels,
                           nullptr, 0, dims.z);
}

std::vector<gl::TextureName> uploadBricked(const BrickLayout& layout, glm::ivec3 dims,
                                           GLenum internalFormat, GLenum format, GLenum type,
                                           std::size_t bytesPerVoxel, const void* texels,
                                           const SlabPart& slab, int zFirst, int zCount) {
  return uploadBrickedPart(layout, dims, internalFormat, format, type, bytesPerVoxel, texels, &slab,
                           zFirst, zCount);
}

std::vector<gl::TextureName> uploadBrickedPart(const BrickLayout& layout, glm::ivec3 dims,
                                               GLenum internalFormat, GLenum format, GLenum type,
                                               std::size_t bytesPerVoxel, const void* texels,
                                               const SlabPart* slab, int zFirst, int zCount) {
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_3D, &bound);
  VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 1));
  const auto* voxels = static_cast<const std::byte*>(texels);
  std::vector<gl::TextureName> textures;
  std::vector<std::byte> slice;
  for (std::size_t b = 0; b < layout.bricks().size(); ++b) {
    const Brick& brick = layout.bricks()[b];
    if (slab && !slab->holds(b)) {
      textures.emplace_back();
      continue;
    }
    const glm::ivec3 size = brick.size;
    gl::TextureName texture = gl::createTexture();
    VSIL_GL(glBindTexture(GL_TEXTURE_3D, texture.id()));
    VSIL_GL(glTexImage3D(GL_TEXTURE_3D, 0, GLint(internalFormat), size.x, size.y, size.z, 0, format,
                         type, nullptr));
    // One z slice at a time, past the volume's far sides repeating its last voxel.
    slice.resize(std::size_t(size.x) * std::size_t(size.y) * bytesPerVoxel);
    for (int z = 0; z < size.z; ++z) {
      const int vz =
          std::clamp(std::min(brick.origin.z + z, dims.z - 1), zFirst, zFirst + zCount - 1) -
          zFirst;
      for (int y = 0; y < size.y; ++y) {
        const int vy = std::min(brick.origin.y + y, dims.y - 1);
        std::byte* row = slice.data() + std::size_t(y) * size.x * bytesPerVoxel;
        for (int x = 0; x < size.x; ++x) {
          const int vx = std::min(brick.origin.x + x, dims.x - 1);
          std::memcpy(row + std::size_t(x) * bytesPerVoxel,
                      voxels + ((std::size_t(vz) * dims.y + vy) * dims.x + vx) * bytesPerVoxel,
                      bytesPerVoxel);
        }
      }
      VSIL_GL(glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z, size.x, size.y, 1, format, type,
                              slice.data()));
    }
    setSampling(internalFormat == GL_R8 ? GL_NEAREST : GL_LINEAR);
    textures.push_back(std::move(texture));
  }
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, GLuint(bound)));
  return textures;
}

}  // namespace vsil
