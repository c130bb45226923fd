#include "slicing/shader_program.h"

#include <algorithm>
#include <regex>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "slicing/texture_units.h"

namespace vsil::gl {

namespace {

// Each stage's name in messages and the define its sources see.
struct Stage {
  GLenum stage;
  const char* name;
  const char* define;
};
constexpr Stage kStages[] = {{GL_VERTEX_SHADER, "vertex", "VSIL_VERTEX_SHADER"},
                             {GL_FRAGMENT_SHADER, "fragment", "VSIL_FRAGMENT_SHADER"},
                             {GL_COMPUTE_SHADER, "compute", "VSIL_COMPUTE_SHADER"}};

const Stage& stageOf(GLenum stage) {
  for (const Stage& s : kStages) {
    if (s.stage == stage) return s;
  }
  throw std::logic_error("unknown shader stage");
}

std::string sourceText(const ShaderSource& source) {
  return source.text.empty() ? std::string(embeddedShaderSource(source.label)) : source.text;
}

// Compiler messages name the source string ("2:14(3): error ..."); string 0 is the prelude and
// string k the k-th source. Rewrites them as "techniques/silhouette/footprint.frag:14(3): ...".
std::string namedLog(const std::string& log, const std::vector<ShaderSource>& sources) {
  static const std::regex location(R"((^|\n)(\d+):(\d+)\()");
  std::string named;
  auto begin = std::sregex_iterator(log.begin(), log.end(), location);
  std::size_t copied = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const auto& match = *it;
    const std::size_t index = std::stoul(match[2].str());
    named += log.substr(copied, std::size_t(match.position(0)) - copied) + match[1].str();
    named +=
        (index == 0 || index > sources.size() ? std::string("prelude") : sources[index - 1].label) +
        ":" + match[3].str() + "(";
    copied = std::size_t(match.position(0) + match.length(0));
  }
  return named + log.substr(copied);
}

GLuint compileStage(GLenum stage, const std::vector<ShaderSource>& sources,
                    const std::vector<std::string>& defines, const std::string& programLabel) {
  std::string text = "#version 450 core\n#define " + std::string(stageOf(stage).define) + " 1\n";
  text += glslUnitDefines();
  for (const auto& define : defines) text += "#define " + define + "\n";
  for (std::size_t k = 0; k < sources.size(); ++k) {
    text += "#line 1 " + std::to_string(k + 1) + "\n" + sourceText(sources[k]) + "\n";
  }
  const GLuint shader = glCreateShader(stage);
  const char* pointer = text.c_str();
  glShaderSource(shader, 1, &pointer, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(std::size_t(std::max(length, 1)));
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw GlError("compiling the " + std::string(stageOf(stage).name) + " stage of " +
                  programLabel + ": " + namedLog(log.data(), sources));
  }
  return shader;
}

std::string labelOf(const ProgramSpec& spec) {
  const auto& last = [](const std::vector<ShaderSource>& sources) {
    return sources.empty() ? std::string() : sources.back().label;
  };
  std::string label =
      spec.compute.empty() ? last(spec.vertex) + "+" + last(spec.fragment) : last(spec.compute);
  for (const auto& define : spec.defines) label += " " + define;
  return label;
}

std::vector<ShaderSource> files(const std::vector<std::string>& shared, std::string last) {
  std::vector<ShaderSource> sources{ShaderSource::file("shaders/common.glsl")};
  for (const auto& path : shared) sources.push_back(ShaderSource::file(path));
  sources.push_back(ShaderSource::file(std::move(last)));
  return sources;
}

}  // namespace

std::string ProgramSpec::key() const {
  std::string key;
  const auto add = [&key](const char* stage, const std::vector<ShaderSource>& sources) {
    key += stage;
    for (const auto& source : sources) {
      key += "|" + source.label;
      if (!source.text.empty()) key += "#" + source.text;  // generated: the text itself
    }
  };
  add("v", vertex);
  add(";f", fragment);
  add(";c", compute);
  key += ";d";
  for (const auto& define : defines) key += "|" + define;
  return key;
}

