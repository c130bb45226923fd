#pragma once
// Scoped GL state: a pass changes viewport, scissor, blending, depth and stencil tests and
// bindings through
// this guard, which puts back what it found when it leaves scope. No pass leaks state.
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
  GLboolean stencilTest_ = GL_FALSE, blend_ = GL_FALSE;
};

}  // namespace vsil::gl
