#pragma once
// Comparing frames of any technique by what it returns (states, depth, shade, tone, colour).
#include "core/frame.h"
#include "core/options.h"
#include "slicing/technique_table.h"

namespace vsil::test {

// Pixels where any buffer the frames hold differs (NaN equals NaN; every byte and float exact).
int differingPixels(const FrameBuffers& a, const FrameBuffers& b);

// The largest difference of any channel between two colour images of the same size.
double maxChannelDifference(const cv::Mat4f& a, const cv::Mat4f& b);
// The same at pixel (x, y) alone (row y, column x).
double maxChannelDifference(const cv::Mat4f& a, const cv::Mat4f& b, int y, int x);

// Pixels that show something: a state other than Empty, or a colour with alpha > 0.
int shownPixels(const FrameBuffers& frame);

// Options that make `technique` show the iso-surface at `iso` where it has an iso value; none
// otherwise (its defaults).
OptionValues isoOptions(const TechniqueInfo& technique, double iso);

}  // namespace vsil::test
