// mip and demip through the built binary: demip with both weights 0 writes mip's PNG byte for
// byte; demip's depth image and metadata; mip makes no depth image.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/depth_image.h"
#include "core/image_file.h"
#include "test_support.h"

namespace vsil {
namespace {

TEST(MipCommand, DemipWithoutWeightsWritesMipsBytes) {
  const auto dir = test::scratchDir();
  const std::string common = " --size 96x80 --view 30,20 --background black";
  for (const std::string input : {"gen:blobs:64", "gen:spheres:48"}) {
    const std::string mip = (dir / "mip.png").string(), demip = (dir / "demip.png").string();
    const auto a = test::runVsil("render " + input + " --technique mip" + common + " --out " + mip);
    ASSERT_EQ(a.exitCode, 0) << a.err;
    const auto b = test::runVsil("render " + input + " --technique demip --depth-weight 0 " +
                                 "--sphere-weight 0" + common + " --out " + demip);
    ASSERT_EQ(b.exitCode, 0) << b.err;
    const std::string mipBytes = test::readFileBytes(mip);
    EXPECT_GT(mipBytes.size(), 100u);
    EXPECT_EQ(mipBytes, test::readFileBytes(demip)) << input;
    // The default weight changes the picture: the comparison above can fail.
    const auto c =
        test::runVsil("render " + input + " --technique demip" + common + " --out " + demip);
    ASSERT_EQ(c.exitCode, 0) << c.err;
    EXPECT_NE(mipBytes, test::readFileBytes(demip)) << input;
  }
}

TEST(MipCommand, DemipWritesTheFirstHitDepthAndEveryParameter) {
  const auto dir = test::scratchDir();
  const std::string out = (dir / "d.png").string(), depth = (dir / "depth.png").string(),
                    meta = (dir / "meta.json").string();
  const auto result = test::runVsil(
      "render gen:blobs:48 --technique demip --sphere-weight 0.5 --sphere-map green-blue "
      "--size 64x64 --out " +
      out + " --depth-out " + depth + " --meta-out " + meta);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const cv::Mat1f d = decodeDepthImage(readImage(depth), depth);
  int withDepth = 0;
  for (auto it = d.begin(); it != d.end(); ++it) {
    if (std::isnan(*it)) continue;
    ++withDepth;
    EXPECT_GE(*it, 0.0f);
    EXPECT_LE(*it, 1.0f);
  }
  const auto json = nlohmann::json::parse(test::readFileBytes(meta));
  const auto& p = json["parameters"];
  EXPECT_EQ(p["technique"], "demip");
  EXPECT_EQ(p["depth_weight"], 0.15);
  EXPECT_EQ(p["depth_mode"], "exact");
  EXPECT_EQ(p["sphere_weight"], 0.5);
  EXPECT_EQ(p["sphere_map"], "green-blue");
  EXPECT_EQ(p["sphere_rotate"], "0,0");
  EXPECT_EQ(p["sphere_frame"], "view");
  // Not given: the default window from the histogram, as it was used (default_pictures_test).
  EXPECT_FALSE(p["window"].get<std::string>().empty());
  // Not given: 5 % of the value range.
  const auto range = json["dataset"]["value_range"];
  EXPECT_NEAR(p["material_eps"].get<double>(),
              0.05 * (range[1].get<double>() - range[0].get<double>()), 1e-9);
  EXPECT_EQ(json["pixels"]["covered"], withDepth) << "every pixel shown has its first hit";
  EXPECT_GT(withDepth, 100);
}

// With --tf the metadata records the function's points in the data's values: a preset's are
// mapped per volume (round 18: "window": "" alone said nothing of where the ramp landed).
TEST(MipCommand, ATransferFunctionIsRecordedInTheDatasValues) {
  const auto dir = test::scratchDir();
  const std::string out = (dir / "m.png").string(), meta = (dir / "meta.json").string();
  const auto result = test::runVsil(
      "render gen:blobs:48 --technique mip --tf ct-bone --size 32x32"
      " --out " +
      out + " --meta-out " + meta);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto json = nlohmann::json::parse(test::readFileBytes(meta));
  const auto& points = json["parameters"]["transfer_function"];
  ASSERT_EQ(points.size(), 4u) << "ct-bone's four points";
  // Rising, and not the preset's Hounsfield values (-3024 .. 3071) on these 0 .. 1 blobs.
  for (std::size_t i = 1; i < points.size(); ++i) {
    EXPECT_GT(points[i]["value"].get<double>(), points[i - 1]["value"].get<double>());
  }
  EXPECT_LT(points.back()["value"].get<double>(), 10.0);
}

// --sphere-map FILE.png: the render reads the map, the metadata names the file and its size,
// and --legend draws it (the inset's pixels take the map's one colour).
TEST(MipCommand, DemipReadsAPngSphereMapAndRecordsIt) {
  const auto dir = test::scratchDir();
  const std::string map = (dir / "map.png").string(), out = (dir / "d.png").string(),
                    meta = (dir / "meta.json").string();
  writePng(map, cv::Mat3b(6, 12, cv::Vec3b(0, 200, 0)));  // green (BGR)
  const auto result =
      test::runVsil("render gen:blobs:48 --technique demip --sphere-weight 1 --sphere-map " + map +
                    " --legend --size 80x80 --out " + out + " --meta-out " + meta);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto json = nlohmann::json::parse(test::readFileBytes(meta));
  const auto& p = json["parameters"];
  EXPECT_EQ(p["sphere_map"], map);
  EXPECT_EQ(p["sphere_map_file"]["path"], map);
  EXPECT_EQ(p["sphere_map_file"]["size"], nlohmann::json::parse("[12, 6]"));
  const cv::Mat image = readImage(out);
  // The legend's disc around (80 − 2 − 8 − 1, 80 − 2 − 8 − 1), off its white cross.
  EXPECT_EQ(image.at<cv::Vec3b>(66, 66), cv::Vec3b(0, 200, 0));
}

TEST(MipCommand, MipRefusesADepthImageBeforeAnyWork) {
  const auto dir = test::scratchDir();
  const auto result =
      test::runVsil("render gen:sphere:16 --technique mip --out " + (dir / "x.png").string() +
                    " --depth-out " + (dir / "d.png").string());
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err, "vsil: --depth-out: technique 'mip' makes no depth image\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

}  // namespace
}  // namespace vsil
