// OSMesa and EGL on the same llvmpipe draw the same bytes, for every technique (and silhouette's
// two pipelines): the back ends differ only in how the context is made. Each case renders through
// the built `vsil` with --gl osmesa and with EGL on llvmpipe (Mesa's software device; a GPU would
// draw other bytes), then compares the state, depth and illustration images byte for byte and the
// metadata's counts. Techniques come from the table of techniques (every value of each of their
// choice options), so a new one is covered when it lands.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "backend_support.h"
#include "slicing/technique_table.h"
#include "test_support.h"

namespace vsil {
namespace {

// A technique and the flags of one variant (e.g. "--pipeline paper"); `name` for the test name.
struct Case {
  std::string technique;
  std::string flags;
  std::string name;
};

// The volumes and views each case renders: a generated torus in perspective, and the NegHip
// dataset orthographic from below (empty-space skipping, clipping at the image border).
const std::vector<std::string> kScenes = {
    "gen:torus:48 --size 96x80 --view 25,15",
    test::datasetPath("neghip_64x64x64_uint8.nhdr").string() +
        " --size 120x104 --ortho --zoom 1.3 --view 40,-20",
};

// Bytes that differ between two images of the same size and type (-1 when they cannot be
// compared: missing, or of another size or type).
long differingBytes(const std::filesystem::path& a, const std::filesystem::path& b) {
  const cv::Mat imageA = cv::imread(a.string(), cv::IMREAD_UNCHANGED);
  const cv::Mat imageB = cv::imread(b.string(), cv::IMREAD_UNCHANGED);
  if (imageA.empty() || imageB.empty() || imageA.size() != imageB.size() ||
      imageA.type() != imageB.type()) {
    return -1;
  }
  const cv::Mat bytesA = imageA.reshape(1, 1), bytesB = imageB.reshape(1, 1);
  cv::Mat different;
  cv::compare(bytesA, bytesB, different, cv::CMP_NE);
  return long(cv::countNonZero(different));
}

class BackendIdentity : public ::testing::TestWithParam<Case> {};

TEST_P(BackendIdentity, OsmesaAndEglOnLlvmpipeDrawTheSameBytes) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Osmesa);
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  const test::ScopedEnvironment noBackend("VSIL_GL", nullptr), noDevice("VSIL_GL_DEVICE", nullptr);
  const std::optional<int> software = test::softwareEglDevice();
  const std::string eglFlags =
      software ? "--gl egl --gl-device " + std::to_string(*software) : "--gl egl";
  const Case& c = GetParam();
  const TechniqueInfo& technique = findTechnique(c.technique);
  const auto dir = test::scratchDir();
  VSIL_REQUIRE_DATASETS();  // the NegHip scene

  for (std::size_t scene = 0; scene < kScenes.size(); ++scene) {
    SCOPED_TRACE(kScenes[scene]);
    nlohmann::json meta[2];
    const std::string flags[2] = {"--gl osmesa", eglFlags};
    for (int b = 0; b < 2; ++b) {
      const auto prefix = dir / (std::to_string(scene) + (b ? "-egl" : "-osmesa"));
      const std::string outputs =
          (technique.outputs.state ? " --state-out " + prefix.string() + "-state.png" : "") +
          (technique.outputs.depth ? " --depth-out " + prefix.string() + "-depth.png" : "");
      const auto result =
          test::runVsil("render " + kScenes[scene] + " --technique " + c.technique + " " + c.flags +
                        " --fill shaded --width 3 " + flags[b] + " --out " + prefix.string() +
                        ".png" + outputs + " --meta-out " + prefix.string() + ".json");
      ASSERT_EQ(result.exitCode, 0) << flags[b] << ": " << result.err;
      meta[b] = nlohmann::json::parse(test::readFileBytes(prefix.string() + ".json"));
    }
    EXPECT_EQ(meta[0]["gl"]["backend"], "osmesa");
    EXPECT_EQ(meta[1]["gl"]["backend"], "egl");
    const std::string renderer = meta[1]["gl"]["renderer"];
    if (renderer.find("llvmpipe") == std::string::npos) {
      if (test::allBackendsRequired()) FAIL() << "EGL renders on " << renderer;
      GTEST_SKIP() << "EGL renders on " << renderer << " here, not llvmpipe: nothing to compare";
    }
    EXPECT_EQ(meta[0]["gl"]["renderer"], renderer) << "the same llvmpipe on both sides";

    // The frames are not empty, so equal bytes mean something.
    const auto& pixels = meta[0]["pixels"];
    EXPECT_GT(pixels.contains("covered")
                  ? pixels["covered"].get<int>()
                  : pixels["silhouette"].get<int>() + pixels["filled"].get<int>(),
              100);
    EXPECT_EQ(meta[0]["pixels"], meta[1]["pixels"]);
    EXPECT_EQ(meta[0]["slices"], meta[1]["slices"]);
    EXPECT_EQ(meta[0]["camera"], meta[1]["camera"]);
    for (const char* image : {"-state.png", "-depth.png", ".png"}) {
      if (std::string(image) == "-state.png" && !technique.outputs.state) continue;
      if (std::string(image) == "-depth.png" && !technique.outputs.depth) continue;
      const auto osmesa = dir / (std::to_string(scene) + "-osmesa" + image);
      const auto egl = dir / (std::to_string(scene) + "-egl" + image);
      EXPECT_EQ(differingBytes(osmesa, egl), 0) << image << ": " << osmesa << " vs " << egl;
    }
  }
}

// Every technique, once per value of each of its choice options (silhouette's pipelines).
std::vector<Case> cases() {
  std::vector<Case> all;
  for (const auto& technique : techniqueTable()) {
    std::vector<Case> variants{{technique.name, "", technique.name}};
    for (const auto& option : technique.options) {
      if (option.kind != OptionKind::Choice) continue;
      std::vector<Case> expanded;
      for (const auto& variant : variants) {
        for (const auto& choice : option.choices) {
          expanded.push_back({technique.name, variant.flags + " " + option.flag() + " " + choice,
                              variant.name + "_" + choice});
        }
      }
      variants = expanded;
    }
    all.insert(all.end(), variants.begin(), variants.end());
  }
  return all;
}

INSTANTIATE_TEST_SUITE_P(EveryTechnique, BackendIdentity, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.name;
                           // Test names: letters, digits, _ (choices such as entry-plus-steps).
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace vsil