ProgramSpec slicePassProgram(const std::vector<std::string>& shared, std::string fragmentFile,
                             std::vector<std::string> defines) {
  return {files(shared, "shaders/slice.vert"),
          files(shared, std::move(fragmentFile)),
          {},
          std::move(defines)};
}

ProgramSpec screenPassProgram(const std::vector<std::string>& shared, std::string fragmentFile,
                              std::vector<std::string> defines) {
  return {files(shared, "shaders/screen.vert"),
          files(shared, std::move(fragmentFile)),
          {},
          std::move(defines)};
}

ProgramSpec computeProgram(const std::vector<std::string>& shared, std::string computeFile,
                           std::vector<std::string> defines) {
  return {{}, {}, files(shared, std::move(computeFile)), std::move(defines)};
}

namespace {
thread_local StageTime builtSoFar;  // programBuildTime()
}  // namespace

StageTime programBuildTime() {
  return builtSoFar;
}

Program::Program(const ProgramSpec& spec) : label_(labelOf(spec)) {
  StageClock clock;
  struct CountOnExit {
    StageClock& clock;
    ~CountOnExit() { builtSoFar += clock.elapsed(); }
  } countOnExit{clock};
  std::vector<GLuint> shaders;
  const auto deleteShaders = [&shaders] {
    for (GLuint shader : shaders) glDeleteShader(shader);  // freed with the program once attached
  };
  try {
    if (!spec.compute.empty()) {
      shaders.push_back(compileStage(GL_COMPUTE_SHADER, spec.compute, spec.defines, label_));
    } else {
      shaders.push_back(compileStage(GL_VERTEX_SHADER, spec.vertex, spec.defines, label_));
      shaders.push_back(compileStage(GL_FRAGMENT_SHADER, spec.fragment, spec.defines, label_));
    }
  } catch (...) {
    deleteShaders();
    throw;
  }
  name_ = GlName<ProgramTraits>(glCreateProgram());
  for (GLuint shader : shaders) glAttachShader(name_.id(), shader);
  glLinkProgram(name_.id());
  deleteShaders();
  GLint ok = GL_FALSE;
  glGetProgramiv(name_.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(name_.id(), GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(std::size_t(std::max(length, 1)));
    glGetProgramInfoLog(name_.id(), length, nullptr, log.data());
    throw GlError("linking " + label_ + ": " + std::string(log.data()));
  }
  checkGlError(("building program " + label_).c_str(), __FILE__, __LINE__);
}

void Program::use() const {
  VSIL_GL(glUseProgram(name_.id()));
}

GLint Program::location(const char* name) {
  auto it = locations_.find(name);
  if (it == locations_.end()) {
    it = locations_.emplace(name, glGetUniformLocation(name_.id(), name)).first;
  }
  return it->second;
}

void Program::set(const char* name, int value) {
  glUniform1i(location(name), value);
}
void Program::set(const char* name, unsigned value) {
  glUniform1ui(location(name), value);
}
void Program::set(const char* name, float value) {
  glUniform1f(location(name), value);
}
void Program::set(const char* name, glm::vec2 value) {
  glUniform2fv(location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, glm::vec3 value) {
  glUniform3fv(location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, glm::vec4 value) {
  glUniform4fv(location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, glm::ivec2 value) {
  glUniform2iv(location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::mat3& value) {
  glUniformMatrix3fv(location(name), 1, GL_FALSE, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::mat4& value) {
  glUniformMatrix4fv(location(name), 1, GL_FALSE, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::vec3* values, int count) {
  if (count > 0) glUniform3fv(location(name), count, glm::value_ptr(values[0]));
}
void Program::set(const char* name, const float* values, int count) {
  if (count > 0) glUniform1fv(location(name), count, values);
}

void Program::set(const char* name, const int* values, int count) {
  if (count > 0) glUniform1iv(location(name), count, values);
}

Program& ProgramCache::get(const ProgramSpec& spec) {
  const std::string key = spec.key();
  auto it = programs_.find(key);
  if (it == programs_.end()) {
    it = programs_.emplace(key, std::make_unique<Program>(spec)).first;
    ++builds_;
  }
  return *it->second;
}

}  // namespace vsil::gl
