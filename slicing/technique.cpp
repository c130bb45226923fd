#include "slicing/technique.h"

#include <cmath>

#include <opencv2/core.hpp>

namespace vsil {

PixelRect SliceContext::recentUnion(int count, int margin, glm::ivec2 viewport) const {
  PixelRect rect;
  for (int i = 0; i < count; ++i) rect = rect.united(recentBounds[std::size_t(i)]);
  return rect.grown(margin, viewport);
}

BrickOccupancy reachesIso(float iso) {
  return [iso](ValueRange brick) {
    return brick.max >= iso - 1e-5f * (std::abs(iso) + std::abs(brick.max));
  };
}

void drawSlicePolygon(const FrameContext& frame, const SliceContext& slice) {
  glBindVertexArray(frame.sliceVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, slice.firstVertex, slice.vertexCount));
}

void drawScreen(const FrameContext& frame) {
  glBindVertexArray(frame.screenVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
}

cv::Mat readTargetFlipped(const gl::RenderTarget& target, int channels) {
  const glm::ivec2 size = target.size();
  cv::Mat image(size.y, size.x, CV_32FC(channels));
  VSIL_GL(glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer()));
  VSIL_GL(glReadBuffer(GL_COLOR_ATTACHMENT0));
  VSIL_GL(glPixelStorei(GL_PACK_ALIGNMENT, 1));
  VSIL_GL(
      glReadPixels(0, 0, size.x, size.y, channels == 1 ? GL_RED : GL_RGBA, GL_FLOAT, image.data));
  cv::Mat flipped;
  cv::flip(image, flipped, 0);
  return flipped;
}

}  // namespace vsil
