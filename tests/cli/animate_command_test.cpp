// `vsil animate` end to end, through the built binary: the numbered frames and frames.json,
// sweeps that reach the metadata and change what they should, every frame the same bytes as
// `vsil render` with that frame's parameters, the video (read back), progress and --quiet.
// Small on purpose (64² frames of a 48³ volume, a handful of frames).
#include <sys/resource.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

nlohmann::json readJson(const fs::path& path) {
  return nlohmann::json::parse(test::readFileBytes(path));
}

// A number as the command line takes it back exactly (JSON numbers are written round-trip).
std::string text(const nlohmann::json& number) {
  return number.dump();
}

// Pixels of the illustration that are not background (white).
int inkPixels(const cv::Mat& image) {
  cv::Mat grey;
  cv::extractChannel(image, grey, 0);
  return cv::countNonZero(grey < 128);
}

TEST(AnimateCommand, WritesNumberedFramesAndTheirJson) {
  const fs::path dir = test::scratchDir() / "frames";
  const auto result = test::runVsil(
      "animate gen:spheres:48 --size 64x64 --frames 4 --orbit 360 "
      "--sweep iso=0.3:0.6 --out-dir " +
      dir.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  for (const char* name :
       {"frame_0000.png", "frame_0001.png", "frame_0002.png", "frame_0003.png", "frames.json"}) {
    EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "frame_0004.png"));
  EXPECT_NE(result.out.find((dir / "frames.json").string()), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("4 frames in "), std::string::npos) << result.out;
  EXPECT_NE(result.out.find(" fps"), std::string::npos) << result.out;

  const nlohmann::json json = readJson(dir / "frames.json");
  EXPECT_EQ(json["input"], "gen:spheres:48");
  EXPECT_EQ(json["technique"], "silhouette");
  EXPECT_EQ(json["animation"]["frames"], 4);
  EXPECT_EQ(json["animation"]["orbit_deg"], 360.0);
  EXPECT_EQ(json["dataset"]["dims"], nlohmann::json({48, 48, 48}));
  // The suite runs once per back end with $VSIL_GL set; animate renders on the one chosen.
  if (const char* backend = std::getenv("VSIL_GL"); backend && *backend) {
    EXPECT_EQ(json["gl"]["backend"], backend) << json["gl"].dump();
  }
  EXPECT_GT(json["fps"].get<double>(), 0);
  for (const char* key : {"setup", "frames", "render", "readback", "postfx", "write", "total"}) {
    EXPECT_TRUE(json["timings_ms"][key].is_number()) << key;
  }
  ASSERT_EQ(json["frames"].size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const nlohmann::json& frame = json["frames"][i];
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_EQ(frame["index"], i);
    EXPECT_DOUBLE_EQ(frame["t"].get<double>(), i / 3.0);
    char file[32];
    std::snprintf(file, sizeof file, "frame_%04d.png", i);
    EXPECT_EQ(frame["file"], file);
    // The orbit adds 360·i/4 to --view's azimuth; the sweep runs from 0.3 to 0.6.
    EXPECT_DOUBLE_EQ(frame["parameters"]["view"][0].get<double>(), 30 + 90 * i);
    EXPECT_DOUBLE_EQ(frame["parameters"]["view"][1].get<double>(), 20);
    EXPECT_DOUBLE_EQ(frame["swept"]["iso"].get<double>(), 0.3 + 0.1 * i);
    EXPECT_EQ(frame["swept"]["iso"], frame["parameters"]["iso"]);
    EXPECT_EQ(frame["parameters"]["pipeline"], "tiles") << "render's default, from one table";
    for (const char* key : {"render", "readback", "postfx", "write", "total"}) {
      EXPECT_TRUE(frame["timings_ms"][key].is_number()) << key;
    }
    EXPECT_GT(frame["pixels"]["silhouette"].get<int>(), 20);
    EXPECT_GT(frame["slices"].get<int>(), 40);
  }
  EXPECT_EQ(json["frames"][0]["swept"]["iso"], 0.3) << "the first frame is exactly A";
  EXPECT_EQ(json["frames"][3]["swept"]["iso"], 0.6) << "the last frame is exactly B";
}

