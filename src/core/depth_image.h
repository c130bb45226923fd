#pragma once
// The depth image vsil writes (`render --depth-out`) and reads back (`measure-width --depth`):
// 16-bit grey, 0 where a pixel has no depth, 1 + round(d·65534) where it has the normalized
// depth d in [0, 1]. Encoding and decoding live here alone, so the two ends cannot disagree.
#include <filesystem>

#include <opencv2/core.hpp>

namespace vsil {

// NaN (no depth) → 0; d → 1 + round(clamp(d, 0, 1)·65534).
cv::Mat1w encodeDepthImage(const cv::Mat1f& depth);

// The inverse: 0 → NaN, v → (v − 1) / 65534. `image` must be single-channel 16-bit (what
// encodeDepthImage makes) or 32-bit float (NaN = no depth, passed through); anything else throws
// InputError naming `path`.
cv::Mat1f decodeDepthImage(const cv::Mat& image, const std::filesystem::path& path);

}  // namespace vsil
