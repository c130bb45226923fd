#pragma once
// Scoped GL state, as Inviwo's state objects do it: each guard sets one piece of state for one
// scope and puts back what it found when it leaves it, so no pass leaks state into the next.
// ScopedState keeps everything a frame touches (the Renderer holds one per render); the small
// guards below set what one pass needs, in one line:
//   gl::DepthTest depth(GL_GREATER, /*write=*/false);
//   gl::Blending blend(GL_MAX, GL_ONE, GL_ONE);
#include <array>

#include "slicing/gl.h"

namespace vsil::gl {

class ScopedState {
 public:
  ScopedState() {
    glGetIntegerv(GL_VIEWPORT, viewport_.data());
    glGetIntegerv(GL_SCISSOR_BOX, scissorBox_.data());
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer_);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertexArray_);
    glGetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
    glGetIntegerv(GL_BLEND_SRC_RGB, &blendSrcRgb_);
    glGetIntegerv(GL_BLEND_DST_RGB, &blendDstRgb_);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &blendSrcAlpha_);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &blendDstAlpha_);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &blendEquationRgb_);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &blendEquationAlpha_);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask_);
    scissorTest_ = glIsEnabled(GL_SCISSOR_TEST);
    depthTest_ = glIsEnabled(GL_DEPTH_TEST);
    stencilTest_ = glIsEnabled(GL_STENCIL_TEST);
    blend_ = glIsEnabled(GL_BLEND);
    depthClamp_ = glIsEnabled(GL_DEPTH_CLAMP);
    glGetBooleanv(GL_COLOR_WRITEMASK, colorMask_.data());
    glGetDoublev(GL_DEPTH_RANGE, depthRange_.data());
  }
  ~ScopedState() {
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    glScissor(scissorBox_[0], scissorBox_[1], scissorBox_[2], scissorBox_[3]);
    // Objects current on entry may have been deleted since (a program deleted while in use
    // lives on only until another one is used): those are not restored.
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, liveOrZero(drawFramebuffer_, glIsFramebuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, liveOrZero(readFramebuffer_, glIsFramebuffer));
    glUseProgram(liveOrZero(program_, glIsProgram));
    glBindVertexArray(liveOrZero(vertexArray_, glIsVertexArray));
    glDepthFunc(GLenum(depthFunc_));
    glDepthMask(depthMask_);
    glBlendFuncSeparate(GLenum(blendSrcRgb_), GLenum(blendDstRgb_), GLenum(blendSrcAlpha_),
                        GLenum(blendDstAlpha_));
    glBlendEquationSeparate(GLenum(blendEquationRgb_), GLenum(blendEquationAlpha_));
    setEnabled(GL_SCISSOR_TEST, scissorTest_);
    setEnabled(GL_DEPTH_TEST, depthTest_);
    setEnabled(GL_STENCIL_TEST, stencilTest_);
    setEnabled(GL_BLEND, blend_);
    setEnabled(GL_DEPTH_CLAMP, depthClamp_);
    glColorMask(colorMask_[0], colorMask_[1], colorMask_[2], colorMask_[3]);
    glDepthRange(depthRange_[0], depthRange_[1]);
  }
  ScopedState(const ScopedState&) = delete;
  ScopedState& operator=(const ScopedState&) = delete;

  static GLuint liveOrZero(GLint name, GLboolean (*isLive)(GLuint)) {
    return name != 0 && isLive(GLuint(name)) ? GLuint(name) : 0;
  }

  static void setEnabled(GLenum capability, bool enabled) {
    if (enabled) {
      glEnable(capability);
    } else {
      glDisable(capability);
    }
  }

 private:
  std::array<GLint, 4> viewport_{};
  std::array<GLint, 4> scissorBox_{};
  GLint drawFramebuffer_ = 0, readFramebuffer_ = 0, program_ = 0, vertexArray_ = 0;
  GLint depthFunc_ = 0, blendSrcRgb_ = 0, blendDstRgb_ = 0, blendSrcAlpha_ = 0, blendDstAlpha_ = 0;
  GLint blendEquationRgb_ = 0, blendEquationAlpha_ = 0;
  GLboolean depthMask_ = GL_TRUE, scissorTest_ = GL_FALSE, depthTest_ = GL_FALSE;
  GLboolean stencilTest_ = GL_FALSE, blend_ = GL_FALSE, depthClamp_ = GL_FALSE;
  std::array<GLboolean, 4> colorMask_{GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  std::array<GLdouble, 2> depthRange_{0.0, 1.0};
};

