#pragma once
// Frames to a video file through OpenCV's VideoWriter with its FFmpeg backend (Debian's OpenCV
// has it; in the plugin libvsil_video.so, loaded on first use: video_encoder.h says why),
// written whole or not at all: the frames go to a hidden temporary beside the target
// (core/atomic_file.h AtomicOutputFile, removed on the cleanup signals and on errors), which
// finish() renames over the target.
//
// The format is chosen by the extension: .mp4 (MPEG-4 Part 2, FourCC mp4v) or .avi (Motion
// JPEG, FourCC MJPG; every frame a JPEG, the closer to the frames' pixels). Both subsample
// colour by two, so the image's width and height must be even. Frames are 8-bit BGR; the alpha
// of a BGRA frame is dropped (a transparent background shows as its colour).
#include <filesystem>
#include <memory>

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

namespace vsil {

class AtomicOutputFile;

class VideoFile {
 public:
  // Whether a video can take `fps` frames per second: [0.01, 1000]. A value no video could
  // take is refused also where no video is written.
  static bool validFps(double fps);
  static constexpr const char* kFpsRange = "[0.01, 1000]";  // for messages
  // The checks that create nothing: a known extension, an existing folder (or `folderToMake`,
  // one the command creates before the video: animate's --out-dir), an even size and a frame
  // rate in kFpsRange. Throws InputError naming `flag` and the path.
  static void checkTarget(const std::string& flag, const std::filesystem::path& target,
                          glm::ivec2 size, double fps,
                          const std::filesystem::path& folderToMake = {});

  // Opens the writer on a temporary beside `target`. Throws InputError when the folder is not
  // writable or OpenCV cannot write the format here (no FFmpeg backend, codec missing), and
  // std::runtime_error when the plugin cannot be loaded (an incomplete installation).
  VideoFile(const std::filesystem::path& target, glm::ivec2 size, double fps);
  // Unfinished: the writer is closed and the temporary removed; the target is not touched.
  ~VideoFile();
  VideoFile(const VideoFile&) = delete;
  VideoFile& operator=(const VideoFile&) = delete;

  // Appends a frame: 8-bit BGR or BGRA of the size given.
  void write(const cv::Mat& image);
  // Closes the writer, checks the video and renames the temporary over the target. Throws
  // InputError naming the target when the container's sizes do not account for the file or it
  // does not give back every frame written (a full disk: OpenCV reports no failed write); the
  // temporary is then removed.
  void finish();
  int framesWritten() const { return frames_; }

 private:
  struct Writer;
  glm::ivec2 size_;
  std::unique_ptr<AtomicOutputFile> file_;
  std::unique_ptr<Writer> writer_;
  int frames_ = 0;
};

}  // namespace vsil