// Each frame is the render of its parameters: the same bytes as `vsil render` given them. One
// job renders every frame (its GL state, programs and FFT plans reused), a process each time here.
// An option ignored only in some frames (the sphere's rotation while the swept weight is 0) is
// not called ignored; one every frame ignores is, once.
TEST(AnimateCommand, WarnsOfAnOptionOnlyWhereEveryFrameIgnoresIt) {
  const fs::path dir = test::scratchDir();
  const std::string base =
      "animate gen:spheres:32 --technique demip --size 16x16 --frames 3 --sphere-rotate 90,0 ";
  const auto swept =
      test::runVsil(base + "--sweep sphere-weight=0:1 --quiet --out-dir " + (dir / "a").string());
  ASSERT_EQ(swept.exitCode, 0) << swept.err;
  EXPECT_EQ(swept.err, "");
  const auto still = test::runVsil(base + "--quiet --out-dir " + (dir / "b").string());
  ASSERT_EQ(still.exitCode, 0) << still.err;
  EXPECT_EQ(still.err,
            "vsil: warning: --sphere-rotate: the colour sphere is off (--sphere-weight 0, no "
            "--legend); ignored\n");
}

// Numbers are read in decimal: CLI11 alone read --frames 010 as the octal 8.
TEST(AnimateCommand, AFrameCountWithLeadingZerosIsDecimal) {
  const fs::path dir = test::scratchDir() / "ten";
  const auto result =
      test::runVsil("animate gen:sphere:16 --size 16x16 --frames 010 --out-dir " + dir.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(readJson(dir / "frames.json")["animation"]["frames"], 10);
  EXPECT_TRUE(fs::is_regular_file(dir / "frame_0009.png"));
  EXPECT_FALSE(fs::exists(dir / "frame_0010.png"));
}

TEST(AnimateCommand, EachFrameIsTheSameBytesAsARenderOfItsParameters) {
  const fs::path dir = test::scratchDir();
  const auto result = test::runVsil(
      "animate gen:spheres:48 --size 64x64 --frames 3 --view-from 10,-20 --view-to 100,40 "
      "--orbit 90 --sweep iso=0.35:0.55 --sweep width=2:6 --sweep zoom=1:1.5 --quiet --out-dir " +
      (dir / "frames").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json json = readJson(dir / "frames" / "frames.json");
  ASSERT_EQ(json["frames"].size(), 3u);
  for (const auto& frame : json["frames"]) {
    const nlohmann::json& p = frame["parameters"];
    SCOPED_TRACE(frame.dump());
    EXPECT_EQ(frame["swept"]["width"], p["width_near"]);
    EXPECT_EQ(frame["swept"]["zoom"], p["zoom"]);
    const fs::path rendered = dir / ("render_" + frame["file"].get<std::string>());
    const auto render = test::runVsil("render gen:spheres:48 --size 64x64 --view " +
                                      text(p["view"][0]) + "," + text(p["view"][1]) + " --iso " +
                                      text(p["iso"]) + " --width " + text(p["width_near"]) +
                                      " --zoom " + text(p["zoom"]) + " --out " + rendered.string());
    ASSERT_EQ(render.exitCode, 0) << render.err;
    EXPECT_EQ(test::readFileBytes(rendered),
              test::readFileBytes(dir / "frames" / frame["file"].get<std::string>()));
  }
  // The view moved: first from --view-from, last from --view-to plus two thirds of the orbit.
  EXPECT_EQ(json["frames"][0]["parameters"]["view"], nlohmann::json({10.0, -20.0}));
  EXPECT_EQ(json["frames"][2]["parameters"]["view"], nlohmann::json({160.0, 40.0}));
}

// An iso sweep on the sphere (the surface f = v has radius (1 − v)·N/2) shrinks its outline, and
// a width sweep thickens the lines, frame by frame, from the same view.
TEST(AnimateCommand, SweepsChangeWhatTheyShould) {
  const fs::path dir = test::scratchDir();
  ASSERT_EQ(test::runVsil("animate gen:sphere:48 --size 64x64 --ortho --frames 3 "
                          "--sweep iso=0.2:0.7 --width 1 --quiet --out-dir " +
                          (dir / "iso").string())
                .exitCode,
            0);
  const nlohmann::json iso = readJson(dir / "iso" / "frames.json");
  int previous = 1 << 30;
  for (const auto& frame : iso["frames"]) {
    const int silhouettes = frame["pixels"]["silhouette"];
    const int filled = frame["pixels"]["filled"];
    EXPECT_LT(silhouettes + filled, previous) << frame["swept"].dump();
    previous = silhouettes + filled;
  }
  const cv::Mat big = cv::imread((dir / "iso" / "frame_0000.png").string());
  const cv::Mat small = cv::imread((dir / "iso" / "frame_0002.png").string());
  // One-pixel circles: their ink grows with the radius, (1 − 0.2) / (1 − 0.7) ≈ 2.7 times.
  EXPECT_GT(inkPixels(big), 2 * inkPixels(small));

  ASSERT_EQ(test::runVsil("animate gen:sphere:48 --size 64x64 --ortho --frames 3 "
                          "--sweep width=1:7 --quiet --out-dir " +
                          (dir / "width").string())
                .exitCode,
            0);
  const nlohmann::json width = readJson(dir / "width" / "frames.json");
  EXPECT_EQ(width["frames"][0]["pixels"], width["frames"][2]["pixels"]) << "the same silhouettes";
  int thinner = 0;
  for (int i = 0; i < 3; ++i) {
    const std::string file = width["frames"][i]["file"];
    const int ink = inkPixels(cv::imread((dir / "width" / file).string()));
    EXPECT_GT(ink, thinner) << "frame " << i;
    thinner = ink;
  }
}

// The video holds the same frames as the PNGs: Motion JPEG (.avi) read back with OpenCV, every
// frame close to its PNG; MPEG-4 (.mp4) with the right frame count.
TEST(AnimateCommand, VideoHoldsTheFramesOfThePngs) {
  const fs::path dir = test::scratchDir();
  const auto result = test::runVsil(
      "animate gen:spheres:48 --size 64x48 --frames 5 --orbit 120 --width 4 --quiet --out-dir " +
      (dir / "frames").string() + " --video " + (dir / "movie.avi").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find((dir / "movie.avi").string()), std::string::npos) << result.out;
  EXPECT_EQ(readJson(dir / "frames" / "frames.json")["video"], (dir / "movie.avi").string());

  cv::VideoCapture capture((dir / "movie.avi").string(), cv::CAP_FFMPEG);
  ASSERT_TRUE(capture.isOpened());
  EXPECT_EQ(capture.get(cv::CAP_PROP_FRAME_COUNT), 5);
  int frames = 0;
  cv::Mat frame;
  while (capture.read(frame)) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", frames);
    const cv::Mat png = cv::imread((dir / "frames" / name).string());
    ASSERT_EQ(frame.size(), png.size()) << name;
    cv::Mat difference;
    cv::absdiff(frame, png, difference);
    // JPEG rounds colours and rings at the lines' edges: small on average, never a line missing
    // (a missing 4 px black line on white would differ by ~255 over its whole band).
    const double mean = cv::mean(difference)[0];
    EXPECT_LT(mean, 3.0) << name;
    EXPECT_LT(cv::countNonZero(difference.reshape(1) > 96), int(difference.total() / 100)) << name;
    ++frames;
  }
  EXPECT_EQ(frames, 5);

  ASSERT_EQ(test::runVsil("animate gen:spheres:48 --size 64x48 --frames 4 --orbit 90 --quiet "
                          "--video " +
                          (dir / "movie.mp4").string())
                .exitCode,
            0);
  cv::VideoCapture mp4((dir / "movie.mp4").string(), cv::CAP_FFMPEG);
  ASSERT_TRUE(mp4.isOpened());
  int mp4Frames = 0;
  while (mp4.read(frame)) ++mp4Frames;
  EXPECT_EQ(mp4Frames, 4);
  // Nothing beside the two videos and the frames' folder: no temporary left.
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "frames" || name == "movie.avi" || name == "movie.mp4") << name;
  }
}

