// Colours, composition and the shared postfx command-line flags.
#include "postfx/compose.h"

#include <gtest/gtest.h>

#include "cli/cli_postfx_options.h"
#include "core/error.h"
#include "digital_curves.h"

namespace vsil {
namespace {

TEST(Color, NamesAndHexForms) {
  EXPECT_EQ(parseColor("black", "--c"), (Rgba{0, 0, 0, 255}));
  EXPECT_EQ(parseColor("White", "--c"), (Rgba{255, 255, 255, 255}));
  EXPECT_EQ(parseColor("#f80", "--c"), (Rgba{255, 136, 0, 255}));
  EXPECT_EQ(parseColor("#102030", "--c"), (Rgba{16, 32, 48, 255}));
  EXPECT_EQ(parseColor("#10203080", "--c"), (Rgba{16, 32, 48, 128}));
}

TEST(Color, BadInputNamesTheFlag) {
  for (const char* bad : {"", "#12", "#gggggg", "blurple", "#1234567"}) {
    try {
      parseColor(bad, "--line-color");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--line-color"), std::string::npos) << e.what();
    }
  }
}

TEST(Compose, LinesFillAndBackground) {
  const FrameBuffers frame = test::discsFrame({100, 100}, {{{50.3, 49.6}, 30, 0.5}});
  PostfxOptions options;
  options.width = WidthLaw::fixed(5);
  options.lineColor = {255, 0, 0, 255};
  options.background = {0, 0, 255, 255};
  options.fill = FillMode::Flat;
  options.fillColor = {0, 255, 0, 255};
  FftGaussianBlur blur;
  const cv::Mat image = composeIllustration(frame, options, blur);
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.at<cv::Vec3b>(50, 50), cv::Vec3b(0, 255, 0)) << "centre: fill";
  EXPECT_EQ(image.at<cv::Vec3b>(2, 2), cv::Vec3b(255, 0, 0)) << "corner: background";
  EXPECT_EQ(image.at<cv::Vec3b>(50, 20), cv::Vec3b(0, 0, 255)) << "on the outline: line";
  options.fill = FillMode::Shaded;
  const cv::Mat shaded = composeIllustration(frame, options, blur);
  EXPECT_LT(shaded.at<cv::Vec3b>(50, 28)[1], shaded.at<cv::Vec3b>(50, 50)[1]) << "darker rim";
  options.background = parseColor("transparent", "--background");
  EXPECT_EQ(composeIllustration(frame, options, blur).type(), CV_8UC4);
}

// Colours with an alpha are composited over what is under them (they replaced it: a
// half-transparent fill punched a half-transparent hole in an opaque background); over a
// transparent background they keep their own alpha.
TEST(Compose, ColoursWithAnAlphaGoOverWhatIsUnderThem) {
  const FrameBuffers frame = test::discsFrame({100, 100}, {{{50.3, 49.6}, 30, 0.5}});
  PostfxOptions options;
  options.width = WidthLaw::fixed(5);
  options.lineColor = {0, 0, 255, 128};
  options.background = {255, 255, 255, 255};
  options.fill = FillMode::Flat;
  options.fillColor = {255, 0, 0, 128};
  FftGaussianBlur blur;
  const cv::Mat opaque = composeIllustration(frame, options, blur);
  ASSERT_EQ(opaque.type(), CV_8UC3);
  EXPECT_EQ(opaque.at<cv::Vec3b>(50, 50), cv::Vec3b(127, 127, 255)) << "fill over white (BGR)";
  EXPECT_EQ(opaque.at<cv::Vec3b>(2, 2), cv::Vec3b(255, 255, 255)) << "background";
  // On the outline inside the disc: the line over the fill over white; outside it: over white.
  EXPECT_EQ(opaque.at<cv::Vec3b>(50, 21), cv::Vec3b(191, 63, 127)) << "line over fill";
  EXPECT_EQ(opaque.at<cv::Vec3b>(50, 19), cv::Vec3b(255, 127, 127)) << "line over white";

  options.background = parseColor("transparent", "--background");
  const cv::Mat clear = composeIllustration(frame, options, blur);
  ASSERT_EQ(clear.type(), CV_8UC4);
  EXPECT_EQ(clear.at<cv::Vec4b>(50, 50), cv::Vec4b(0, 0, 255, 128)) << "the fill's own alpha";
  EXPECT_EQ(clear.at<cv::Vec4b>(50, 19), cv::Vec4b(255, 0, 0, 128)) << "the line's own alpha";
}

TEST(Compose, ToneFillShowsTheTechniquesColourAtFilledPixels) {
  FrameBuffers frame = test::discsFrame({100, 100}, {{{50.3, 49.6}, 30, 0.5}});
  // Red fading to green from left to right (straight RGB), red beyond 1 left of x = 50.
  frame.tone.create(frame.state.size());
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) frame.tone(y, x) = cv::Vec3f(1.5f - x / 100.0f, x / 100.0f, 0);
  }
  PostfxOptions options;
  options.width = WidthLaw::fixed(3);
  options.background = Rgba{0, 0, 255, 255};
  options.fill = FillMode::Tone;
  FftGaussianBlur blur;
  const cv::Mat image = composeIllustration(frame, options, blur);
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.at<cv::Vec3b>(50, 61), cv::Vec3b(0, 156, 227)) << "BGR of (0.89, 0.61, 0)";
  EXPECT_EQ(image.at<cv::Vec3b>(50, 31), cv::Vec3b(0, 79, 255)) << "(1.19, 0.31, 0) clamped";
  EXPECT_EQ(image.at<cv::Vec3b>(2, 2), cv::Vec3b(255, 0, 0)) << "Empty: background";
  EXPECT_EQ(fillModeName(FillMode::Tone), std::string("tone"));
}

