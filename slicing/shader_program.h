#pragma once
// Shader assembly: a program is a list of GLSL sources per stage plus `#define` flags (as
// Magnum's shaders and Inviwo's shader components make variants), so an optional effect is a
// program variant and never a per-fragment branch (llvmpipe runs both sides of a branch).
// Sources are embedded files, keyed by their path under slicing/ ("shaders/common.glsl",
// "techniques/silhouette/footprint.frag"), or generated text with a label (the rule compiler's
// output). Compile errors name the file or label and its line. Programs are built once per
// (sources, flags) and kept in a ProgramCache.
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "core/clock.h"
#include "slicing/gl_objects.h"

namespace vsil::gl {

// The GLSL embedded at build time (cmake/EmbedShadersScript.cmake), by path under slicing/.
std::string_view embeddedShaderSource(std::string_view path);
std::vector<std::string_view> embeddedShaderPaths();

struct ShaderSource {
  std::string label;  // the path of an embedded file, or the label of generated text
  std::string text;   // generated text; empty for an embedded file

  static ShaderSource file(std::string path) { return {std::move(path), {}}; }
  static ShaderSource generated(std::string label, std::string text) {
    return {std::move(label), std::move(text)};
  }
};

struct ProgramSpec {
  std::vector<ShaderSource> vertex;    // in order, after the prelude
  std::vector<ShaderSource> fragment;  // (empty for a compute program)
  std::vector<ShaderSource> compute;
  // "NAME" or "NAME VALUE", each becoming `#define NAME VALUE` in every stage.
  std::vector<std::string> defines;

  // Identifies the program: sources (generated text by content) and defines.
  std::string key() const;
};

// The usual shapes: every stage starts with shaders/common.glsl, then `shared` (e.g. a
// technique's own .glsl), then the stage's file.
//   slice pass: shaders/slice.vert (the slice polygon) + `fragmentFile`
//   screen pass: shaders/screen.vert (one triangle over the viewport) + `fragmentFile`
ProgramSpec slicePassProgram(const std::vector<std::string>& shared, std::string fragmentFile,
                             std::vector<std::string> defines = {});
ProgramSpec screenPassProgram(const std::vector<std::string>& shared, std::string fragmentFile,
                              std::vector<std::string> defines = {});
//   compute program: `computeFile` alone (common.glsl then needs SLICE_STRIDE_VEC4 among the
//   defines: tile_march.h marchProgram)
ProgramSpec computeProgram(const std::vector<std::string>& shared, std::string computeFile,
                           std::vector<std::string> defines = {});

// A linked program. Every stage gets `#version 450 core`, VSIL_<STAGE>_SHADER, the texture and
// image unit names (texture_units.h), the defines, then its sources, each numbered from line 1.
class Program {
 public:
  explicit Program(const ProgramSpec& spec);
  GLuint id() const { return name_.id(); }
  const std::string& label() const { return label_; }
  void use() const;

  // Uniform setters; the program must be in use. Unknown names are ignored (GL optimises away
  // unused uniforms), so one setter can serve programs that share uniforms.
  void set(const char* name, int value);
  void set(const char* name, unsigned value);
  void set(const char* name, float value);
  void set(const char* name, glm::vec2 value);
  void set(const char* name, glm::vec3 value);
  void set(const char* name, glm::vec4 value);
  void set(const char* name, glm::ivec2 value);
  void set(const char* name, const glm::mat3& value);
  void set(const char* name, const glm::mat4& value);
  // Arrays (e.g. light directions), `count` elements from `values`.
  void set(const char* name, const glm::vec3* values, int count);
  void set(const char* name, const float* values, int count);
  void set(const char* name, const int* values, int count);

 private:
  GLint location(const char* name);
  GlName<ProgramTraits> name_;
  std::string label_;
  std::unordered_map<std::string, GLint> locations_;
};

// The time this thread spent building programs so far (compiling and linking, for timings;
// llvmpipe compiles the machine code of a fragment program's state at its first draw, which
// counts as drawing). Mesa's on-disk shader cache (~/.cache/mesa_shader_cache) serves repeats.
StageTime programBuildTime();

// Programs by ProgramSpec::key(), built on first use and kept for the context's lifetime.
class ProgramCache {
 public:
  Program& get(const ProgramSpec& spec);
  std::size_t size() const { return programs_.size(); }
  int builds() const { return builds_; }  // programs compiled so far (tests count recompiles)

 private:
  std::map<std::string, std::unique_ptr<Program>> programs_;
  int builds_ = 0;
};

}  // namespace vsil::gl
