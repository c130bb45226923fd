#include "slicing/volume_texture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
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
  volume.visit([&](auto samples) {
    using C = typename decltype(samples)::value_type;
    std::size_t at = 0;  // texels written
    for (int z = origin.z; z < origin.z + size.z; ++z) {
      for (int y = origin.y; y < origin.y + size.y; ++y, at += rowTexels) {
        const C* row = samples.data() + volume.index(origin.x, y, z);
        if (internalFormat == GL_R32F) {
          float* texels = reinterpret_cast<float*>(out.data()) + at;
          for (std::size_t x = 0; x < rowTexels; ++x) texels[x] = float(row[x]);
          continue;
        }
        std::uint16_t* texels = reinterpret_cast<std::uint16_t*>(out.data()) + at;
        const std::uint16_t* half = halfOfInteger().data() + kMaxExactHalfInteger;
        if constexpr (std::is_integral_v<C> && sizeof(C) == 1) {
          for (std::size_t x = 0; x < rowTexels; ++x) texels[x] = half[row[x]];
        } else if constexpr (std::is_integral_v<C>) {
          // Clamped only so that a misuse cannot read outside the table.
          for (std::size_t x = 0; x < rowTexels; ++x) {
            texels[x] = half[std::clamp(int(row[x]), -kMaxExactHalfInteger, kMaxExactHalfInteger)];
          }
        } else {
          for (std::size_t x = 0; x < rowTexels; ++x) texels[x] = glm::packHalf1x16(row[x]);
        }
      }
    }
  });
}

VolumeTexture::VolumeTexture(const Volume& volume, std::size_t slabBytes)
    : dims_(volume.dims), internalFormat_(textureFormatFor(volume)) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  for (int axis = 0; axis < 3; ++axis) {
    if (dims_[axis] > maxSize) {
      throwInputError(volume.source, "dimension " + std::to_string(dims_[axis]) +
                                         " exceeds the OpenGL 3D texture limit of " +
                                         std::to_string(maxSize));
    }
  }
  if (volume.sampleCount() != volume.voxelCount()) {
    throw std::logic_error("VolumeTexture: sample count does not match the dimensions");
  }
  if (!textureFits(dims_, internalFormat_)) {
    const double mib =
        double(dims_.x) * dims_.y * dims_.z * double(texelSize(internalFormat_)) / double(1 << 20);
    throwInputError(volume.source,
                    "its " + std::to_string(dims_.x) + "x" + std::to_string(dims_.y) + "x" +
                        std::to_string(dims_.z) + " texture (" +
                        (internalFormat_ == GL_R16F ? "R16F, " : "R32F, ") +
                        std::to_string(std::llround(mib)) +
                        " MiB) is more than one 3D texture can hold here; read less with --crop "
                        "X0:X1,Y0:Y1,Z0:Z1 or --stride N");
  }
  const GLenum type = internalFormat_ == GL_R16F ? GL_HALF_FLOAT : GL_FLOAT;
  texture_ = gl::createTexture();
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, texture_.id()));
  VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 1));
  VSIL_GL(glTexImage3D(GL_TEXTURE_3D, 0, GLint(internalFormat_), dims_.x, dims_.y, dims_.z, 0,
                       GL_RED, type, nullptr));
  if (volume.type() == SampleType::Float32 && internalFormat_ == GL_R32F) {
    // The samples are the texels already.
    VSIL_GL(glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, dims_.x, dims_.y, dims_.z, GL_RED, type,
                            volume.samples<float>().data()));
  } else {
    // Slabs of z of about slabBytes: the next slab is converted on a second thread while this
    // one is uploaded (GL calls stay on this thread).
    const std::size_t sliceBytes =
        std::size_t(dims_.x) * std::size_t(dims_.y) * texelSize(internalFormat_);
    const int depth = int(std::clamp<std::size_t>(slabBytes / sliceBytes, 1, std::size_t(dims_.z)));
    std::vector<std::byte> slabs[2];
    auto convert = [&](int slab) {
      const int z = slab * depth, slabDepth = std::min(depth, dims_.z - z);
      std::vector<std::byte>& texels = slabs[slab % 2];
      texels.resize(sliceBytes * std::size_t(slabDepth));
      convertTexels(volume, {0, 0, z}, {dims_.x, dims_.y, slabDepth}, internalFormat_, texels);
    };
    const int slabCount = (dims_.z + depth - 1) / depth;
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
        VSIL_GL(glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z, dims_.x, dims_.y,
                                std::min(depth, dims_.z - z), GL_RED, type,
                                slabs[slab % 2].data()));
      }
      if (failed) std::rethrow_exception(failed);
    }
  }
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  }
  VSIL_GL(glBindTexture(GL_TEXTURE_3D, 0));
}

}  // namespace vsil
