#pragma once
// PNG images in and out, through OpenCV. Writing is atomic (core/atomic_file.h).
#include <filesystem>

#include <opencv2/core.hpp>

namespace vsil {

// Writes 8-bit or 16-bit grey, BGR or BGRA images as PNG. Throws InputError naming the path.
void writePng(const std::filesystem::path& path, const cv::Mat& image);

// Reads an image as stored (IMREAD_UNCHANGED). Throws InputError naming the path when it is
// missing or not a decodable image.
cv::Mat readImage(const std::filesystem::path& path);

}  // namespace vsil
