#pragma once
// One GL context for a whole test program (Magnum's OpenGLTester habit): made on first use with
// the back end $VSIL_GL names (auto when unset), current on the main thread; each test makes its
// own targets and must leave no GL error.
#include <gtest/gtest.h>

#include "slicing/gl.h"
#include "slicing/gl_context.h"

namespace vsil::test {

gl::GlContext& sharedGlContext();

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override { sharedGlContext().makeCurrent(); }
  void TearDown() override {
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "the test left a GL error behind";
  }
};

}  // namespace vsil::test
