// Shader assembly (slicing/shader_program.h): variants from #defines, the program cache,
// generated sources, and compile errors that name the file or label and the line.
#include <string>

#include <gtest/gtest.h>

#include "gl_harness.h"
#include "slicing/gl_state.h"
#include "slicing/shader_program.h"

namespace vsil {
namespace {

using test::GlTest;

std::string errorOf(const gl::ProgramSpec& spec) {
  try {
    gl::Program program(spec);
  } catch (const gl::GlError& e) {
    return e.what();
  }
  return "";
}

TEST_F(GlTest, EveryEmbeddedShaderIsKeyedByItsPathUnderSlicing) {
  const auto paths = gl::embeddedShaderPaths();
  EXPECT_GE(paths.size(), 10u);
  for (const auto& path : paths) {
    EXPECT_TRUE(path.starts_with("shaders/") || path.starts_with("techniques/")) << path;
    EXPECT_FALSE(gl::embeddedShaderSource(path).empty()) << path;
  }
  EXPECT_THROW(gl::embeddedShaderSource("footprint.frag"), std::invalid_argument)
      << "base names alone are not keys";
}

TEST_F(GlTest, CacheBuildsEachVariantOnceAndVariantsDiffer) {
  gl::ProgramCache cache;
  const gl::ProgramSpec plain = gl::screenPassProgram({}, "shaders/mark_dead.frag");
  const gl::ProgramSpec variant = gl::screenPassProgram(
      {"shaders/hit_records.glsl"}, "shaders/mark_dead.frag", {"NEIGHBOURS_FINAL"});
  EXPECT_NE(plain.key(), variant.key());
  // mark_dead.frag needs hit_records.glsl; listing it makes the program build.
  const gl::ProgramSpec withRecords =
      gl::screenPassProgram({"shaders/hit_records.glsl"}, "shaders/mark_dead.frag");
  gl::Program& a = cache.get(withRecords);
  gl::Program& b = cache.get(variant);
  gl::Program& again = cache.get(withRecords);
  EXPECT_EQ(&a, &again);
  EXPECT_NE(a.id(), b.id());
  EXPECT_EQ(cache.builds(), 2);
  EXPECT_EQ(cache.size(), 2u);
}

TEST_F(GlTest, CompileErrorsNameTheFileAndLine) {
  const std::string error = errorOf(gl::screenPassProgram({}, "shaders/mark_dead.frag"));
  // mark_dead.frag uses isFinal() from hit_records.glsl, which this program leaves out.
  EXPECT_NE(error.find("shaders/mark_dead.frag:"), std::string::npos) << error;
  EXPECT_NE(error.find("fragment"), std::string::npos) << error;
}

TEST_F(GlTest, ComputeProgramsAreBuiltFromTheirOneStage) {
  const std::vector<std::string> shared{"shaders/hit_records.glsl", "shaders/tile_march.glsl"};
  // Without the slice layout, tile_march.glsl stops the build and the error names it.
  const std::string error = errorOf(gl::computeProgram(shared, "shaders/first_hit_march.comp"));
  EXPECT_NE(error.find("shaders/tile_march.glsl:"), std::string::npos) << error;
  EXPECT_NE(error.find("compute"), std::string::npos) << error;
  const gl::ProgramSpec spec = gl::computeProgram(
      shared, "shaders/first_hit_march.comp",
      {"MARCH_GROUP_X 8", "MARCH_GROUP_Y 8", "MARCH_TILE_X 8", "MARCH_TILE_Y 8",
       "MARCH_RANGE_SLICES 4", "SLICE_STRIDE_VEC4 4"});
  EXPECT_TRUE(spec.vertex.empty() && spec.fragment.empty());
  gl::Program program(spec);
  EXPECT_NE(program.id(), 0u);
  EXPECT_EQ(program.label().rfind("shaders/first_hit_march.comp MARCH_GROUP_X 8", 0), 0u)
      << program.label();
}

TEST_F(GlTest, GeneratedSourcesCarryTheirLabelIntoErrorsAndTheCacheKey) {
  gl::ProgramSpec spec = gl::screenPassProgram({}, "shaders/state_constants.frag");
  spec.fragment.insert(spec.fragment.begin() + 1,
                       gl::ShaderSource::generated(
                           "rules:focus.rules", "\n\nfloat broken() { return undefinedName; }\n"));
  const std::string error = errorOf(spec);
  EXPECT_NE(error.find("rules:focus.rules:3("), std::string::npos) << error;

  gl::ProgramSpec a = gl::screenPassProgram({}, "shaders/occupied_faces.frag");
  gl::ProgramSpec b = a;
  a.fragment.insert(a.fragment.begin() + 1,
                    gl::ShaderSource::generated("rules", "const float k = 1.0;\n"));
  b.fragment.insert(b.fragment.begin() + 1,
                    gl::ShaderSource::generated("rules", "const float k = 2.0;\n"));
  EXPECT_NE(a.key(), b.key()) << "the same label with other text is another program";
  gl::ProgramCache cache;
  cache.get(a);
  cache.get(b);
  EXPECT_EQ(cache.builds(), 2);
}

TEST_F(GlTest, StateGuardsPutBackWhatTheyFound) {
  gl::ScopedState restore;
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  {
    gl::DepthTest depth(GL_GREATER, /*write=*/false);
    gl::Blending blend(GL_MAX, GL_ONE, GL_ONE);
    gl::ColorMask noColor(false);
    gl::Capability clamp(GL_DEPTH_CLAMP, true);
    gl::DepthRange far(1.0, 1.0);
    GLint function = 0;
    glGetIntegerv(GL_DEPTH_FUNC, &function);
    EXPECT_EQ(function, GL_GREATER);
    EXPECT_TRUE(glIsEnabled(GL_BLEND));
    EXPECT_TRUE(glIsEnabled(GL_DEPTH_CLAMP));
  }
  GLint function = 0, equation = 0;
  GLboolean mask = GL_FALSE, colorMask[4] = {};
  GLdouble range[2] = {};
  glGetIntegerv(GL_DEPTH_FUNC, &function);
  glGetIntegerv(GL_BLEND_EQUATION_RGB, &equation);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
  glGetBooleanv(GL_COLOR_WRITEMASK, colorMask);
  glGetDoublev(GL_DEPTH_RANGE, range);
  EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
  EXPECT_FALSE(glIsEnabled(GL_BLEND));
  EXPECT_FALSE(glIsEnabled(GL_DEPTH_CLAMP));
  EXPECT_EQ(function, GL_LESS);
  EXPECT_EQ(equation, GL_FUNC_ADD);
  EXPECT_EQ(mask, GL_TRUE);
  EXPECT_EQ(colorMask[0], GL_TRUE);
  EXPECT_EQ(range[0], 0.0);
  EXPECT_EQ(range[1], 1.0);
}

}  // namespace
}  // namespace vsil
