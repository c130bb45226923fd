// The GLSL side of the pixel states and of the decision table, checked against C++.
#include <array>
#include <vector>

#include <gtest/gtest.h>

#include "core/frame.h"
#include "gl_harness.h"
#include "silhouette_reference.h"
#include "slicing/frame_uniforms.h"
#include "slicing/gl_objects.h"
#include "slicing/gl_state.h"
#include "slicing/shader_program.h"
#include "slicing/texture_units.h"

namespace vsil {
namespace {

using test::GlTest;

std::vector<std::uint8_t> readUint8(const gl::RenderTarget& target) {
  std::vector<std::uint8_t> values(std::size_t(target.size().x * target.size().y));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, target.size().x, target.size().y, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
               values.data());
  return values;
}

void drawScreenTriangle(const gl::RenderTarget& target) {
  gl::VertexArrayName vertexArray = gl::createVertexArray();
  target.bindForDrawing();
  glViewport(0, 0, target.size().x, target.size().y);
  glBindVertexArray(vertexArray.id());
  VSIL_GL(glDrawArrays(GL_TRIANGLES, 0, 3));
  glBindVertexArray(0);
}

TEST_F(GlTest, GlslStateConstantsEqualThePixelStateEnum) {
  gl::ScopedState restore;
  gl::RenderTarget target({4, 1}, GL_R8UI);
  gl::Program program(
      gl::screenPassProgram({"shaders/hit_records.glsl"}, "shaders/state_constants.frag"));
  program.use();
  drawScreenTriangle(target);
  const auto values = readUint8(target);
  EXPECT_EQ(values[0], std::uint8_t(PixelState::Empty));
  EXPECT_EQ(values[1], std::uint8_t(PixelState::Filled));
  EXPECT_EQ(values[2], std::uint8_t(PixelState::Contour));
  EXPECT_EQ(values[3], std::uint8_t(PixelState::Silhouette));
}

// The paper's Table 2, as restated in shared/papers/README.md: rows t, columns c.
constexpr std::array<std::array<PixelState, 3>, 4> kPaperTable = {{
    {PixelState::Empty, PixelState::Filled, PixelState::Contour},
    {PixelState::Filled, PixelState::Filled, PixelState::Filled},
    {PixelState::Silhouette, PixelState::Filled, PixelState::Contour},
    {PixelState::Silhouette, PixelState::Silhouette, PixelState::Silhouette},
}};

TEST(DecisionTable, ReferenceMatchesThePaperInAllTwelveCases) {
  for (int t = 0; t < 4; ++t) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(reference::decide(PixelState(t), PixelState(c)), kPaperTable[t][c])
          << "t=" << t << " c=" << c;
    }
  }
}

TEST_F(GlTest, DecisionShaderMatchesThePaperInAllTwelveCases) {
  gl::ScopedState restore;
  // A 3x4 image: column = c, row = t. Inputs as the silhouette technique lays them out.
  std::vector<float> intermediate;
  std::vector<std::uint8_t> contour;
  for (int t = 0; t < 4; ++t) {
    for (int c = 0; c < 3; ++c) {
      intermediate.insert(intermediate.end(), {float(t), 0.25f, 0.5f, 0.0f});
      contour.push_back(std::uint8_t(c));
    }
  }
  gl::TextureName intermediateTexture = gl::createTexture();
  glBindTexture(GL_TEXTURE_2D, intermediateTexture.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 3, 4, 0, GL_RGBA, GL_FLOAT, intermediate.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::TextureName contourTexture = gl::createTexture();
  glBindTexture(GL_TEXTURE_2D, contourTexture.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R8UI, 3, 4, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
               contour.data());
  // Integer textures are incomplete (read as 0) under the default linear magnification.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  gl::RenderTarget target({3, 4}, GL_RGBA32F);
  // The pass as the paper pipeline runs it, with a frame's uniform blocks bound.
  gl::Program program(
      gl::screenPassProgram({"shaders/hit_records.glsl", "techniques/silhouette/silhouette.glsl"},
                            "techniques/silhouette/decision.frag", {"PAPER_PIPELINE"}));
  const glm::ivec3 dims(4);
  const View view = makeView(CameraSpec{}, dims, glm::dvec3(1.0), {3, 4});
  FrameUniforms uniforms;
  uniforms.upload(view, dims, planSlices(view, dims, glm::dvec3(1.0), 1.0));
  program.use();
  gl::bindTexture(gl::TextureUnit::Contour, GL_TEXTURE_2D, contourTexture.id());
  gl::bindTexture(gl::TextureUnit::Record, GL_TEXTURE_2D, intermediateTexture.id());
  drawScreenTriangle(target);

  std::vector<float> result(3 * 4 * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer());
  glReadPixels(0, 0, 3, 4, GL_RGBA, GL_FLOAT, result.data());
  for (int t = 0; t < 4; ++t) {
    for (int c = 0; c < 3; ++c) {
      const float state = result[std::size_t((t * 3 + c) * 4)];
      EXPECT_EQ(int(state), int(kPaperTable[t][c])) << "t=" << t << " c=" << c;
    }
  }
}

}  // namespace
}  // namespace vsil
