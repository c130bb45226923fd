#include "slicing/techniques/firsthit/firsthit_technique.h"

#include <limits>

namespace vsil {

TechniqueInfo firstHitTechniqueInfo() {
  return {"firsthit",
          "the depth of the first iso-surface hit as grey (near white, far black), and as depth",
          {isoOption()},
          FrameOutputs{.state = false, .color = true, .depth = true},
          [] { return std::make_unique<FirstHitTechnique>(); },
          /*usesGradients=*/false,
          /*checkValues=*/{},
          /*needsOneTexture=*/{}};
}

BrickOccupancy FirstHitTechnique::occupancy(const FrameContext& frame) const {
  return reachesIso(float(frame.options->number("iso")));
}

FrameBuffers FirstHitTechnique::readBack(const FrameContext&) {
  const cv::Mat records = readTargetFlipped(hits_.record(), 4);
  FrameBuffers frame;
  frame.depth.create(records.rows, records.cols);
  frame.color.create(records.rows, records.cols);
  for (int y = 0; y < records.rows; ++y) {
    const cv::Vec4f* record = records.ptr<cv::Vec4f>(y);
    for (int x = 0; x < records.cols; ++x) {
      const bool hit = record[x][3] > 0.5f;
      const float depth = record[x][1];
      const float grey = 1.0f - depth;
      frame.depth(y, x) = hit ? depth : std::numeric_limits<float>::quiet_NaN();
      frame.color(y, x) = hit ? cv::Vec4f(grey, grey, grey, 1.0f) : cv::Vec4f(0, 0, 0, 0);
    }
  }
  return frame;
}

}  // namespace vsil
