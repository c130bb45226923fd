// vsil measure-width end to end: a PNG of broadened circles in, statistics and JSON out.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/depth_image.h"
#include "core/image_file.h"
#include "digital_curves.h"
#include "postfx/broaden.h"
#include "test_support.h"

namespace vsil {
namespace {

// test::runVsil() calls scratchDir() itself, which empties the calling test's scratch folder;
// the inputs therefore live in a sibling folder of their own.
std::filesystem::path inputDir(const std::string& name) {
  const auto dir = test::scratchDir().parent_path() / ("measure-width-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(MeasureWidthCommand, ReportsWidthsAndWidthAgainstDepth) {
  const auto dir = inputDir("depth");
  const FrameBuffers frame =
      test::discsFrame({300, 160}, {{{75.3, 80.2}, 50, 0.0}, {{225.4, 79.6}, 50, 1.0}});
  FftGaussianBlur blur;
  const cv::Mat1b band = broadenSilhouettes(frame, WidthLaw::depthAdaptive(4, 12), blur);
  cv::Mat1b image(band.size(), std::uint8_t(255));
  image.setTo(0, band);
  writePng(dir / "lines.png", image);
  writePng(dir / "depth.png", encodeDepthImage(frame.depth));

  const auto result =
      test::runVsil("measure-width " + (dir / "lines.png").string() + " --json " +
                    (dir / "report.json").string() + " --depth " + (dir / "depth.png").string() +
                    " --bins 2 --plot " + (dir / "plot.png").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  std::ifstream in(dir / "report.json");
  const auto report = nlohmann::json::parse(in);
  const auto& bins = report["by_depth"];
  ASSERT_EQ(bins.size(), 2u);
  // Broadening within max(0.75, 6 %) of the law, the estimator within 0.25 px (line_width.h).
  EXPECT_NEAR(bins[0]["median_width"].get<double>(), 4.0, 1.0);
  EXPECT_NEAR(bins[1]["median_width"].get<double>(), 12.0, 1.0);
  EXPECT_FALSE(readImage(dir / "plot.png").empty());
}

// A depth image that gives no line pixel a depth (all 0: none) leaves every bin empty: the
// report says so in a warning, and the empty bins' widths are null (they read 0 px).
TEST(MeasureWidthCommand, ADepthImageWithoutDepthsWarnsAndLeavesWidthsNull) {
  const auto dir = inputDir("no-depth");
  cv::Mat1b image(40, 60, std::uint8_t(255));
  image(cv::Rect(5, 10, 50, 4)).setTo(0);
  writePng(dir / "lines.png", image);
  writePng(dir / "depth.png", cv::Mat1w(image.size(), std::uint16_t(0)));
  const auto result =
      test::runVsil("measure-width " + (dir / "lines.png").string() + " --depth " +
                    (dir / "depth.png").string() + " --json " + (dir / "report.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(
      result.err.find("vsil: warning: --depth " + (dir / "depth.png").string() + ": none of the "),
      std::string::npos)
      << result.err;
  std::ifstream in(dir / "report.json");
  const auto report = nlohmann::json::parse(in);  // kept: the loop walks into it
  for (const auto& bin : report["by_depth"]) {
    EXPECT_EQ(bin["count"], 0);
    EXPECT_TRUE(bin["mean_width"].is_null());
  }
}

TEST(MeasureWidthCommand, BadInputExitsTwoNamingTheProblem) {
  const auto dir = inputDir("bad");
  const auto missing = test::runVsil("measure-width " + (dir / "nope.png").string());
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("nope.png"), std::string::npos) << missing.err;
  writePng(dir / "white.png", cv::Mat1b(10, 10, std::uint8_t(255)));
  const auto badColor =
      test::runVsil("measure-width " + (dir / "white.png").string() + " --line-color nocolor");
  EXPECT_EQ(badColor.exitCode, 2);
  EXPECT_NE(badColor.err.find("--line-color"), std::string::npos) << badColor.err;
}

}  // namespace
}  // namespace vsil