// A video the disk cannot hold is refused, not left half-written: OpenCV's VideoWriter reports
// no failed write, so a full disk (here a file-size limit, with SIGXFSZ ignored so that writes
// fail with EFBIG) left an MP4 without its index, or an AVI cut short, exit 0. Cut early (at
// 1 KiB: frames lost) and late (8 bytes short of the whole file: every frame decodable, the
// MP4's last box or the AVI's index cut, round 15).
TEST(AnimateCommand, AVideoTheDiskCannotHoldIsRefused) {
  const fs::path dir = test::scratchDir();
  const std::string args = "animate gen:spheres:48 --size 128x128 --frames 12 --quiet --video ";
  struct rlimit previous {};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &previous), 0);
  for (const char* name : {"movie.mp4", "movie.avi"}) {
    ASSERT_EQ(test::runVsil(args + (dir / "whole").string() + fs::path(name).extension().string())
                  .exitCode,
              0);
    const auto whole = fs::file_size(dir / ("whole" + fs::path(name).extension().string()));
    for (const rlim_t limit : {rlim_t(1024), rlim_t(whole - 8)}) {
      SCOPED_TRACE(std::string(name) + " limited to " + std::to_string(limit) + " of " +
                   std::to_string(whole) + " bytes");
      const auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);  // inherited through exec
      struct rlimit small = previous;
      small.rlim_cur = limit;
      ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
      const test::CommandResult result = test::runVsil(args + (dir / name).string());
      setrlimit(RLIMIT_FSIZE, &previous);
      std::signal(SIGXFSZ, previousHandler);
      EXPECT_EQ(result.exitCode, 2) << result.out << result.err;
      EXPECT_NE(result.err.find("cannot write the video whole"), std::string::npos) << result.err;
      EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
      EXPECT_FALSE(fs::exists(dir / name));
    }
  }
  // Nothing but the whole videos: no temporary left.
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().stem(), "whole") << entry.path();
  }
}

