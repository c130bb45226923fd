#include "slicing/technique.h"

#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/core.hpp>

#include "core/error.h"
#include "slicing/rightangle_technique.h"
#include "slicing/silhouette_technique.h"

namespace vsil {

std::unique_ptr<Technique> makeTechnique(const std::string& name) {
  if (name == "silhouette") return std::make_unique<SilhouetteTechnique>();
  if (name == "rightangle") return std::make_unique<RightAngleTechnique>();
  throw InputError("--technique: unknown technique '" + name + "' (known: silhouette, rightangle)");
}

PixelRect SliceContext::recentUnion(int count, int margin, glm::ivec2 viewport) const {
  PixelRect rect;
  for (int i = 0; i < count; ++i) rect = rect.united(recentBounds[std::size_t(i)]);
  return rect.grown(margin, viewport);
}

void setSliceUniforms(gl::Program& program, const FrameContext& frame, const Slice* slice) {
  const View& view = *frame.view;
  program.set("volumeTexture", 0);
  program.set("volumeDims", glm::vec3(frame.dims));
  program.set("voxelFromEye", glm::mat4(glm::inverse(view.eyeFromVoxel)));
  program.set("eyeFromVoxelGradient",
              glm::mat3(glm::transpose(glm::inverse(glm::dmat3(view.eyeFromVoxel)))));
  program.set("viewportSize", glm::vec2(view.viewport));
  program.set("halfExtent", glm::vec2(view.halfExtent));
  program.set("orthographic", view.orthographic ? 1 : 0);
  program.set("isoValue", frame.settings->iso);
  program.set("clipFromVoxel", glm::mat4(view.clipFromVoxel()));
  if (slice) {
    program.set("sliceEyeDistance", float(slice->eyeDistance));
    program.set("sliceDepth", float(slice->depth));
    const glm::dvec4 clip = view.clipFromEye * glm::dvec4(0.0, 0.0, -slice->eyeDistance, 1.0);
    program.set("sliceWindowDepth", float(0.5 * clip.z / clip.w + 0.5));
    const SliceTexCoords tex = sliceTexCoords(view, frame.dims, slice->eyeDistance);
    program.set("sliceTexPerNdcX", tex.perNdcX);
    program.set("sliceTexPerNdcY", tex.perNdcY);
    program.set("sliceTexAtNdcOrigin", tex.atNdcOrigin);
  }
}

void markDeadPixels(gl::Program& markDead, const FrameContext& frame, const SliceContext& slice,
                    const gl::EmptyFramebuffer& depthOnly, const gl::RenderTarget& record) {
  glDisable(GL_SCISSOR_TEST);
  depthOnly.bindForDrawing();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);  // pixels already dead (depth 1) are skipped
  glDepthMask(GL_TRUE);
  glDepthRange(1.0, 1.0);  // every kept fragment writes depth 1
  markDead.use();
  setSliceUniforms(markDead, frame, slice.slice);
  markDead.set("intermediateTexture", 2);
  markDead.set("exitDepthTexture", 3);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, record.texture());
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D, frame.emptySpace->exitDepthTexture());
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(frame.sliceVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, slice.firstVertex, slice.vertexCount));
  glDepthRange(0.0, 1.0);
  glDisable(GL_DEPTH_TEST);
}

void finishRecords(gl::Program& finish, const FrameContext& frame, const gl::RenderTarget& record,
                   const gl::RenderTarget& output) {
  glDisable(GL_SCISSOR_TEST);
  output.bindForDrawing();
  finish.use();
  setSliceUniforms(finish, frame, nullptr);
  finish.set("recordTexture", 1);
  finish.set("rightAngleExponent", float(frame.settings->rightAngleExponent));
  finish.set("rightAngleThreshold", float(frame.settings->rightAngleThreshold));
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, record.texture());
  glActiveTexture(GL_TEXTURE0);
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

FrameBuffers frameFromStateImage(const cv::Mat& stateDepthShade) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  FrameBuffers frame;
  frame.state.create(stateDepthShade.rows, stateDepthShade.cols);
  frame.depth.create(stateDepthShade.rows, stateDepthShade.cols);
  frame.shade.create(stateDepthShade.rows, stateDepthShade.cols);
  for (int y = 0; y < stateDepthShade.rows; ++y) {
    const cv::Vec4f* row = stateDepthShade.ptr<cv::Vec4f>(y);
    for (int x = 0; x < stateDepthShade.cols; ++x) {
      const auto state = PixelState(std::uint8_t(row[x][0] + 0.5f));
      frame.state(y, x) = std::uint8_t(state);
      frame.depth(y, x) = state == PixelState::Empty ? nan : row[x][1];
      frame.shade(y, x) = state == PixelState::Filled ? row[x][2] : nan;
    }
  }
  return frame;
}

}  // namespace vsil
