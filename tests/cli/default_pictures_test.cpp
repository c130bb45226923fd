// What `vsil render FILE --technique T` gives with no other options on the classic datasets: the
// object over the background, and nothing but the background around it. The object's mask comes
// from another technique: silhouette's footprint at its default iso (Otsu's threshold), grown by
// a few pixels for the sampling at its edge. Outside it, mip and demip (over black) and
// illustrate and semantic (over white) must leave the background within a few levels: before
// their defaults came from the histogram, air and CT noise made a dark box (the MIP family),
// a fog box, or with boundary and silhouette enhancement a spray hiding the object (illustrate).
// Also: the default window is recorded in the metadata, the presets of --tf render, an unknown
// preset is one line, and `vsil info` suggests a preset.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "core/image_file.h"
#include "test_support.h"

namespace vsil {
namespace {

constexpr const char* kSize = " --size 128x128";

// Pixels silhouette covers at its default iso, grown by `grow` pixels.
cv::Mat1b objectMask(const std::string& input, int grow) {
  const auto dir = test::scratchDir();
  const std::string out = (dir / "s.png").string(), state = (dir / "state.png").string();
  const auto run = test::runVsil("render " + input + " --technique silhouette" + kSize + " --out " +
                                 out + " --state-out " + state);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  cv::Mat1b mask = readImage(state) > 0;
  cv::dilate(mask, mask,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * grow + 1, 2 * grow + 1}));
  return mask;
}

cv::Mat1b greyOf(const std::string& path) {
  const cv::Mat image = readImage(path);
  cv::Mat1b grey;
  if (image.channels() == 1) return image;
  cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
}

struct Coverage {
  int outsideOff = 0;  // pixels outside the mask more than `levels` from the background
  int outside = 0;
  int insideShown = 0;  // pixels inside the mask more than 40 levels from the background
  int inside = 0;
};

Coverage coverage(const cv::Mat1b& grey, const cv::Mat1b& mask, int background, int levels) {
  Coverage c;
  for (int y = 0; y < grey.rows; ++y) {
    for (int x = 0; x < grey.cols; ++x) {
      const int off = std::abs(int(grey(y, x)) - background);
      if (mask(y, x)) {
        ++c.inside;
        c.insideShown += off > 40;
      } else {
        ++c.outside;
        c.outsideOff += off > levels;
      }
    }
  }
  return c;
}

const char* const kDatasets[] = {"aneurism.vti", "bonsai.vti", "engine.vti", "tooth.nrrd"};

TEST(DefaultPictures, TheMipFamilyShowsTheObjectOverBlackAndNothingAroundIt) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  for (const char* name : kDatasets) {
    const std::string input = test::datasetPath(name).string();
    const cv::Mat1b mask = objectMask(input, 3);
    for (const std::string technique : {"mip", "demip"}) {
      const std::string out = (dir / (technique + ".png")).string();
      const auto run =
          test::runVsil("render " + input + " --technique " + technique + kSize + " --out " + out);
      ASSERT_EQ(run.exitCode, 0) << run.err;
      const Coverage c = coverage(greyOf(out), mask, 0, 3);
      EXPECT_EQ(c.outsideOff, 0) << name << " " << technique << ": of " << c.outside
                                 << " pixels around the object";
      EXPECT_GT(c.outside, 128 * 128 / 10) << name << ": the mask leaves some background";
      EXPECT_GT(c.insideShown, c.inside / 5) << name << " " << technique << ": the object shows";
    }
  }
}

TEST(DefaultPictures, IllustrateAndSemanticLeaveNoFogAroundTheObject) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  for (const char* name : kDatasets) {
    const std::string input = test::datasetPath(name).string();
    const cv::Mat1b mask = objectMask(input, 3);
    for (const std::string options :
         {"--technique illustrate", "--technique illustrate --style fig4-boundary-silhouette",
          "--technique semantic"}) {
      const std::string out = (dir / "i.png").string();
      const auto run = test::runVsil("render " + input + " " + options + kSize + " --out " + out);
      ASSERT_EQ(run.exitCode, 0) << run.err;
      const Coverage c = coverage(greyOf(out), mask, 255, 4);
      EXPECT_LE(c.outsideOff, c.outside / 200)
          << name << " " << options << ": of " << c.outside << " pixels around the object";
      EXPECT_GT(c.insideShown, c.inside / 10) << name << " " << options << ": the object shows";
    }
  }
}

