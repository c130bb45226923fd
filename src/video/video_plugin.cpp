// libvsil_video.so: OpenCV's VideoWriter behind video_encoder.h, loaded by VideoFile.
#include <opencv2/videoio.hpp>

#include "video/video_encoder.h"

namespace {

class OpenCvEncoder final : public vsil::video::Encoder {
 public:
  OpenCvEncoder(const char* path, int fourcc, double fps, int width, int height) {
    // FFmpeg only: the same encoder everywhere, and no other backend's messages on stderr.
    writer_.open(path, cv::CAP_FFMPEG, fourcc, fps, cv::Size(width, height), true);
  }
  bool opened() const { return writer_.isOpened(); }
  void write(const cv::Mat& bgr) override { writer_.write(bgr); }
  void close() override { writer_.release(); }

 private:
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