// Depth test on with `function` and the depth write mask; restores test, function and mask.
class DepthTest {
 public:
  DepthTest(GLenum function, bool write) {
    glGetIntegerv(GL_DEPTH_FUNC, &function_);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &write_);
    enabled_ = glIsEnabled(GL_DEPTH_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(function);
    glDepthMask(write ? GL_TRUE : GL_FALSE);
  }
  ~DepthTest() {
    glDepthFunc(GLenum(function_));
    glDepthMask(write_);
    ScopedState::setEnabled(GL_DEPTH_TEST, enabled_);
  }
  DepthTest(const DepthTest&) = delete;
  DepthTest& operator=(const DepthTest&) = delete;

 private:
  GLint function_ = GL_LESS;
  GLboolean write_ = GL_TRUE, enabled_ = GL_FALSE;
};

// Blending on with one equation and factors for colour and alpha; restores all of it.
class Blending {
 public:
  Blending(GLenum equation, GLenum source, GLenum destination) {
    glGetIntegerv(GL_BLEND_SRC_RGB, &sourceRgb_);
    glGetIntegerv(GL_BLEND_DST_RGB, &destinationRgb_);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &sourceAlpha_);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &destinationAlpha_);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &equationRgb_);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &equationAlpha_);
    enabled_ = glIsEnabled(GL_BLEND);
    glEnable(GL_BLEND);
    glBlendEquation(equation);
    glBlendFunc(source, destination);
  }
  ~Blending() {
    glBlendFuncSeparate(GLenum(sourceRgb_), GLenum(destinationRgb_), GLenum(sourceAlpha_),
                        GLenum(destinationAlpha_));
    glBlendEquationSeparate(GLenum(equationRgb_), GLenum(equationAlpha_));
    ScopedState::setEnabled(GL_BLEND, enabled_);
  }
  Blending(const Blending&) = delete;
  Blending& operator=(const Blending&) = delete;

 private:
  GLint sourceRgb_ = 0, destinationRgb_ = 0, sourceAlpha_ = 0, destinationAlpha_ = 0;
  GLint equationRgb_ = 0, equationAlpha_ = 0;
  GLboolean enabled_ = GL_FALSE;
};

// Colour writes off (or on, per channel); restores the mask.
class ColorMask {
 public:
  explicit ColorMask(bool write) {
    glGetBooleanv(GL_COLOR_WRITEMASK, mask_.data());
    const GLboolean w = write ? GL_TRUE : GL_FALSE;
    glColorMask(w, w, w, w);
  }
  ~ColorMask() { glColorMask(mask_[0], mask_[1], mask_[2], mask_[3]); }
  ColorMask(const ColorMask&) = delete;
  ColorMask& operator=(const ColorMask&) = delete;

 private:
  std::array<GLboolean, 4> mask_{GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
};

// One capability (GL_DEPTH_CLAMP, GL_SCISSOR_TEST, ...) on or off; restores it.
class Capability {
 public:
  Capability(GLenum capability, bool enabled)
      : capability_(capability), enabled_(glIsEnabled(capability)) {
    ScopedState::setEnabled(capability, enabled);
  }
  ~Capability() { ScopedState::setEnabled(capability_, enabled_); }
  Capability(const Capability&) = delete;
  Capability& operator=(const Capability&) = delete;

 private:
  GLenum capability_;
  GLboolean enabled_;
};

// The window depth range fragments are mapped to; restores it.
class DepthRange {
 public:
  DepthRange(double near, double far) {
    glGetDoublev(GL_DEPTH_RANGE, range_.data());
    glDepthRange(near, far);
  }
  ~DepthRange() { glDepthRange(range_[0], range_[1]); }
  DepthRange(const DepthRange&) = delete;
  DepthRange& operator=(const DepthRange&) = delete;

 private:
  std::array<GLdouble, 2> range_{0.0, 1.0};
};

}  // namespace vsil::gl
