// vsil render → vsil measure-width, end to end through the built binary: a sphere rendered with
// --width 9 measures 9 px, and the JSON report has its documented schema.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/depth_image.h"
#include "core/image_file.h"
#include "test_support.h"
#include "width_tolerances.h"

namespace vsil {
namespace {

TEST(RenderThenMeasureWidth, SphereAtWidthNineMeasuresNine) {
  const auto dir = test::scratchDir();
  const auto out = (dir / "out.png").string(), depth = (dir / "depth.png").string(),
             state = (dir / "state.png").string(), json = (dir / "report.json").string();
  const auto render = test::runVsil(
      "render gen:sphere:64 --ortho --view 20,10 --size 240x240 "
      "--width 9 --out " +
      out + " --depth-out " + depth + " --state-out " + state);
  ASSERT_EQ(render.exitCode, 0) << render.err;
  const auto measure =
      test::runVsil("measure-width " + out + " --depth " + depth + " --json " + json);
  ASSERT_EQ(measure.exitCode, 0) << measure.err;

  std::ifstream in(json);
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["image"], out);
  EXPECT_EQ(report["line_color"], "black");
  const auto& widths = report["widths"];
  for (const char* key :
       {"count", "mean", "median", "min", "max", "p05", "p25", "p75", "p95", "bin_width"}) {
    EXPECT_TRUE(widths[key].is_number()) << key;
  }
  ASSERT_TRUE(widths["histogram"].is_array());
  int histogramTotal = 0;
  for (const auto& count : widths["histogram"]) histogramTotal += count.get<int>();
  EXPECT_EQ(histogramTotal, widths["count"].get<int>());
  // Broadening within max(0.5, 4 %) of 9 (tests/postfx_gl), measure-width within 0.25 px
  // (postfx/line_width.h).
  EXPECT_NEAR(widths["median"].get<double>(), 9.0, 0.5) << measure.out;
  EXPECT_NEAR(widths["mean"].get<double>(), 9.0, 0.5) << measure.out;

  ASSERT_TRUE(report["by_depth"].is_array());
  ASSERT_EQ(report["by_depth"].size(), 10u);
  int binned = 0;
  for (const auto& bin : report["by_depth"]) {
    for (const char* key : {"depth_from", "depth_to", "count"}) {
      EXPECT_TRUE(bin[key].is_number()) << key;
    }
    // An empty bin has no width (null), the others a number.
    for (const char* key : {"mean_width", "median_width"}) {
      EXPECT_TRUE(bin["count"] == 0 ? bin[key].is_null() : bin[key].is_number()) << key;
    }
    binned += bin["count"].get<int>();
    // A sphere's silhouette lies at one depth, its centre's (near 0.5 here): a fixed width there.
    if (bin["count"].get<int>() > 20) {
      EXPECT_NEAR(bin["median_width"].get<double>(), 9.0, 0.5) << bin.dump();
    }
  }
  EXPECT_GT(binned, widths["count"].get<int>() / 2) << "most samples find a depth";
  EXPECT_EQ(measure.err, "") << "a sphere's line is a line";
  EXPECT_EQ(report["warnings"], nlohmann::json::array());
}

// A line wider than the object it outlines fills it: measure-width still reports the region
// (exit 0) and says that its widths are no line's (round 14: 23.3 px read for a 12 px line).
TEST(RenderThenMeasureWidth, ALineWiderThanTheObjectIsSaidToBeNoLine) {
  const auto dir = test::scratchDir();
  const auto out = (dir / "out.png").string();
  ASSERT_EQ(test::runVsil("render gen:sphere:24 --ortho --view 0,0 --size 64x64 --width 30 "
                          "--out " +
                          out)
                .exitCode,
            0);
  const auto json = (dir / "m.json").string();
  const auto measure = test::runVsil("measure-width " + out + " --json " + json);
  ASSERT_EQ(measure.exitCode, 0) << measure.err;
  EXPECT_NE(measure.err.find("vsil: warning: " + out + ": "), std::string::npos) << measure.err;
  EXPECT_NE(measure.err.find("no longer than wide"), std::string::npos) << measure.err;
  // The report keeps it beside the numbers it qualifies.
  std::ifstream in(json);
  const auto report = nlohmann::json::parse(in);
  ASSERT_EQ(report["warnings"].size(), 1u) << report.dump();
  EXPECT_NE(report["warnings"][0].get<std::string>().find("no longer than wide"),
            std::string::npos);
}

// A width study as a user runs it (the issue that found the depth PNG read back wrongly):
// the Engine rendered with a depth law, its depth image into measure-width. Every depth bin
// that holds samples must lie where silhouettes lie, and its median width on the law.
TEST(RenderThenMeasureWidth, DepthLawStudyOnTheEngine) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const auto out = (dir / "engine.png").string(), depth = (dir / "depth.png").string(),
             json = (dir / "report.json").string(), plot = (dir / "plot.png").string();
  const double nearWidth = 8, farWidth = 2;
  const auto render = test::runVsil("render " + test::datasetPath("engine.vti").string() +
                                    " --iso 80 --view 40,25 --width-near 8 --width-far 2 --out " +
                                    out + " --depth-out " + depth);
  ASSERT_EQ(render.exitCode, 0) << render.err;
  const auto measure = test::runVsil("measure-width " + out + " --depth " + depth + " --plot " +
                                     plot + " --json " + json);
  ASSERT_EQ(measure.exitCode, 0) << measure.err;
  EXPECT_TRUE(std::filesystem::exists(plot));

  // Where the silhouettes lie, straight from the depth image.
  const cv::Mat1f lineDepth = decodeDepthImage(readImage(depth), depth);
  double lo = 1, hi = 0;
  int lines = 0;
  for (float d : cv::Mat_<float>(lineDepth)) {
    if (std::isnan(d)) continue;
    lo = std::min(lo, double(d));
    hi = std::max(hi, double(d));
    ++lines;
  }
  ASSERT_GT(lines, 500);

  std::ifstream in(json);
  const auto report = nlohmann::json::parse(in);
  int binned = 0, checked = 0;
  for (const auto& bin : report["by_depth"]) {
    const int count = bin["count"].get<int>();
    if (count == 0) continue;
    binned += count;
    const double from = bin["depth_from"].get<double>(), to = bin["depth_to"].get<double>();
    EXPECT_TRUE(to > lo && from <= hi)
        << "samples in bin " << bin.dump() << " where no silhouette lies (silhouettes at " << lo
        << ".." << hi << ")";
    if (count < 100) continue;  // a few samples near a bin edge say little about the law
    const double d = 0.5 * (from + to);
    const double law = nearWidth + (farWidth - nearWidth) * d;
    EXPECT_NEAR(bin["median_width"].get<double>(), law, test::depthTolerance(law)) << bin.dump();
    ++checked;
  }
  EXPECT_GT(binned, report["widths"]["count"].get<int>() / 2) << "most samples find a depth";
  EXPECT_GE(checked, 3) << "the law is checked over several depths";
}

}  // namespace
}  // namespace vsil
