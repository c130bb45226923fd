#pragma once
// PNG images in and out, through libpng (OpenCV's image codecs, whose GDAL alone pulls ~120 shared
// libraries into every process start, are not linked). Writing is atomic (core/atomic_file.h).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace vsil {

// Writes 8-bit or 16-bit grey, BGR or BGRA images as PNG. Throws InputError naming the path.
void writePng(const std::filesystem::path& path, const cv::Mat& image);
// The PNG file's bytes writePng writes (for an OutputBatch, core/atomic_file.h); InputError
// naming the path.
std::vector<std::uint8_t> encodePng(const std::filesystem::path& path, const cv::Mat& image);
// The same bytes with no file behind them (`vsil serve` sends them: the page's PNG is the
// file's); std::runtime_error when they cannot be made.
std::vector<std::uint8_t> encodePng(const cv::Mat& image);

// Refuses (InputError "<flag> <path>: vsil writes PNG images; name the file .png") an image
// output whose name says another format (o.jpg, d.tiff): it would hold PNG bytes all the same.
// A name without an extension (/dev/stdout) is taken.
void requirePngName(const std::string& flag, const std::filesystem::path& path);

// Reads a PNG image of at most limits::kMaxImageSide pixels a side as readPng. Throws InputError
// naming the path when it is missing, not a PNG image, too large or not decodable.
cv::Mat readImage(const std::filesystem::path& path);

// The width and height a PNG file's header (its first chunk, IHDR) declares, read without
// decoding the image, so that a caller can refuse a huge one before any allocation. Throws
// InputError naming the path when the file is missing, empty, not a PNG, or declares a side of
// 0 or beyond 2^31 − 1 pixels (invalid PNG).
cv::Size readPngSize(const std::filesystem::path& path);

// Reads a PNG image as stored (OpenCV's IMREAD_UNCHANGED layout: grey, BGR or BGRA, 8 or 16
// bits), after readPngSize's checks and a walk over its chunks: a file that is truncated, holds
// a chunk whose CRC does not match, ends without IEND or is larger than an image of its declared
// size can need is refused with one line naming the path before libpng decodes it. What the
// chunk walk cannot see (valid chunks around an invalid compressed stream) fails as "not a
// readable PNG image (libpng's reason)".
cv::Mat readPng(const std::filesystem::path& path);

}  // namespace vsil
