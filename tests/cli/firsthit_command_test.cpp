// `firsthit`, the smallest technique (one folder, one table entry), through the built binary:
// a colour image with a depth image, the outputs it has and refuses, and its metadata.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/depth_image.h"
#include "core/image_file.h"
#include "test_support.h"

namespace vsil {
namespace {

TEST(FirstHitCommand, GreyIsOneMinusTheDepthWrittenBesideIt) {
  const auto dir = test::scratchDir();
  const std::string out = (dir / "hit.png").string(), depth = (dir / "depth.png").string(),
                    meta = (dir / "meta.json").string();
  const auto result = test::runVsil(
      "render gen:sphere:48 --technique firsthit --iso 0.5 --ortho --zoom 2 "
      "--size 80x64 --background black --out " +
      out + " --depth-out " + depth + " --meta-out " + meta);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const cv::Mat image = cv::imread(out, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(image.type(), CV_8UC3);
  const cv::Mat1f d = decodeDepthImage(readImage(depth), depth);
  ASSERT_EQ(d.size(), image.size());
  int hits = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const cv::Vec3b bgr = image.at<cv::Vec3b>(y, x);
      EXPECT_TRUE(bgr[0] == bgr[1] && bgr[1] == bgr[2]) << "grey at " << x << "," << y;
      if (std::isnan(d(y, x))) {
        EXPECT_EQ(bgr[0], 0) << "background where no hit, at " << x << "," << y;
        continue;
      }
      ++hits;
      // 8-bit grey of 1 - d, the 16-bit depth of d: within half a grey step and a depth step.
      EXPECT_NEAR(bgr[0] / 255.0, 1.0 - d(y, x), 0.5 / 255 + 1e-4) << x << "," << y;
    }
  }
  EXPECT_GT(hits, 500);
  // The sphere's front: its centre nearer than its rim.
  const cv::Point centre(image.cols / 2, image.rows / 2);
  EXPECT_LT(d(centre), d(centre.y, centre.x + 14));

  const auto json = nlohmann::json::parse(test::readFileBytes(meta));
  EXPECT_EQ(json["parameters"]["technique"], "firsthit");
  EXPECT_EQ(json["parameters"]["iso"], 0.5);
  EXPECT_FALSE(json["parameters"].contains("pipeline")) << "only the technique's own options";
  EXPECT_FALSE(json["parameters"].contains("width_near")) << "no lines, no widths";
  EXPECT_EQ(json["pixels"]["covered"], hits);
}

TEST(FirstHitCommand, RefusesAStateImageBeforeAnyWork) {
  const auto dir = test::scratchDir();
  const auto result =
      test::runVsil("render gen:sphere:16 --technique firsthit --out " + (dir / "x.png").string() +
                    " --state-out " + (dir / "s.png").string());
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err, "vsil: --state-out: technique 'firsthit' makes no state image\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "s.png"));
}

}  // namespace
}  // namespace vsil
