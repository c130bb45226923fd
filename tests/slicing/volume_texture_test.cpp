// The volume texture holds every sample exactly, whatever the volume's sample type: R16F where
// all samples are integers of magnitude <= 2048, else R32F; uploaded slab by slab of z (the
// slab borders must not show). convertTexels converts any box on its own (a brick).
#include "slicing/volume_texture.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/packing.hpp>

#include "gl_harness.h"

namespace vsil {
namespace {

template <typename C, typename Pattern>
Volume volumeOf(glm::ivec3 dims, Pattern pattern) {
  Volume volume;
  volume.dims = dims;
  volume.allocate(sampleTypeFor<C>());
  std::span<C> samples = volume.samples<C>();
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = C(pattern(i));
  return volume;
}

// Every type, within and beyond R16F's exact integers.
std::vector<std::pair<Volume, GLenum>> volumes() {
  const glm::ivec3 dims(7, 5, 9);
  std::vector<std::pair<Volume, GLenum>> v;
  v.emplace_back(volumeOf<std::uint8_t>(dims, [](std::size_t i) { return (i * 37) % 256; }),
                 GL_R16F);
  v.emplace_back(volumeOf<std::int8_t>(dims, [](std::size_t i) { return int(i % 256) - 128; }),
                 GL_R16F);
  v.emplace_back(volumeOf<std::uint16_t>(dims, [](std::size_t i) { return (i * 13) % 2049; }),
                 GL_R16F);
  v.emplace_back(volumeOf<std::uint16_t>(dims, [](std::size_t i) { return 2000 + i; }), GL_R32F);
  v.emplace_back(volumeOf<std::int16_t>(dims, [](std::size_t i) { return -2048 + int(i) * 13; }),
                 GL_R16F);
  v.emplace_back(volumeOf<std::int16_t>(dims, [](std::size_t i) { return -2049 + int(i); }),
                 GL_R32F);
  v.emplace_back(volumeOf<float>(dims, [](std::size_t i) { return float(i % 40) - 20.0f; }),
                 GL_R16F);
  v.emplace_back(volumeOf<float>(dims, [](std::size_t i) { return float(i) * 0.25f; }), GL_R32F);
  return v;
}

TEST(TextureFormat, IsR16FOnlyWhereEverySampleIsASmallInteger) {
  for (const auto& [volume, format] : volumes()) {
    EXPECT_EQ(textureFormatFor(volume), format) << sampleTypeName(volume.type());
  }
}

TEST(ConvertTexels, ABoxGivesItsSamplesAsHalfOrFloatTexels) {
  for (const auto& [volume, format] : volumes()) {
    SCOPED_TRACE(sampleTypeName(volume.type()));
    const glm::ivec3 origin(1, 2, 3), size(5, 3, 4);
    std::vector<std::byte> texels(std::size_t(size.x * size.y * size.z) * texelSize(format));
    convertTexels(volume, origin, size, format, texels);
    std::size_t i = 0;
    for (int z = origin.z; z < origin.z + size.z; ++z) {
      for (int y = origin.y; y < origin.y + size.y; ++y) {
        for (int x = origin.x; x < origin.x + size.x; ++x, ++i) {
          const float expected = volume.at(x, y, z);
          float texel;
          if (format == GL_R16F) {
            std::uint16_t half;
            std::memcpy(&half, &texels[i * 2], 2);
            texel = glm::unpackHalf1x16(half);
          } else {
            std::memcpy(&texel, &texels[i * 4], 4);
          }
          ASSERT_EQ(texel, expected) << x << "," << y << "," << z;
        }
      }
    }
  }
}

class VolumeTextureUpload : public test::GlTest {};

// llvmpipe's largest 3D texture (limits::kMaxTextureBytes): 720³ floats fit, 800³ do not (as
// half floats they do), so such a volume is refused with an InputError, not GL_OUT_OF_MEMORY.
TEST_F(VolumeTextureUpload, TextureFitsAsTheProxyTextureSays) {
  EXPECT_TRUE(textureFits(glm::ivec3(720), GL_R32F));
  EXPECT_FALSE(textureFits(glm::ivec3(800), GL_R32F));
  EXPECT_TRUE(textureFits(glm::ivec3(800), GL_R16F));
  EXPECT_FALSE(textureFits(glm::ivec3(1024), GL_R16F));
  // Nothing beyond limits::kMaxTextureBytes at all.
  const int slices = int(limits::kMaxTextureBytes / (2048ull * 2048 * 2)) + 1;
  EXPECT_FALSE(textureFits({2048, 2048, slices}, GL_R16F));
}

TEST_F(VolumeTextureUpload, HoldsEverySampleExactlyAcrossSlabBorders) {
  for (auto& [volume, format] : volumes()) {
    // Slabs of one and of two slices (9 slices, padded to 16: the last slab is partial), and
    // one slab.
    for (std::size_t slabBytes :
         {std::size_t(1), std::size_t(8 * 8 * 2 * 4), std::size_t(1) << 20}) {
      SCOPED_TRACE(std::string(sampleTypeName(volume.type())) + " slab bytes " +
                   std::to_string(slabBytes));
      const VolumeTexture texture(volume, limits::kMaxTextureBytes, slabBytes);
      EXPECT_EQ(texture.internalFormat(), format);
      ASSERT_EQ(texture.brickCount(), 1u);
      const std::vector<float> read = texture.readVoxels();
      for (std::size_t i = 0; i < read.size(); ++i) {
        ASSERT_EQ(read[i], volume.value(i)) << "sample " << i;
      }
    }
  }
}

// Bricks of 8³ texels (4 voxels of their own, 2 of overlap on each side): every texel of
// every brick is the voxel at its origin + its index, clamped to the volume.
TEST_F(VolumeTextureUpload, EveryBrickHoldsItsVoxelsOverlapAndPadding) {
  for (auto& [volume, format] : volumes()) {
    SCOPED_TRACE(sampleTypeName(volume.type()));
    const VolumeTexture texture(volume, 8 * 8 * 8 * texelSize(format));
    ASSERT_GT(texture.brickCount(), 1u);
    std::vector<float> texels;
    for (std::size_t b = 0; b < texture.brickCount(); ++b) {
      const Brick& brick = texture.layout().bricks()[b];
      const glm::ivec3 size = brick.size;
      texels.assign(std::size_t(size.x * size.y * size.z), -99.0f);
      glBindTexture(GL_TEXTURE_3D, texture.brickTexture(b));
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glGetTexImage(GL_TEXTURE_3D, 0, GL_RED, GL_FLOAT, texels.data());
      std::size_t i = 0;
      for (int z = 0; z < size.z; ++z) {
        for (int y = 0; y < size.y; ++y) {
          for (int x = 0; x < size.x; ++x, ++i) {
            const glm::ivec3 voxel = glm::min(brick.origin + glm::ivec3(x, y, z), volume.dims - 1);
            ASSERT_EQ(texels[i], volume.at(voxel.x, voxel.y, voxel.z))
                << "brick " << b << " texel " << x << "," << y << "," << z;
          }
        }
      }
    }
    glBindTexture(GL_TEXTURE_3D, 0);
    const std::vector<float> read = texture.readVoxels();
    for (std::size_t i = 0; i < read.size(); ++i) {
      ASSERT_EQ(read[i], volume.value(i)) << "sample " << i;
    }
  }
}

// One process's part of a volume split along z (slicing/slab.h): the held bricks hold the
// whole volume's voxels at their origins (overlap and padding as in the whole volume's
// textures), the others have no texture; a slab that misses a held brick's voxels is refused.
TEST_F(VolumeTextureUpload, ASlabHoldsItsBricksAsTheWholeVolumeDoes) {
  const glm::ivec3 dims(12, 10, 40);
  const Volume whole =
      volumeOf<std::uint8_t>(dims, [](std::size_t i) { return (i * 37 + i / 97) % 256; });
  SlabPart part;
  part.dims = dims;
  part.layout = BrickLayout::withStorage(dims, {16, 16, 16});  // layers own z from 0, 12, 24, 36
  ASSERT_EQ(part.layout.counts().z, 4);
  part.ownedZ0 = 1, part.ownedZ1 = 2;  // the second layer, with the third as its ghost
  part.heldZ0 = 1, part.heldZ1 = 3;
  part.voxelZ0 = 10;  // layer 1's origin (12 − 2 voxels of overlap)
  part.internalFormat = GL_R16F;
  const int slabEnd = 22 + 16;  // layer 2's origin + its texture's size
  Volume slab =
      volumeOf<std::uint8_t>({dims.x, dims.y, slabEnd - part.voxelZ0}, [&](std::size_t i) {
        return whole.value(i + std::size_t(part.voxelZ0) * std::size_t(dims.x * dims.y));
      });
  EXPECT_EQ(part.ownedLowZ(), 11.5);
  EXPECT_EQ(part.ownedHighZ(), 23.5);
  EXPECT_EQ(part.ownedVoxels(), (std::array<int, 2>{12, 24}));
  // The first and last layers reach to ∓1e30: their voxels are cut to the volume.
  EXPECT_EQ(layersVoxels(part.layout, 0, 1, dims.z), (std::array<int, 2>{0, 12}));
  EXPECT_EQ(layersVoxels(part.layout, 3, 4, dims.z), (std::array<int, 2>{36, 40}));
  EXPECT_EQ(layersVoxels(part.layout, 0, 4, dims.z), (std::array<int, 2>{0, 40}));
  EXPECT_EQ(part.ghostVoxels(), 12);

  const VolumeTexture texture(slab, part);
  ASSERT_EQ(texture.brickCount(), part.layout.size());
  std::vector<float> texels;
  int held = 0;
  for (std::size_t b = 0; b < texture.brickCount(); ++b) {
    if (!part.holds(b)) {
      EXPECT_EQ(texture.brickTexture(b), 0u) << "brick " << b;
      continue;
    }
    ++held;
    const Brick& brick = part.layout.bricks()[b];
    const glm::ivec3 size = brick.size;
    texels.assign(std::size_t(size.x * size.y * size.z), -99.0f);
    glBindTexture(GL_TEXTURE_3D, texture.brickTexture(b));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_3D, 0, GL_RED, GL_FLOAT, texels.data());
    std::size_t i = 0;
    for (int z = 0; z < size.z; ++z) {
      for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x, ++i) {
          const glm::ivec3 voxel = glm::min(brick.origin + glm::ivec3(x, y, z), dims - 1);
          ASSERT_EQ(texels[i], whole.at(voxel.x, voxel.y, voxel.z))
              << "brick " << b << " texel " << x << "," << y << "," << z;
        }
      }
    }
  }
  glBindTexture(GL_TEXTURE_3D, 0);
  EXPECT_EQ(held, 2);

  part.heldZ1 = 4;  // the last layer too, whose voxels this slab does not hold
  EXPECT_THROW(VolumeTexture(slab, part), std::logic_error);
}

