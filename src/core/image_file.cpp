#include "core/image_file.h"

#include <system_error>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.h"
#include "core/error.h"

namespace vsil {

void writePng(const std::filesystem::path& path, const cv::Mat& image) {
  if (image.empty()) throwInputError(path.string(), "refusing to write an empty image");
  std::vector<std::uint8_t> bytes;
  if (!cv::imencode(".png", image, bytes)) throwInputError(path.string(), "PNG encoding failed");
  writeFileAtomically(path, bytes);
}

cv::Mat readImage(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throwInputError(path.string(),
                    std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file");
  }
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (image.empty()) throwInputError(path.string(), "not a readable image");
  return image;
}

}  // namespace vsil
