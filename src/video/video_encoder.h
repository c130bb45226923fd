#pragma once
// The interface between vsil and its video plugin, libvsil_video.so (video_plugin.cpp). The
// plugin alone links OpenCV's videoio, and with it FFmpeg, GStreamer and their ~100 shared
// libraries; linked into the tool they would add about 0.4 s to the start of every `vsil`
// process (measured on 2 loaded cores), so VideoFile loads the plugin when a video is written.
// Both sides are built together, by the same compiler against the same OpenCV.
#include <opencv2/core.hpp>

namespace vsil::video {

class Encoder {
 public:
  virtual ~Encoder() = default;
  // Appends an 8-bit BGR frame of the size the encoder was made for.
  virtual void write(const cv::Mat& bgr) = 0;
  // Finishes the file (the container's index, trailing frames).
  virtual void close() = 0;
  // After close(): how many frames the file gives back, decoded; -1 when it cannot be opened.
  // OpenCV's VideoWriter reports no failed write (a full disk left a video without its index,
  // or cut short, that still counted as written), so the file is read back instead.
  virtual int framesReadBack() = 0;
};

// The plugin's entry point: an encoder writing `path` in the codec `fourcc` through OpenCV's
// FFmpeg backend, or nullptr when OpenCV cannot open it (no FFmpeg backend, codec missing).
using CreateEncoder = Encoder* (*)(const char* path, int fourcc, double fps, int width, int height);
inline constexpr const char* kCreateEncoderSymbol = "vsilCreateVideoEncoder";
inline constexpr const char* kPluginFile = "libvsil_video.so";

}  // namespace vsil::video