// "--out-dir new/" names the folder new, created in the current folder (it was refused:
// "folder new does not exist", the trailing slash's empty name taken for the folder).
TEST(AnimateCommand, AnOutDirWithATrailingSlashIsCreated) {
  const fs::path dir = test::scratchDir();
  const std::string animate = "animate gen:sphere:16 --size 32x32 --frames 2 --quiet --out-dir ";
  const auto result = test::runVsil(animate + (dir / "new").string() + "/");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_TRUE(fs::exists(dir / "new" / "frames.json"));
  EXPECT_TRUE(fs::exists(dir / "new" / "frame_0001.png"));
  // "dot/." alike; a video into the --out-dir the command makes (round 15: both refused); a
  // link to nothing said as such (it was "cannot create the folder: File exists").
  const auto dot = test::runVsil(animate + (dir / "dot").string() + "/.");
  ASSERT_EQ(dot.exitCode, 0) << dot.err;
  EXPECT_TRUE(fs::exists(dir / "dot" / "frames.json"));
  const auto video = test::runVsil(animate + (dir / "both").string() + " --video " +
                                   (dir / "both" / "v.avi").string());
  ASSERT_EQ(video.exitCode, 0) << video.err;
  EXPECT_TRUE(fs::exists(dir / "both" / "v.avi"));
  fs::create_symlink(dir / "nowhere", dir / "dangling");
  const auto dangling = test::runVsil(animate + (dir / "dangling").string());
  EXPECT_EQ(dangling.exitCode, 2);
  EXPECT_EQ(dangling.err, "vsil: --out-dir " + (dir / "dangling").string() +
                              ": is a link to nothing (" + (dir / "nowhere").string() + ")\n");
}

TEST(AnimateCommand, ShowsProgressUnlessQuiet) {
  const fs::path dir = test::scratchDir();
  const auto loud = test::runVsil("animate gen:sphere:32 --size 32x32 --frames 3 --out-dir " +
                                  (dir / "a").string());
  ASSERT_EQ(loud.exitCode, 0) << loud.err;
  // stderr is a file here: milestones, one line each, the last one the whole sequence.
  EXPECT_NE(loud.err.find("frame 3/3 [####################]"), std::string::npos) << loud.err;
  EXPECT_NE(loud.err.find(" fps, 0 s left\n"), std::string::npos) << loud.err;
  const auto quiet = test::runVsil(
      "animate gen:sphere:32 --size 32x32 --frames 3 --quiet "
      "--out-dir " +
      (dir / "b").string());
  ASSERT_EQ(quiet.exitCode, 0);
  EXPECT_EQ(quiet.err, "");
}

}  // namespace
}  // namespace vsil
