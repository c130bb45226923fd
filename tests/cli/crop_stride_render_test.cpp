// `vsil render --crop/--stride` through the built binary: the same state, depth and image bytes
// as rendering a file written already cropped or subsampled (with its spacing grown by the
// stride), and the metadata and `vsil info` say what was read.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "reference/test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

constexpr int kX = 40, kY = 36, kZ = 44;

// Two overlapping balls, a uint16 ramp 0..1000 over 4 voxels around radius 11 and 8.
std::uint16_t sampleAt(int x, int y, int z) {
  const double a = std::hypot(x - 17.0, y - 16.0, z - 20.0) - 11.0;
  const double b = std::hypot(x - 27.0, y - 21.0, z - 26.0) - 8.0;
  return std::uint16_t(std::clamp(500.0 - std::min(a, b) * 125.0, 0.0, 1000.0));
}

// A NRRD file of the samples lo + i·stride below hi, with spacing `stride` along each axis.
fs::path writeNrrd(const fs::path& path, glm::ivec3 lo, glm::ivec3 hi, int stride) {
  const glm::ivec3 dims = (hi - lo + stride - 1) / stride;
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\ntype: uint16\ndimension: 3\nsizes: " << dims.x << " " << dims.y << " " << dims.z
      << "\nspacings: " << stride << " " << stride << " " << stride
      << "\nendian: little\nencoding: raw\n\n";
  for (int z = lo.z; z < hi.z; z += stride) {
    for (int y = lo.y; y < hi.y; y += stride) {
      for (int x = lo.x; x < hi.x; x += stride) {
        const std::uint16_t v = sampleAt(x, y, z);
        const char bytes[2] = {char(v & 0xff), char(v >> 8)};
        out.write(bytes, 2);
      }
    }
  }
  return path;
}

// Renders `input` with `flags` into dir/<name>{.png,-state.png,-depth.png}; returns the three
// files' bytes.
std::string render(const fs::path& dir, const std::string& name, const std::string& input,
                   const std::string& flags) {
  const std::string base = (dir / name).string();
  const auto result = test::runVsil("render '" + input + "' " + flags +
                                    " --iso 500 --size 96x80 --view 25,15 --out " + base +
                                    ".png --state-out " + base + "-state.png --depth-out " + base +
                                    "-depth.png --meta-out " + base + ".json");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err, "");
  return test::readFileBytes(base + ".png") + "|" + test::readFileBytes(base + "-state.png") + "|" +
         test::readFileBytes(base + "-depth.png");
}

struct Case {
  const char* name;
  const char* crop;  // --crop, "" for none
  glm::ivec3 lo, hi;
  int stride;
};

const Case kCases[] = {
    {"Crop", "5:37,3:30,8:40", {5, 3, 8}, {37, 30, 40}, 1},
    {"Stride", "", {0, 0, 0}, {kX, kY, kZ}, 2},
    {"CropAndStride", "2:39,:,4:", {2, 0, 4}, {39, kY, kZ}, 3},
};

class CropStrideRender : public ::testing::TestWithParam<Case> {};

TEST_P(CropStrideRender, EqualsRenderingTheFileWrittenThatWay) {
  const Case& c = GetParam();
  const fs::path dir = test::scratchDir();
  const fs::path whole = writeNrrd(dir / "whole.nrrd", {0, 0, 0}, {kX, kY, kZ}, 1);
  const fs::path part = writeNrrd(dir / "part.nrrd", c.lo, c.hi, c.stride);
  std::string flags = " --stride " + std::to_string(c.stride);
  if (*c.crop) flags += std::string(" --crop ") + c.crop;
  for (const char* technique : {"silhouette", "rightangle"}) {
    SCOPED_TRACE(technique);
    const std::string t = std::string(" --technique ") + technique;
    const std::string read = render(dir, "read", whole.string(), flags + t);
    const std::string written = render(dir, "written", part.string(), t);
    EXPECT_GT(read.size(), 300u);
    EXPECT_TRUE(read == written) << "the outputs differ";
    // Not trivially equal: the whole volume renders differently.
    EXPECT_NE(render(dir, "whole", whole.string(), t), written);
  }
  const auto meta = nlohmann::json::parse(test::readFileBytes(dir / "read.json"));
  const auto& read = meta["dataset"]["read"];
  EXPECT_EQ(read["file_dims"], nlohmann::json({kX, kY, kZ}));
  EXPECT_EQ(read["crop"], nlohmann::json({{c.lo.x, c.hi.x}, {c.lo.y, c.hi.y}, {c.lo.z, c.hi.z}}));
  EXPECT_EQ(read["stride"], c.stride);
  const glm::ivec3 dims = (c.hi - c.lo + c.stride - 1) / c.stride;
  EXPECT_EQ(meta["dataset"]["dims"], nlohmann::json({dims.x, dims.y, dims.z}));
  EXPECT_EQ(meta["dataset"]["spacing"], nlohmann::json({c.stride, c.stride, c.stride}));
  EXPECT_FALSE(
      nlohmann::json::parse(test::readFileBytes(dir / "written.json"))["dataset"].contains("read"));
}

INSTANTIATE_TEST_SUITE_P(Cases, CropStrideRender, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(CropStrideInfo, SaysWhatWasRead) {
  const fs::path dir = test::scratchDir();
  const fs::path whole = writeNrrd(dir / "whole.nrrd", {0, 0, 0}, {kX, kY, kZ}, 1);
  const auto text = test::runVsil("info '" + whole.string() + "' --crop 1:33,:,2: --stride 4");
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_NE(text.out.find("dims      8 x 9 x 11 (792 samples)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("read      --crop 1:33,0:36,2:44 --stride 4 of 40 x 36 x 44"),
            std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("spacing   4 4 4"), std::string::npos) << text.out;
  const auto json = test::runVsil("info --json '" + whole.string() + "' --stride 5");
  ASSERT_EQ(json.exitCode, 0) << json.err;
  const auto info = nlohmann::json::parse(json.out);
  EXPECT_EQ(info["dims"], nlohmann::json({8, 8, 9}));
  EXPECT_EQ(info["read"]["stride"], 5);
  EXPECT_EQ(info["read"]["crop"], nlohmann::json({{0, kX}, {0, kY}, {0, kZ}}));
}

}  // namespace
}  // namespace vsil
