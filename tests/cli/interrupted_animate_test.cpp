// An interrupted `vsil animate` keeps the frames it wrote, each a complete PNG, and leaves no
// temporary and no half-written video: the video is complete (the signal came after it was
// finished) or absent. A sequence of a few seconds (frames of a 96³ generated volume at 256²,
// PNGs and a Motion JPEG video) is started in a child process and sent SIGINT or SIGTERM once it
// has written a given number of frames, at points spread over the sequence (not over a time
// measured once: under a loaded machine's changing speed, signals timed so came after the end).
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

// The frame_*.png files in `dir`/frames so far (temporaries are hidden: not counted).
int framesWritten(const fs::path& dir) {
  int frames = 0;
  std::error_code error;
  for (fs::directory_iterator entry(dir / "frames", error), end; !error && entry != end;
       entry.increment(error)) {
    frames += entry->path().filename().string().starts_with("frame_");
  }
  return frames;
}

// Runs the sequence into `dir`; sends `signal` once `afterFrames` frames are written (never, if
// negative).
test::InterruptedRun animateInto(const fs::path& dir, int afterFrames, int signal) {
  return test::runVsilInterrupted(
      {"animate", "gen:blobs:96", "--size", "256x256", "--frames", std::to_string(kFrames),
       "--orbit", "360", "--out-dir", (dir / "frames").string(), "--video",
       (dir / "movie.avi").string()},
      afterFrames < 0 ? -1.0 : 0.0, signal,
      [&] { return afterFrames >= 0 && framesWritten(dir) >= afterFrames; });
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
  // Uninterrupted: what the whole run writes.
  const fs::path full = test::scratchDir();
  const test::InterruptedRun complete = animateInto(full, -1, 0);
  ASSERT_TRUE(WIFEXITED(complete.status) && WEXITSTATUS(complete.status) == 0) << complete.status;
  EXPECT_EQ(checkFrames(full), kFrames);
  EXPECT_EQ(videoFrames(full / "movie.avi"), kFrames);

  int killed = 0, partial = 0;
  for (int afterFrames : {kFrames * 3 / 10, kFrames * 6 / 10, kFrames * 9 / 10}) {
    for (int signal : {SIGINT, SIGTERM}) {
      const fs::path dir =
          test::scratchDir() / (std::to_string(signal) + "_" + std::to_string(afterFrames));
      fs::create_directories(dir);
      const test::InterruptedRun run = animateInto(dir, afterFrames, signal);
      SCOPED_TRACE("signal " + std::to_string(signal) + " after frame " +
                   std::to_string(afterFrames));
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
  // A signal sent after frame 21 of 24 may still come after the end; the others land.
  EXPECT_GE(killed, 4) << "few signals arrived while the sequence was running";
  EXPECT_GE(partial, 4) << "few signals arrived between frames";
}

}  // namespace
}  // namespace vsil
