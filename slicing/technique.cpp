#include "slicing/technique.h"

#include <cmath>

#include <opencv2/core.hpp>

#include "core/error.h"
#include "slicing/texture_units.h"
#include "slicing/volume_texture.h"

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

namespace {
void drawPieces(const FrameContext& frame, const std::vector<PieceDraw>& pieces,
                const std::vector<gl::TextureName>* auxiliaryBricks) {
  glBindVertexArray(frame.sliceVertexArray);
  const bool bricked = frame.volume->brickCount() > 1;
  for (const PieceDraw& piece : pieces) {
    if (bricked) {
      gl::bindTexture(gl::TextureUnit::Volume, GL_TEXTURE_3D,
                      frame.volume->brickTexture(piece.brick));
      if (frame.gradients->built()) {
        gl::bindTexture(gl::TextureUnit::Gradient, GL_TEXTURE_3D,
                        frame.gradients->texture().brickTexture(piece.brick));
      }
      if (auxiliaryBricks) {
        gl::bindTexture(gl::TextureUnit::Auxiliary0, GL_TEXTURE_3D,
                        (*auxiliaryBricks)[piece.brick].id());
      }
      frame.uniforms->bindBrick(piece.brick);
    }
    VSIL_GL(glDrawArrays(GL_TRIANGLE_FAN, piece.firstVertex, piece.vertexCount));
  }
}
}  // namespace

void drawSlicePolygon(const FrameContext& frame, const SliceContext& slice,
                      const std::vector<gl::TextureName>* auxiliaryBricks) {
  drawPieces(frame, slice.pieces, auxiliaryBricks);
}

void drawGhostPieces(const FrameContext& frame, const SliceContext& slice) {
  drawPieces(frame, slice.ghostPieces, nullptr);
}

void Technique::combineSlabs(const FrameContext& frame, SlabRelay&) {
  throw UnavailableError("--technique " + frame.settings->technique +
                         ": rendering across MPI ranks is not available yet; run one rank");
}

void requireOneBrick(const FrameContext& frame, const std::string& what, const std::string& hint) {
  if (frame.volume->brickCount() <= 1) return;
  const glm::ivec3 counts = frame.volume->layout().counts();
  throw InputError(what + " needs the volume in one texture, and this volume takes " +
                   std::to_string(frame.volume->brickCount()) + " bricks (" +
                   std::to_string(counts.x) + "x" + std::to_string(counts.y) + "x" +
                   std::to_string(counts.z) + "); " + hint);
}

void drawScreen(const FrameContext& frame) {
  glBindVertexArray(frame.screenVertexArray);
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
}

void drawScreenPerBrick(const FrameContext& frame) {
  for (std::size_t brick = 0; brick < frame.volume->brickCount(); ++brick) {
    if (frame.slab && !frame.slab->owns(brick)) continue;
    gl::bindTexture(gl::TextureUnit::Volume, GL_TEXTURE_3D, frame.volume->brickTexture(brick));
    frame.uniforms->bindBrick(brick);
    drawScreen(frame);
  }
  gl::bindTexture(gl::TextureUnit::Volume, GL_TEXTURE_3D, frame.volume->brickTexture(0));
  frame.uniforms->bindBrick(0);
}

void relayScreenPass(const FrameContext& frame, const std::vector<const gl::RenderTarget*>& targets,
                     const std::function<void()>& draw) {
  SlabRelay* relay = frame.slab ? frame.slab->relay : nullptr;
  if (relay) relay->receive(targets);
  draw();
  if (relay) {
    relay->send(targets);
    relay->shareLast(targets);
  }
}

namespace {
cv::Mat readFlipped(const gl::RenderTarget& target, int channels, GLenum format) {
  const glm::ivec2 size = target.size();
  cv::Mat image(size.y, size.x, CV_32FC(channels));
  VSIL_GL(glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer()));
  VSIL_GL(glReadBuffer(GL_COLOR_ATTACHMENT0));
  VSIL_GL(glPixelStorei(GL_PACK_ALIGNMENT, 1));
  VSIL_GL(glReadPixels(0, 0, size.x, size.y, format, GL_FLOAT, image.data));
  cv::Mat flipped;
  cv::flip(image, flipped, 0);
  return flipped;
}
}  // namespace

cv::Mat readTargetFlipped(const gl::RenderTarget& target, int channels) {
  return readFlipped(target, channels, channels == 1 ? GL_RED : GL_RGBA);
}

cv::Mat1f readChannelFlipped(const gl::RenderTarget& target, int channel) {
  static constexpr GLenum kFormats[] = {GL_RED, GL_GREEN, GL_BLUE, GL_ALPHA};
  return readFlipped(target, 1, kFormats[channel]);
}

}  // namespace vsil
