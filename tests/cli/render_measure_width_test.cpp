// vsil render → vsil measure-width, end to end through the built binary: a sphere rendered with
// --width 9 measures 9 px, and the JSON report has its documented schema.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace vsil {
namespace {

TEST(RenderThenMeasureWidth, SphereAtWidthNineMeasuresNine) {
  // Inputs in a folder of their own: runVsil() does not touch it.
  const auto dir = test::scratchDir().parent_path() / "render-measure-width";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
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
    for (const char* key : {"depth_from", "depth_to", "count", "mean_width", "median_width"}) {
      EXPECT_TRUE(bin[key].is_number()) << key;
    }
    binned += bin["count"].get<int>();
    // A sphere's silhouette lies at one depth, its centre's (near 0.5 here): a fixed width there.
    if (bin["count"].get<int>() > 20) {
      EXPECT_NEAR(bin["median_width"].get<double>(), 9.0, 0.5) << bin.dump();
    }
  }
  EXPECT_GT(binned, widths["count"].get<int>() / 2) << "most samples find a depth";
}

}  // namespace
}  // namespace vsil
