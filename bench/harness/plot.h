#pragma once
// Grouped bar charts of benchmark tables, drawn with OpenCV (imgproc drawing and putText): one
// panel per table, stacked vertically, written as one PNG.
#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

#include "harness/table.h"

namespace vsil::bench {

// A white BGR image; panels without series are left out. Empty input gives an empty Mat.
cv::Mat drawPlots(const std::vector<const PlotSpec*>& plots);

}  // namespace vsil::bench
