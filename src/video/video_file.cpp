#include "video/video_file.h"

#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/plugin.h"
#include "video/video_encoder.h"

namespace vsil {

namespace {

struct VideoFormat {
  const char* extension;
  const char* name;  // for messages
  char fourcc[4];
};

constexpr VideoFormat kFormats[] = {
    {".mp4", "MPEG-4 (mp4v)", {'m', 'p', '4', 'v'}},
    {".avi", "Motion JPEG (MJPG)", {'M', 'J', 'P', 'G'}},
};

const VideoFormat* formatOf(const std::filesystem::path& target) {
  for (const VideoFormat& format : kFormats) {
    if (target.extension() == format.extension) return &format;
  }
  return nullptr;
}

// The plugin (video_encoder.h), loaded once and kept (core/plugin.h).
video::CreateEncoder loadPlugin() {
#ifdef VSIL_VIDEO_PLUGIN_BUILT
  const std::string built = VSIL_VIDEO_PLUGIN_BUILT;
#else
  const std::string built;
#endif
  return reinterpret_cast<video::CreateEncoder>(
      pluginSymbol("video", video::kPluginFile, video::kCreateEncoderSymbol, built));
}

// Whether the container's own sizes account for the file, to its last byte: a disk that filled
// late cut an MP4's last box or an AVI's index (or its last frame) with every frame still
// decodable (round 15). MP4: top-level boxes (32-bit big-endian size and type; size 1: a 64-bit
// size follows, 0: to the end) ending at the file's end, one of them "moov". AVI: "RIFF" chunks
// (the first "AVI ", OpenDML's further ones "AVIX"; 32-bit little-endian sizes, padded to even)
// ending there. Only the headers are read.
bool containerComplete(const std::filesystem::path& path, const VideoFormat& format) {
  std::ifstream in(path, std::ios::binary);
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(path, error);
  if (!in || error || size == 0) return false;
  // `length` bytes at `at` as an unsigned word; false where the file ends first.
  const auto word = [&](std::uint64_t at, int length, bool bigEndian, std::uint64_t& value) {
    unsigned char bytes[8] = {};
    if (size - at < std::uint64_t(length)) return false;
    in.seekg(std::streamoff(at));
    if (!in.read(reinterpret_cast<char*>(bytes), length)) return false;
    value = 0;
    for (int i = 0; i < length; ++i) {
      value |= std::uint64_t(bytes[i]) << (8 * (bigEndian ? length - 1 - i : i));
    }
    return true;
  };
  const bool mp4 = std::string_view(format.extension) == ".mp4";
  bool movie = false;
  std::uint64_t at = 0, value = 0;
  while (at < size) {
    std::uint64_t next = 0;
    if (mp4) {  // size, then type
      std::uint64_t type = 0;
      if (!word(at, 4, true, value) || !word(at + 4, 4, true, type)) return false;
      movie = movie || type == 0x6d6f6f76;  // "moov"
      if (value == 1 && !word(at + 8, 8, true, value)) return false;
      if (value == 0) value = size - at;
      if (value < 8) return false;
      next = at + value;
    } else {  // "RIFF", then the size
      std::uint64_t riff = 0;
      if (!word(at, 4, true, riff) || riff != 0x52494646 || !word(at + 4, 4, false, value)) {
        return false;
      }
      next = at + 8 + value + (value % 2);
    }
    if (next > size) return false;
    at = next;
  }
  return mp4 ? movie : true;
}

}  // namespace

struct VideoFile::Writer {
  std::unique_ptr<video::Encoder> encoder;
};

void VideoFile::checkTarget(const std::string& flag, const std::filesystem::path& target,
                            glm::ivec2 size, double fps,
                            const std::filesystem::path& folderToMake) {
  const std::string where = flag + " " + target.string();
  if (!formatOf(target)) {
    std::string known;
    for (const VideoFormat& format : kFormats) {
      known += (known.empty() ? "" : ", ") + std::string(format.extension);
    }
    throwInputError(
        where, "unknown video format '" + target.extension().string() + "' (known: " + known + ")");
  }
  const std::filesystem::path folder =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  if (folderToMake.empty() || folderNamed(folder) != folderNamed(folderToMake)) {
    refuseMissingFolder(where, target);
  }
  if (size.x % 2 != 0 || size.y % 2 != 0) {
    throwInputError(where, "video needs an even width and height (--size " +
                               std::to_string(size.x) + "x" + std::to_string(size.y) + ")");
  }
  if (!validFps(fps)) throwInputError(where, std::string("--fps must be in ") + kFpsRange);
}

bool VideoFile::validFps(double fps) {
  // Below 0.01 FFmpeg has no time base for it (0.001: "The encoder timebase is not set", and
  // OpenCV's error blamed a missing back end).
  return fps >= 0.01 && fps <= 1000;
}

VideoFile::VideoFile(const std::filesystem::path& target, glm::ivec2 size, double fps)
    : size_(size), writer_(std::make_unique<Writer>()) {
  const VideoFormat* format = formatOf(target);
  if (!format) throw std::logic_error("VideoFile: call checkTarget first");
  const video::CreateEncoder create = loadPlugin();
  file_ = std::make_unique<AtomicOutputFile>(target);
  // As OpenCV's VideoWriter::fourcc: the four characters, little-endian.
  const int fourcc = format->fourcc[0] | format->fourcc[1] << 8 | format->fourcc[2] << 16 |
                     format->fourcc[3] << 24;
  writer_->encoder.reset(create(file_->temporaryPath().c_str(), fourcc, fps, size.x, size.y));
  if (!writer_->encoder) {
    throwInputError(target.string(), std::string("OpenCV cannot write ") + format->name +
                                         " video here (its videoio needs the FFmpeg backend)");
  }
}

VideoFile::~VideoFile() = default;

void VideoFile::write(const cv::Mat& image) {
  if (image.cols != size_.x || image.rows != size_.y || image.depth() != CV_8U) {
    throw std::logic_error("VideoFile: a frame of another size or depth");
  }
  if (image.channels() == 4) {
    cv::Mat bgr;
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
    writer_->encoder->write(bgr);
  } else {
    writer_->encoder->write(image);
  }
  ++frames_;
}

void VideoFile::finish() {
  writer_->encoder->close();
  file_->finish();
  // The headers first: a cut file is told without decoding it.
  if (!containerComplete(file_->temporaryPath(), *formatOf(file_->target()))) {
    throwInputError(file_->target().string(),
                    "cannot write the video whole (the file ends before its container's own "
                    "sizes say; is the disk full?)");
  }
  const int readBack = writer_->encoder->framesReadBack();
  if (readBack != frames_) {
    throwInputError(file_->target().string(),
                    "cannot write the video whole (" +
                        (readBack < 0 ? std::string("it cannot be read back")
                                      : std::to_string(readBack) + " of " +
                                            std::to_string(frames_) + " frames read back") +
                        "; is the disk full?)");
  }
  file_->commit();
}

}  // namespace vsil
