// `vsil render` end to end, through the built binary: outputs, metadata, determinism, errors.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/frame.h"
#include "test_support.h"

namespace vsil {
namespace {

TEST(RenderCommand, WritesImageStateDepthAndMetadata) {
  const auto dir = test::scratchDir();
  const auto result = test::runVsil(
      "render gen:sphere:48 --size 96x80 --iso 0.5 --view 10,20 --ortho --out " +
      (dir / "a.png").string() + " --state-out " + (dir / "state.png").string() + " --depth-out " +
      (dir / "depth.png").string() + " --meta-out " + (dir / "meta.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("a.png"), std::string::npos) << "prints where the image is";

  const cv::Mat state = cv::imread((dir / "state.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(state.type(), CV_8UC1);
  ASSERT_EQ(state.cols, 96);
  ASSERT_EQ(state.rows, 80);
  const cv::Mat depth = cv::imread((dir / "depth.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(depth.type(), CV_16UC1);
  int silhouettes = 0;
  for (int y = 0; y < state.rows; ++y) {
    for (int x = 0; x < state.cols; ++x) {
      const int grey = state.at<std::uint8_t>(y, x);
      EXPECT_TRUE(grey == 0 || grey == 85 || grey == 255) << "grey " << grey;
      const bool line = grey == 255;
      silhouettes += line;
      EXPECT_EQ(depth.at<std::uint16_t>(y, x) != 0, line) << "at (" << x << "," << y << ")";
    }
  }
  EXPECT_GT(silhouettes, 40);

  const auto meta = nlohmann::json::parse(test::readFileBytes(dir / "meta.json"));
  EXPECT_EQ(meta["parameters"]["technique"], "silhouette");
  EXPECT_EQ(meta["parameters"]["fill"], "none");
  EXPECT_FALSE(meta["parameters"].contains("param")) << "only with --fill tone";
  EXPECT_FALSE(meta["parameters"].contains("tone_fill"));
  EXPECT_EQ(meta["dataset"]["name"], "sphere");
  EXPECT_EQ(meta["dataset"]["dims"], nlohmann::json({48, 48, 48}));
  EXPECT_EQ(meta["camera"]["viewport"], nlohmann::json({96, 80}));
  for (const char* key : {"render", "readback", "postfx", "total"}) {
    EXPECT_TRUE(meta["timings_ms"][key].is_number()) << key;
  }
  EXPECT_GT(meta["slices"].get<int>(), 40);
  // The back end the render ran on: $VSIL_GL reaches the binary (ctest runs this once per back
  // end), and the context is 4.5 core.
  if (const char* backend = std::getenv("VSIL_GL")) {
    EXPECT_EQ(meta["gl"]["backend"], backend);
  }
  EXPECT_EQ(meta["gl"]["version"].get<std::string>().rfind("4.5", 0), 0u) << meta["gl"];
  EXPECT_FALSE(meta["gl"]["renderer"].get<std::string>().empty());

  // The camera in the metadata projects the sphere's centre to the middle of its outline.
  glm::dmat4 eyeFromVoxel, clipFromEye;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      eyeFromVoxel[c][r] = meta["camera"]["eye_from_voxel"][r][c].get<double>();
      clipFromEye[c][r] = meta["camera"]["clip_from_eye"][r][c].get<double>();
    }
  }
  const glm::dvec4 clip = clipFromEye * eyeFromVoxel * glm::dvec4(23.5, 23.5, 23.5, 1.0);
  const double px = (clip.x / clip.w + 1) * 0.5 * 96, py = (1 - clip.y / clip.w) * 0.5 * 80;
  double sumX = 0, sumY = 0;
  for (int y = 0; y < state.rows; ++y) {
    for (int x = 0; x < state.cols; ++x) {
      if (state.at<std::uint8_t>(y, x) != 255) continue;
      sumX += x + 0.5;
      sumY += y + 0.5;
    }
  }
  EXPECT_NEAR(sumX / silhouettes, px, 0.5);
  EXPECT_NEAR(sumY / silhouettes, py, 0.5);
  // Silhouette depth: the sphere's centre depth, normalized over depth_range_eye.
  const double nearEye = meta["camera"]["depth_range_eye"][0],
               farEye = meta["camera"]["depth_range_eye"][1];
  const double centreDepth =
      (-(eyeFromVoxel * glm::dvec4(23.5, 23.5, 23.5, 1.0)).z - nearEye) / (farEye - nearEye);
  double depthSum = 0;
  for (int y = 0; y < state.rows; ++y) {
    for (int x = 0; x < state.cols; ++x) {
      const int code = depth.at<std::uint16_t>(y, x);
      if (code) depthSum += (code - 1) / 65534.0;
    }
  }
  EXPECT_NEAR(depthSum / silhouettes, centreDepth, 0.02);
}

// --meta-out times every stage of the process, in wall and CPU time; the stages fit in the
// total; the default iso value's histogram is computed only when --iso is not given.
TEST(RenderCommand, MetadataTimesEveryStageAndSkipsTheHistogramWhenIsoIsGiven) {
  const auto dir = test::scratchDir();
  const char* stages[] = {"startup",  "context", "read",     "upload", "defaults",
                          "programs", "render",  "readback", "postfx", "write"};
  for (const std::string iso : {"", " --iso 0.5"}) {
    const auto meta = dir / "meta.json";
    const auto result = test::runVsil("render gen:blobs:96 --size 64x64" + iso + " --out " +
                                      (dir / "out.png").string() + " --meta-out " + meta.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto json = nlohmann::json::parse(test::readFileBytes(meta));
    for (const char* key : {"timings_ms", "cpu_ms"}) {
      double sum = 0;
      for (const char* stage : stages) {
        ASSERT_TRUE(json[key][stage].is_number()) << key << " " << stage;
        EXPECT_GE(json[key][stage].get<double>(), 0.0) << key << " " << stage;
        sum += json[key][stage].get<double>();
      }
      // The stages are disjoint; CPU time is counted in clock ticks of at most a few ms.
      EXPECT_LE(sum, json[key]["total"].get<double>() + 20.0) << key;
    }
    EXPECT_GT(json["cpu_ms"]["startup"].get<double>(), 0.0);
    if (iso.empty()) {
      EXPECT_GT(json["timings_ms"]["defaults"].get<double>(), 0.0) << "the histogram";
    } else {
      EXPECT_EQ(json["timings_ms"]["defaults"].get<double>(), 0.0) << "no histogram with --iso";
    }
  }
}

// lmip's threshold is an iso option but its window is not: giving the threshold (here its own
// default, the window's low end) must not skip the histogram the window and a --tf preset's
// scale come from. It did: the window became the placeholder 0.5,1, a white picture.
TEST(RenderCommand, LmipThresholdKeepsTheHistogramsWindowAndPresetScale) {
  const auto dir = test::scratchDir();
  for (const std::string tf : {"", " --tf ct-bone"}) {
    std::string images[2];
    for (int given = 0; given < 2; ++given) {
      const auto out = dir / ("lmip" + std::to_string(given) + ".png");
      const auto meta = dir / "meta.json";
      // gen:blobs:64's default window starts at its Otsu threshold: read it from a first run.
      std::string threshold;
      if (given) {
        const auto first = nlohmann::json::parse(test::readFileBytes(meta));
        threshold = " --lmip-threshold " + first["parameters"]["lmip_threshold"].dump();
      }
      const auto result =
          test::runVsil("render gen:blobs:64 --size 48x48 --technique lmip" + tf + threshold +
                        " --out " + out.string() + " --meta-out " + meta.string());
      ASSERT_EQ(result.exitCode, 0) << result.err;
      images[given] = test::readFileBytes(out);
    }
    EXPECT_EQ(images[0], images[1]) << "lmip" << tf;
  }
}

TEST(RenderCommand, WarnsWhenTheIsoValueTheWindowOrTheLmipThresholdLieOutsideTheData) {
  const auto dir = test::scratchDir();
  const auto out = (dir / "empty.png").string();
  const auto result = test::runVsil("render gen:sphere:16 --size 32x32 --iso 1000 --out " + out);
  EXPECT_EQ(result.exitCode, 0) << "the empty frame is what was asked for";
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_EQ(result.err,
            "vsil: warning: --iso 1000 is outside the data's range 0 .. 0.891747 of "
            "gen:sphere:16: no sample reaches it\n");
  const auto inside = test::runVsil("render gen:sphere:16 --size 32x32 --iso 0.5 --out " + out);
  EXPECT_EQ(inside.err, "") << "no warning inside the range";
  // The MIP family's window starting above every value: a blank frame, said so.
  for (const char* technique : {"mip", "demip", "lmip"}) {
    const auto above = test::runVsil("render gen:sphere:16 --size 32x32 --technique " +
                                     std::string(technique) + " --window 300,400 --out " + out);
    EXPECT_EQ(above.exitCode, 0) << above.err;
    EXPECT_EQ(above.err,
              "vsil: warning: --window 300,400 starts at or above the data's largest value "
              "0.891747 of gen:sphere:16: no pixel shows anything\n")
        << technique;
  }
  const auto window = test::runVsil(
      "render gen:sphere:16 --size 32x32 --technique mip --window 0.1,2 --out " + out);
  EXPECT_EQ(window.err, "") << "no warning for a window that starts inside the range";
  // An LMIP threshold above every value: each ray shows its maximum, lmip turns mip.
  const auto lmip = test::runVsil(
      "render gen:sphere:16 --size 32x32 --technique lmip --lmip-threshold 5 --out " + out);
  EXPECT_EQ(lmip.exitCode, 0) << lmip.err;
  EXPECT_EQ(lmip.err,
            "vsil: warning: --lmip-threshold 5 is above the data's largest value 0.891747 of "
            "gen:sphere:16: no local maximum reaches it, and every pixel shows its ray's maximum "
            "(as mip)\n");
  const auto threshold = test::runVsil(
      "render gen:sphere:16 --size 32x32 --technique lmip --lmip-threshold 0.5 --out " + out);
  EXPECT_EQ(threshold.err, "") << "no warning for a threshold within the range";
}

// Options that change nothing in the frame they are given for warn, naming why (a user tuning
// k_os beside a preset transfer function saw nothing change); given where they act, no word.
TEST(RenderCommand, WarnsAboutOptionsThatChangeNothing) {
  const auto out = (test::scratchDir() / "ignored.png").string();
  const std::pair<const char*, const char*> cases[] = {
      {"--technique illustrate --tf ramp --param k_oe=3",
       "--param k_oe: the transfer function gives the opacity (k_os, k_oe shape the power "
       "opacity without one); ignored"},
      {"--technique illustrate --tf ramp --color red",
       "--color: the transfer function gives the samples' colour; ignored"},
      {"--technique illustrate --effects tone --sketch-color red",
       "--sketch-color: the sketch effect is off; ignored"},
      {"--technique illustrate --effects tone --param k_ss=20",
       "--param k_ss: the silhouette effect is off; ignored"},
      {"--technique illustrate --effects tone --halo-mode exact",
       "--halo-mode: the halo effect is off; ignored"},
      {"--technique demip --sphere-map green-red",
       "--sphere-map: the colour sphere is off (--sphere-weight 0, no --legend); ignored"},
      {"--fill-color red", "--fill-color: there is no --fill; ignored"},
      // A style the user wrote, as its flags (a preset's values are its own: below).
      {"--technique illustrate --tf ramp --style '{\"parameters\": {\"k_os\": 2}}'",
       "--style (inline): parameters: k_os: the transfer function gives the opacity (k_os, k_oe "
       "shape the power opacity without one); ignored"},
  };
  for (const auto& [args, warning] : cases) {
    const auto result =
        test::runVsil("render gen:sphere:16 --size 16x16 " + std::string(args) + " --out " + out);
    EXPECT_EQ(result.exitCode, 0) << args << ": " << result.err;
    EXPECT_EQ(result.err, "vsil: warning: " + std::string(warning) + "\n") << args;
  }
  for (const char* args :
       {"--technique illustrate --param k_oe=3", "--technique illustrate --color red",
        "--technique illustrate --effects sketch --sketch-color red",
        "--technique illustrate --effects silhouette --param k_ss=20",
        "--technique illustrate --effects halo --halo-mode exact",
        "--technique demip --sphere-map green-red --sphere-weight 0.5",
        "--technique demip --sphere-map green-red --legend", "--fill-color red --fill flat",
        "--technique illustrate --style fig6-distance-halo --halo-mode exact"}) {
    const auto result =
        test::runVsil("render gen:sphere:16 --size 16x16 " + std::string(args) + " --out " + out);
    EXPECT_EQ(result.exitCode, 0) << args << ": " << result.err;
    EXPECT_EQ(result.err, "") << args;
  }
}

// A --sampling lowered until a few slices remain shows cross-sections: the frame is made and
// says so; the default sampling on a small volume, or a lower one that leaves enough, does not.
TEST(RenderCommand, WarnsWhenTheSamplingLeavesFewSlices) {
  const auto dir = test::scratchDir();
  const auto out = (dir / "few.png").string();
  const auto few = test::runVsil("render gen:sphere:64 --size 32x32 --sampling 0.05 --out " + out);
  EXPECT_EQ(few.exitCode, 0) << few.err;
  EXPECT_EQ(few.err,
            "vsil: warning: --sampling 0.05 leaves fewer than 16 slices through gen:sphere:64: "
            "the picture shows cross-sections, not the volume\n");
  // An orbit's views leave different counts: said once.
  const auto orbit = test::runVsil(
      "animate gen:sphere:64 --size 32x32 --sampling 0.05 --frames 4 "
      "--orbit 90 --out-dir " +
      (dir / "orbit").string());
  EXPECT_EQ(orbit.exitCode, 0) << orbit.err;
  std::size_t said = 0;
  for (std::size_t at = 0; (at = orbit.err.find("leaves fewer than 16", at)) != std::string::npos;
       ++at) {
    ++said;
  }
  EXPECT_EQ(said, 1u) << orbit.err;
  for (const std::string args : {"gen:sphere:64 --sampling 0.25", "gen:sphere:8"}) {
    const auto enough = test::runVsil("render " + args + " --size 32x32 --out " + out);
    EXPECT_EQ(enough.exitCode, 0) << enough.err;
    EXPECT_EQ(enough.err, "") << args;
  }
}

// The line flags shape nothing of a technique that draws no lines: the frame is made and says
// which it ignored; the silhouette takes them without a word.
TEST(RenderCommand, WarnsThatATechniqueWithoutLinesIgnoresTheLineFlags) {
  const auto dir = test::scratchDir();
  const auto out = (dir / "mip.png").string();
  const auto plain = (dir / "plain.png").string();
  const auto mip = test::runVsil(
      "render gen:sphere:16 --size 32x32 --technique mip --width 3 "
      "--fill flat --background white --out " +
      out);
  EXPECT_EQ(mip.exitCode, 0);
  EXPECT_EQ(mip.err,
            "vsil: warning: --width, --fill: technique 'mip' draws no lines or filled pixels; "
            "ignored (the line flags go with silhouette and rightangle)\n");
  const auto without = test::runVsil(
      "render gen:sphere:16 --size 32x32 --technique mip "
      "--background white --out " +
      plain);
  EXPECT_EQ(without.err, "");
  EXPECT_EQ(test::readFileBytes(out), test::readFileBytes(plain)) << "the flags changed the frame";
  const auto lines =
      test::runVsil("render gen:sphere:16 --size 32x32 --width 3 --fill flat --out " + out);
  EXPECT_EQ(lines.exitCode, 0);
  EXPECT_EQ(lines.err, "");
}

// Every pipeline, and the default (no --pipeline: each technique's own, which the metadata
// records), gives the same state and depth bytes.
TEST(RenderCommand, EveryPipelineGivesIdenticalImages) {
  const auto dir = test::scratchDir();
  for (const auto& [technique, defaultPipeline] :
       {std::pair{"silhouette", "tiles"}, std::pair{"rightangle", "tiles"}}) {
    std::string images[4];
    const char* pipelines[4] = {"fast", "paper", "tiles", ""};
    for (int i = 0; i < 4; ++i) {
      const std::string name = *pipelines[i] ? pipelines[i] : "default";
      const auto state = dir / (name + ".png");
      const auto depth = dir / (name + ".depth.png");
      const auto meta = dir / (name + ".json");
      const auto result = test::runVsil(
          "render gen:spheres:64 --size 120x100 --technique " + std::string(technique) +
          (*pipelines[i] ? " --pipeline " + std::string(pipelines[i]) : "") + " --out " +
          (dir / "out.png").string() + " --state-out " + state.string() + " --depth-out " +
          depth.string() + " --meta-out " + meta.string());
      ASSERT_EQ(result.exitCode, 0) << result.err;
      images[i] = test::readFileBytes(state) + test::readFileBytes(depth);
      EXPECT_EQ(nlohmann::json::parse(test::readFileBytes(meta))["parameters"]["pipeline"],
                *pipelines[i] ? pipelines[i] : defaultPipeline)
          << technique << " " << name;
    }
    EXPECT_EQ(images[0], images[1]) << technique << ": paper";
    EXPECT_EQ(images[0], images[2]) << technique << ": tiles";
    EXPECT_EQ(images[0], images[3]) << technique << ": the default";
  }
}

TEST(RenderCommand, EmptySpaceSkippingChangesNoByte) {
  const auto dir = test::scratchDir();
  for (const char* technique : {"silhouette", "rightangle"}) {
    for (const char* pipeline : {"fast", "tiles"}) {
      std::string images[2];
      for (int skipping = 0; skipping < 2; ++skipping) {
        const auto out = dir / (std::string(technique) + std::to_string(skipping) + ".png");
        const auto meta = dir / "meta.json";
        const auto result = test::runVsil(
            "render gen:blobs:64 --size 120x100 --width 4 --technique " + std::string(technique) +
            " --pipeline " + pipeline + (skipping ? "" : " --no-empty-space-skipping") + " --out " +
            out.string() + " --meta-out " + meta.string());
        ASSERT_EQ(result.exitCode, 0) << result.err;
        images[skipping] = test::readFileBytes(out);
        const auto parameters = nlohmann::json::parse(test::readFileBytes(meta))["parameters"];
        EXPECT_EQ(parameters["empty_space_skipping"], skipping == 1);
      }
      EXPECT_EQ(images[0], images[1]) << technique << " " << pipeline;
    }
  }
}

TEST(RenderCommand, SameCommandTwiceGivesIdenticalBytes) {
  const auto dir = test::scratchDir();
  for (const char* technique : {"silhouette", "rightangle"}) {
    std::string outputs[2];
    for (int run = 0; run < 2; ++run) {
      const std::string name = std::string(technique) + std::to_string(run);
      const auto result =
          test::runVsil("render gen:torus:48 --size 100x90 --technique " + std::string(technique) +
                        " --out " + (dir / (name + ".png")).string() + " --depth-out " +
                        (dir / (name + "-depth.png")).string());
      ASSERT_EQ(result.exitCode, 0) << result.err;
      outputs[run] = test::readFileBytes(dir / (name + ".png")) +
                     test::readFileBytes(dir / (name + "-depth.png"));
    }
    EXPECT_EQ(outputs[0], outputs[1]) << technique;
  }
}

// --fill tone end to end: lit from straight above, the top of a sphere's fill is yellow and the
// bottom blue (R + G − 2B), and the metadata records the fill and what shaped it.
TEST(RenderCommand, ToneFillIsWarmWhereLitAndRecorded) {
  const auto dir = test::scratchDir();
  const auto result = test::runVsil(
      "render gen:sphere:48 --size 96x96 --iso 0.5 --ortho --zoom 2 --width 1 --fill tone "
      "--fill-color '#606060' --light 0,90 --param k_ty=0.4 --out " +
      (dir / "tone.png").string() + " --meta-out " + (dir / "meta.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const cv::Mat image = cv::imread((dir / "tone.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(image.type(), CV_8UC3);
  // Rows a quarter of the sphere's projected radius (about 28 px around the centre) above and
  // below the middle, inside the outline.
  const auto warmth = [&](int row) {
    double sum = 0;
    for (int x = 40; x < 56; ++x) {
      const cv::Vec3b bgr = image.at<cv::Vec3b>(row, x);
      sum += double(bgr[2]) + double(bgr[1]) - 2.0 * double(bgr[0]);
    }
    return sum / 16;
  };
  const double top = warmth(30), bottom = warmth(66);
  EXPECT_GT(top, 20) << "yellow where lit";
  EXPECT_LT(bottom, -20) << "blue on the far side";
  const auto meta = nlohmann::json::parse(test::readFileBytes(dir / "meta.json"));
  const auto& parameters = meta["parameters"];
  EXPECT_EQ(parameters["fill"], "tone");
  EXPECT_EQ(parameters["fill_color"], "#606060ff");
  EXPECT_EQ(parameters["tone_fill"]["parameters"]["k_ty"], 0.4);
  EXPECT_EQ(parameters["tone_fill"]["parameters"]["k_tb"], 0.3) << "illustrate's default";
  EXPECT_EQ(parameters["tone_fill"]["lights"], nlohmann::json::parse("[[0, 90]]"));
  EXPECT_EQ(parameters["param"], nlohmann::json::parse(R"(["k_ty=0.4"])")) << "as given";
}

// The tone presets on the datasets they show best on, and the tone fill on the engine, as the
// README shows them: Ebert–Rheingans' sum kept in range (shaders/illustration.glsl toneShade),
// so under 1 % of the object's pixels have a channel at 255, and the object holds both warm
// (R > B) and cool (B > R) pixels.
TEST(RenderCommand, TonePresetsAndTheToneFillStayBelowWhiteOnTheirDatasets) {
  VSIL_REQUIRE_DATASETS();
  struct ToneRender {
    const char* name;
    std::string arguments;
    bool states;  // object = Filled pixels of --state-out; else alpha >= 128
  };
  const std::string engine = test::datasetPath("engine.vti").string();
  const ToneRender renders[] = {
      {"fig7-tone", engine + " --technique illustrate --style fig7-tone --background transparent",
       false},
      {"fig15-tone",
       test::datasetPath("ironProt.vtk").string() +
           " --technique illustrate --style fig15-tone --background transparent",
       false},
      {"fill-tone", engine + " --iso 80 --view 40,25 --width 2 --fill tone --fill-color '#d9c7a0'",
       true},
  };
  const auto dir = test::scratchDir();
  for (const ToneRender& r : renders) {
    SCOPED_TRACE(r.name);
    const auto image = dir / (std::string(r.name) + ".png");
    const auto states = dir / (std::string(r.name) + "-state.png");
    const auto result =
        test::runVsil("render " + r.arguments + " --size 192x192 --out " + image.string() +
                      (r.states ? " --state-out " + states.string() : ""));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const cv::Mat colour = cv::imread(image.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat state = r.states ? cv::imread(states.string(), cv::IMREAD_UNCHANGED) : cv::Mat();
    int object = 0, atWhite = 0, warm = 0, cool = 0;
    for (int y = 0; y < colour.rows; ++y) {
      for (int x = 0; x < colour.cols; ++x) {
        const std::uint8_t* bgr = colour.ptr<std::uint8_t>(y) + x * colour.channels();
        const bool inObject = r.states
                                  ? state.at<std::uint8_t>(y, x) == stateGrey(PixelState::Filled)
                                  : colour.channels() == 4 && bgr[3] >= 128;
        if (!inObject) continue;
        ++object;
        atWhite += bgr[0] == 255 || bgr[1] == 255 || bgr[2] == 255;
        warm += bgr[2] > bgr[0];
        cool += bgr[0] > bgr[2];
      }
    }
    std::cout << "[ info ] " << r.name << ": " << object << " object pixels, " << atWhite
              << " at 255, " << warm << " warm, " << cool << " cool\n";
    EXPECT_GT(object, 2000);
    EXPECT_LT(atWhite, object / 100) << "under 1 % at 255";
    EXPECT_GT(warm, object / 5) << "warm where lit";
    EXPECT_GT(cool, object / 100) << "cool where not";
  }
}

struct BadRender {
  const char* name;
  const char* arguments;
  const char* expected;  // a fragment of the one-line error
};

class RenderCommandRejects : public ::testing::TestWithParam<BadRender> {};

TEST_P(RenderCommandRejects, WithOneLineAndExitTwoAndNoOutput) {
  const auto dir = test::scratchDir();
  const auto out = dir / "never.png";
  const auto result =
      test::runVsil(std::string("render ") + GetParam().arguments + " --out " + out.string());
  EXPECT_EQ(result.exitCode, 2) << result.err;
  EXPECT_NE(result.err.find(GetParam().expected), std::string::npos) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_TRUE(result.out.empty()) << result.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    BadInput, RenderCommandRejects,
    ::testing::Values(
        BadRender{"unknown_technique", "gen:sphere:16 --technique nope", "--technique"},
        BadRender{"unknown_pipeline", "gen:sphere:16 --pipeline slow", "--pipeline"},
        BadRender{"zero_size", "gen:sphere:16 --size 0x10", "--size"},
        BadRender{"size_without_x", "gen:sphere:16 --size 12", "--size"},
        BadRender{"view_one_angle", "gen:sphere:16 --view 1", "--view"},
        BadRender{"negative_zoom", "gen:sphere:16 --zoom -1", "--zoom"},
        BadRender{"zero_sampling", "gen:sphere:16 --sampling 0", "--sampling"},
        BadRender{"nan_iso", "gen:sphere:16 --iso nan", "--iso"},
        BadRender{"width_below_one", "gen:sphere:16 --width 0.5", "--width"},
        BadRender{"unknown_generator", "gen:nosuchthing", "nosuchthing"},
        BadRender{"missing_file", "/nonexistent/volume.nrrd", "/nonexistent/volume.nrrd"}),
    [](const auto& info) { return std::string(info.param.name); });

// A file that places its volume in a patient's frame stands superior up, seen from anterior
// (--up auto); --up +y gives the plain axes back. A ball near the top of the superior axis of
// an NRRD in LPS space shows in the image's upper part by default, and --meta-out says why.
TEST(RenderCommand, AnAnatomicalPlacementStandsTheVolumeSuperiorUp) {
  const auto dir = test::scratchDir();
  std::string samples(32 * 32 * 32, '\0');
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        const int d2 = (x - 16) * (x - 16) + (y - 16) * (y - 16) + (z - 26) * (z - 26);
        if (d2 <= 16) samples[std::size_t((z * 32 + y) * 32 + x)] = char(200);
      }
  const auto input = dir / "oriented.nrrd";
  std::ofstream(input, std::ios::binary)
      << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 32 32 32\n"
         "space: left-posterior-superior\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n"
         "encoding: raw\n\n"
      << samples;
  // The mean image row and column of the ball's pixels, as fractions of the side.
  const auto ballAt = [&](const std::string& up) {
    const auto out = dir / "up.png";
    const auto meta = dir / "up.json";
    const auto run = test::runVsil("render " + input.string() + " --technique mip --size 64x64" +
                                   up + " --out " + out.string() + " --meta-out " + meta.string());
    EXPECT_EQ(run.exitCode, 0) << run.err;
    const cv::Mat grey = cv::imread(out.string(), cv::IMREAD_GRAYSCALE);
    double rows = 0, columns = 0, count = 0;
    for (int y = 0; y < grey.rows; ++y)
      for (int x = 0; x < grey.cols; ++x)
        if (grey.at<std::uint8_t>(y, x) > 40) rows += y, columns += x, ++count;
    EXPECT_GT(count, 20) << up;
    const auto upright = nlohmann::json::parse(test::readFileBytes(meta))["camera"]["upright"];
    return std::make_tuple(rows / count / 64, columns / count / 64, upright);
  };
  const auto [autoRow, autoColumn, autoUpright] = ballAt("");
  EXPECT_LT(autoRow, 0.4);
  EXPECT_NEAR(autoColumn, 0.5, 0.05) << "the orbit turns about the superior axis";
  EXPECT_EQ(autoUpright, nlohmann::json({{"up", "+z"},
                                         {"front", "-y"},
                                         {"from",
                                          "the file's space (LPS): superior up, "
                                          "anterior front"}}));
  const auto [plainRow, plainColumn, plainUpright] = ballAt(" --up y");
  EXPECT_GT(plainRow, 0.45);
  EXPECT_EQ(plainUpright["from"], "--up +y") << "recorded written out";
  // An animation records it once, for all its frames.
  const auto frames = dir / "frames";
  const auto animated = test::runVsil("animate " + input.string() +
                                      " --technique mip --size 16x16 --frames 2 --quiet"
                                      " --out-dir " +
                                      frames.string());
  ASSERT_EQ(animated.exitCode, 0) << animated.err;
  const auto manifest = nlohmann::json::parse(test::readFileBytes(frames / "frames.json"));
  EXPECT_EQ(manifest["upright"], autoUpright);
  // A bad axis: one line, exit 2, no image.
  const auto out = dir / "bad_up.png";
  const auto bad = test::runVsil("render gen:sphere:16 --up sideways --out " + out.string());
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_EQ(bad.err, "vsil: --up: 'sideways' is not auto or an axis (+x, -x, +y, -y, +z, -z)\n");
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace vsil