struct ParsedFlags {
  PostfxOptions options;
  std::vector<std::string> lineFlags;  // the line flags given, in the order they are declared
  std::string error;                   // "" when parsing succeeded
};

ParsedFlags parseFlags(std::vector<std::string> args) {
  ParsedFlags result;
  CLI::App app;
  cli::addPostfxOptions(app, result.options, result.lineFlags);
  std::reverse(args.begin(), args.end());  // CLI11 takes a reversed vector
  try {
    app.parse(args);
  } catch (const InputError& e) {
    result.error = e.what();
  } catch (const CLI::ParseError& e) {
    result.error = std::string("parse: ") + e.what();
  }
  return result;
}

TEST(PostfxFlags, FixedAndAdaptiveWidths) {
  auto fixed = parseFlags({"--width", "7.5"});
  EXPECT_EQ(fixed.error, "");
  EXPECT_EQ(fixed.options.width.near, 7.5);
  EXPECT_TRUE(fixed.options.width.isFixed());
  auto adaptive = parseFlags({"--width-near", "2", "--width-far", "12", "--fill", "shaded"});
  EXPECT_EQ(adaptive.error, "");
  EXPECT_EQ(adaptive.options.width.near, 2);
  EXPECT_EQ(adaptive.options.width.far, 12);
  EXPECT_EQ(adaptive.options.fill, FillMode::Shaded);
  EXPECT_EQ(parseFlags({"--fill", "tone"}).options.fill, FillMode::Tone);
}

// The flags that shape lines and fills are recorded as given (--background is not
// one: every technique composes over it); a technique without lines warns that it ignored them.
TEST(PostfxFlags, RecordsTheLineFlagsGiven) {
  const ParsedFlags given =
      parseFlags({"--background", "white", "--fill-color", "red", "--width", "3"});
  ASSERT_EQ(given.error, "");
  EXPECT_EQ(given.lineFlags, (std::vector<std::string>{"--width", "--fill-color"}));
  EXPECT_TRUE(parseFlags({"--background", "white"}).lineFlags.empty());
}

TEST(PostfxFlags, ImpossibleValuesNameTheFlag) {
  EXPECT_NE(parseFlags({"--width", "0.5"}).error.find("--width"), std::string::npos);
  EXPECT_NE(parseFlags({"--width", "abc"}).error.find("--width"), std::string::npos);
  EXPECT_NE(parseFlags({"--width-near", "0", "--width-far", "3"}).error.find("--width-near"),
            std::string::npos);
  EXPECT_NE(parseFlags({"--fill", "gold"}).error.find("--fill"), std::string::npos);
  EXPECT_NE(parseFlags({"--background", "#12"}).error.find("--background"), std::string::npos);
  EXPECT_NE(parseFlags({"--width", "3", "--width-near", "2", "--width-far", "4"}).error, "")
      << "fixed and adaptive are exclusive";
  EXPECT_NE(parseFlags({"--width-near", "2"}).error, "") << "near needs far";
}

}  // namespace
}  // namespace vsil