// The window used is in the metadata, and it is `vsil info`'s default window: Otsu's threshold
// to the 99.5th percentile above it. lmip's threshold follows the window's low end.
TEST(DefaultPictures, TheDefaultWindowIsRecordedAndLmipFollowsIt) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const std::string input = test::datasetPath("engine.vti").string();
  const auto info = test::runVsil("info " + input + " --json");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const auto facts = nlohmann::json::parse(info.out);
  const double low = facts["default_window"][0], high = facts["default_window"][1];
  EXPECT_EQ(low, facts["default_iso"].get<double>());
  EXPECT_GT(high, low);
  EXPECT_LE(high, facts["max"].get<double>());
  const std::string meta = (dir / "meta.json").string(), out = (dir / "o.png").string();
  for (const std::string technique : {"mip", "demip", "lmip"}) {
    const auto run = test::runVsil("render " + input + " --technique " + technique + kSize +
                                   " --out " + out + " --meta-out " + meta);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto p = nlohmann::json::parse(test::readFileBytes(meta))["parameters"];
    double a = 0, b = 0;
    ASSERT_EQ(std::sscanf(p["window"].get<std::string>().c_str(), "%lf,%lf", &a, &b), 2)
        << p["window"];
    EXPECT_DOUBLE_EQ(a, low) << technique;
    EXPECT_DOUBLE_EQ(b, high) << technique;
    EXPECT_EQ(p["background"], "#000000ff") << technique;
    if (technique == "lmip") {
      EXPECT_DOUBLE_EQ(p["lmip_threshold"].get<double>(), low);
    }
  }
  // A given window: lmip's threshold is its low end; a given threshold wins.
  auto run = test::runVsil("render " + input + " --technique lmip --window 120,200" + kSize +
                           " --out " + out + " --meta-out " + meta);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  auto p = nlohmann::json::parse(test::readFileBytes(meta))["parameters"];
  EXPECT_EQ(p["window"], "120,200");
  EXPECT_EQ(p["lmip_threshold"], 120.0);
  run = test::runVsil("render " + input + " --technique lmip --lmip-threshold 90" + kSize +
                      " --out " + out + " --meta-out " + meta);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  p = nlohmann::json::parse(test::readFileBytes(meta))["parameters"];
  EXPECT_EQ(p["lmip_threshold"], 90.0);
  // --background still chooses.
  run = test::runVsil("render " + input + " --technique mip --background white" + kSize +
                      " --out " + out + " --meta-out " + meta);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  p = nlohmann::json::parse(test::readFileBytes(meta))["parameters"];
  EXPECT_EQ(p["background"], "#ffffffff");
}

TEST(DefaultPictures, EveryPresetRendersOnAClassicDataset) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const std::string input = test::datasetPath("engine.vti").string();
  const cv::Mat1b mask = objectMask(input, 3);
  for (const std::string preset : {"ct-bone", "ct-soft-tissue", "ct-angio", "mr-default", "ramp"}) {
    for (const std::string technique : {"illustrate", "mip"}) {
      const std::string out = (dir / (preset + "-" + technique + ".png")).string(),
                        meta = (dir / "meta.json").string();
      const auto run = test::runVsil("render " + input + " --technique " + technique + " --tf " +
                                     preset + kSize + " --out " + out + " --meta-out " + meta);
      ASSERT_EQ(run.exitCode, 0) << preset << " " << technique << ": " << run.err;
      const Coverage c = coverage(greyOf(out), mask, technique == "mip" ? 0 : 255, 4);
      EXPECT_GT(c.insideShown, 100) << preset << " " << technique << ": the object shows";
      EXPECT_LE(c.outsideOff, c.outside / 200) << preset << " " << technique << ": no fog";
      const auto p = nlohmann::json::parse(test::readFileBytes(meta))["parameters"];
      EXPECT_EQ(p["tf"], preset);
    }
  }
}

TEST(DefaultPictures, AnUnknownPresetIsOneLineAndNoFile) {
  const auto dir = test::scratchDir();
  const std::string out = (dir / "x.png").string();
  for (const std::string technique : {"mip", "illustrate"}) {
    const auto run = test::runVsil("render gen:sphere:16 --technique " + technique +
                                   " --tf ct-bones --out " + out);
    EXPECT_NE(run.exitCode, 0);
    EXPECT_EQ(run.err,
              "vsil: --tf: unknown preset \"ct-bones\" (presets: ct-angio, ct-bone, "
              "ct-soft-tissue, mr-default, ramp; or a .json file)\n");
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

// A CT in HU (int16 with air at −1000) gets ct-bone; an 8-bit volume the ramp.
TEST(DefaultPictures, InfoSuggestsAPreset) {
  const auto dir = test::scratchDir();
  const auto nrrd = dir / "ct.nrrd";
  {
    std::ofstream file(nrrd, std::ios::binary);
    file << "NRRD0004\ntype: short\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n"
            "endian: little\n\n";
    for (int i = 0; i < 512; ++i) {
      const std::int16_t hu = std::int16_t(i % 3 == 0 ? 700 : -1000);
      file.write(reinterpret_cast<const char*>(&hu), 2);
    }
  }
  auto run = test::runVsil("info " + nrrd.string());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("\nsuggested: --tf ct-bone  (values in HU)\n"), std::string::npos)
      << run.out;
  run = test::runVsil("info " + nrrd.string() + " --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["suggested_tf"], "ct-bone");
  // ct-bone renders on it (the HU values as they are; the mapping itself: core tests).
  const std::string meta = (dir / "meta.json").string();
  run = test::runVsil("render " + nrrd.string() +
                      " --technique mip --tf ct-bone --size 32x32 --out " +
                      (dir / "ct.png").string() + " --meta-out " + meta);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto pixels = nlohmann::json::parse(test::readFileBytes(meta))["pixels"];
  EXPECT_GT(pixels["covered"].get<int>(), 100);
  EXPECT_LT(pixels["covered"].get<int>(), 32 * 32);
  run = test::runVsil("info gen:sphere:16 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["suggested_tf"], "ramp");
}

}  // namespace
}  // namespace vsil