TEST(SlabOrder, RaysVisitTheSlabsInTheOrderOfTheirZDirection) {
  const glm::ivec3 dims{40, 30, 64};
  const glm::dvec3 spacing{1.0};
  const glm::ivec2 viewport{64, 48};
  // Seen from +z (azimuth 0) every ray runs towards lower z, orthographic or not.
  const View fromFront = makeView({.azimuthDeg = 0, .elevationDeg = 10}, dims, spacing, viewport);
  EXPECT_EQ(frameZDirection(fromFront), std::optional<int>(-1));
  EXPECT_EQ(rayZDirection(fromFront, {32, 24}), -1);
  const View fromBack = makeView({.azimuthDeg = 180, .elevationDeg = -10, .orthographic = true},
                                 dims, spacing, viewport);
  EXPECT_EQ(frameZDirection(fromBack), std::optional<int>(1));
  // A perspective eye level with the volume's middle along z (seen from +x): the left and the
  // right half of the image run opposite ways, so no one order serves the frame.
  const View fromSide = makeView({.azimuthDeg = 90, .elevationDeg = 0}, dims, spacing, viewport);
  EXPECT_EQ(frameZDirection(fromSide), std::nullopt);
  EXPECT_EQ(rayZDirection(fromSide, {0.5, 24}), -rayZDirection(fromSide, {63.5, 24}));
  // Orthographic from the side: rays parallel to the slabs.
  const View flat = makeView({.azimuthDeg = 90, .elevationDeg = 0, .orthographic = true}, dims,
                             spacing, viewport);
  ASSERT_TRUE(frameZDirection(flat).has_value());
}

}  // namespace
}  // namespace vsil
