// An interrupted `vsil animate` keeps the frames it wrote, each a complete PNG, and leaves no
// temporary and no half-written video: the video is complete (the signal came after it was
// finished) or absent. A sequence of a few seconds (frames of a 96³ generated volume at 256²,
// PNGs and a Motion JPEG video) is started in a child process and sent SIGINT or SIGTERM at
// points spread over its run time.
#include <signal.h>
#include <sys/wait.h>

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>

#include "reference/test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 24;

// Runs the sequence into `dir`; sends `signal` after `delay` seconds (never, if negative).
test::InterruptedRun animateInto(const fs::path& dir, double delay, int signal) {
  return test::runVsilInterrupted(
      {"animate", "gen:blobs:96", "--size", "256x256", "--frames", std::to_string(kFrames),
       "--orbit", "360", "--out-dir", (dir / "frames").string(), "--video",
       (dir / "movie.avi").string()},
      delay, signal);
}

int videoFrames(const fs::path& path) {
  cv::VideoCapture capture(path.string(), cv::CAP_FFMPEG);
  if (!capture.isOpened()) return -1;
  int frames = 0;
  cv::Mat frame;
  while (capture.read(frame)) ++frames;
  return frames;
}

// Every frame_*.png is complete; no hidden temporary anywhere; returns the frames found.
int checkFrames(const fs::path& dir) {
  int frames = 0;
  if (!fs::exists(dir / "frames")) return 0;
  for (const auto& entry : fs::directory_iterator(dir / "frames")) {
    const std::string name = entry.path().filename().string();
    EXPECT_NE(name[0], '.') << "a temporary was left behind: " << name;
    if (name == "frames.json") continue;
    EXPECT_TRUE(name.starts_with("frame_") && name.ends_with(".png")) << name;
    const std::string bytes = test::readFileBytes(entry.path());
    EXPECT_EQ(bytes.substr(1, 3), "PNG") << name;
    EXPECT_EQ(bytes.substr(bytes.size() - 8, 4), "IEND") << name << " is incomplete";
    ++frames;
  }
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "frames" || name == "movie.avi") << "left behind: " << name;
  }
  return frames;
}

TEST(InterruptedAnimate, KeepsTheFramesWrittenAndNoHalfVideo) {
  // Uninterrupted: how long the whole run takes here, and what it writes.
  const fs::path full = test::scratchDir();
  const test::InterruptedRun complete = animateInto(full, -1, 0);
  ASSERT_TRUE(WIFEXITED(complete.status) && WEXITSTATUS(complete.status) == 0) << complete.status;
  EXPECT_EQ(checkFrames(full), kFrames);
  EXPECT_EQ(videoFrames(full / "movie.avi"), kFrames);

  int killed = 0, partial = 0;
  for (double fraction : {0.3, 0.6, 0.9}) {
    for (int signal : {SIGINT, SIGTERM}) {
      const fs::path dir =
          test::scratchDir() / (std::to_string(signal) + "_" + std::to_string(int(fraction * 100)));
      fs::create_directories(dir);
      const test::InterruptedRun run = animateInto(dir, fraction * complete.seconds, signal);
      SCOPED_TRACE("signal " + std::to_string(signal) + " after " +
                   std::to_string(fraction * complete.seconds) + " s");
      const int frames = checkFrames(dir);
      if (WIFSIGNALED(run.status)) {
        ++killed;
        EXPECT_EQ(WTERMSIG(run.status), signal);
        partial += frames > 0 && frames < kFrames;
        // The video is finished and renamed after the last frame, or not at all.
        if (fs::exists(dir / "movie.avi")) {
          EXPECT_EQ(frames, kFrames);
          EXPECT_EQ(videoFrames(dir / "movie.avi"), kFrames);
        }
      } else {
        EXPECT_TRUE(WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) << run.status;
        EXPECT_EQ(frames, kFrames);
      }
    }
  }
  // Timing varies with load (the full run was timed once); the early signals always land.
  EXPECT_GE(killed, 2) << "few signals arrived while the sequence was running";
  EXPECT_GE(partial, 1) << "no signal arrived between frames";
}

}  // namespace
}  // namespace vsil
