// libvsil_video.so: OpenCV's VideoWriter behind video_encoder.h, loaded by VideoFile.
#include <fcntl.h>
#include <unistd.h>

#include <string>

#include <opencv2/videoio.hpp>

#include "video/video_encoder.h"

namespace {

// Standard error pointed at /dev/null while it lives (FFmpeg logs there, not through OpenCV).
class QuietStderr {
 public:
  QuietStderr() : saved_(::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0)) {
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) {
      ::dup2(null, STDERR_FILENO);
      ::close(null);
    }
  }
  ~QuietStderr() {
    if (saved_ < 0) return;
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_;
};

class OpenCvEncoder final : public vsil::video::Encoder {
 public:
  OpenCvEncoder(const char* path, int fourcc, double fps, int width, int height) : path_(path) {
    // FFmpeg only: the same encoder everywhere, and no other backend's messages on stderr.
    writer_.open(path, cv::CAP_FFMPEG, fourcc, fps, cv::Size(width, height), true);
  }
  bool opened() const { return writer_.isOpened(); }
  void write(const cv::Mat& bgr) override { writer_.write(bgr); }
  void close() override { writer_.release(); }
  int framesReadBack() override {
    // FFmpeg's decoders say on stderr what they find wrong in a cut file ("[mjpeg @ 0x..]
    // overread 8"); the caller's one line says it instead.
    const QuietStderr quiet;
    cv::VideoCapture capture(path_, cv::CAP_FFMPEG);
    if (!capture.isOpened()) return -1;
    int frames = 0;
    while (capture.grab()) ++frames;
    return frames;
  }

 private:
  std::string path_;
  cv::VideoWriter writer_;
};

}  // namespace

extern "C" __attribute__((visibility("default"))) vsil::video::Encoder* vsilCreateVideoEncoder(
    const char* path, int fourcc, double fps, int width, int height) {
  auto* encoder = new OpenCvEncoder(path, fourcc, fps, width, height);
  if (encoder->opened()) return encoder;
  delete encoder;
  return nullptr;
}
