#pragma once
// One GL context for a whole test program (Magnum's OpenGLTester habit): made on first use with
// the back end $VSIL_GL names (auto when unset), current on the main thread; each test makes its
// own targets and must leave no GL error.
#include <gtest/gtest.h>

#include "core/volume.h"
#include "slicing/gl.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"

namespace vsil::test {

gl::GlContext& sharedGlContext();

// One frame of `volume` by a fresh Renderer on the shared context.
RenderResult renderOnce(const Volume& volume, const RenderSettings& settings);

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override { sharedGlContext().makeCurrent(); }
  void TearDown() override {
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "the test left a GL error behind";
  }
};

}  // namespace vsil::test
