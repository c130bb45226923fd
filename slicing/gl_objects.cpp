#include "slicing/gl_objects.h"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>
#include <vector>

namespace vsil::gl {

// Defined in the generated embedded_shaders.cpp (cmake/EmbedShadersScript.cmake).
std::string_view embeddedShaderSource(std::string_view name);

TextureName createTexture() {
  GLuint id = 0;
  VSIL_GL(glGenTextures(1, &id));
  return TextureName(id);
}
FramebufferName createFramebuffer() {
  GLuint id = 0;
  VSIL_GL(glGenFramebuffers(1, &id));
  return FramebufferName(id);
}
RenderbufferName createRenderbuffer() {
  GLuint id = 0;
  VSIL_GL(glGenRenderbuffers(1, &id));
  return RenderbufferName(id);
}
BufferName createBuffer() {
  GLuint id = 0;
  VSIL_GL(glGenBuffers(1, &id));
  return BufferName(id);
}
VertexArrayName createVertexArray() {
  GLuint id = 0;
  VSIL_GL(glGenVertexArrays(1, &id));
  return VertexArrayName(id);
}

namespace {

// Compiles one stage; the `#line 1 1` lets compiler messages count lines in `file` itself
// (source string 0 is the prelude, 1 the file).
GLuint compileStage(GLenum stage, std::string_view file, std::string_view defines) {
  const char* stageDefine = stage == GL_FRAGMENT_SHADER ? "#define VSIL_FRAGMENT_SHADER 1\n"
                                                        : "#define VSIL_VERTEX_SHADER 1\n";
  const std::string source = "#version 450 core\n" + std::string(stageDefine) +
                             std::string(defines) + "\n" +
                             std::string(embeddedShaderSource("common.glsl")) + "\n#line 1 1\n" +
                             std::string(embeddedShaderSource(file));
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(std::size_t(std::max(length, 1)));
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw GlError("compiling shaders/" + std::string(file) +
                  " (source 1 = this file): " + std::string(log.data()));
  }
  return shader;
}

}  // namespace

Program::Program(std::string_view vertexFile, std::string_view fragmentFile,
                 std::string_view defines)
    : label_(std::string(vertexFile) + "+" + std::string(fragmentFile)) {
  const GLuint vertex = compileStage(GL_VERTEX_SHADER, vertexFile, defines);
  GLuint fragment = 0;
  try {
    fragment = compileStage(GL_FRAGMENT_SHADER, fragmentFile, defines);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  name_ = GlName<ProgramTraits>(glCreateProgram());
  glAttachShader(name_.id(), vertex);
  glAttachShader(name_.id(), fragment);
  glLinkProgram(name_.id());
  glDeleteShader(vertex);  // flagged for deletion; freed with the program
  glDeleteShader(fragment);
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
void Program::set(const char* name, glm::ivec2 value) {
  glUniform2iv(location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::mat3& value) {
  glUniformMatrix3fv(location(name), 1, GL_FALSE, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::mat4& value) {
  glUniformMatrix4fv(location(name), 1, GL_FALSE, glm::value_ptr(value));
}

namespace {

struct FormatInfo {
  GLenum format;
  GLenum type;
};

FormatInfo uploadFormat(GLenum internalFormat) {
  switch (internalFormat) {
    case GL_R8UI:
      return {GL_RED_INTEGER, GL_UNSIGNED_BYTE};
    case GL_R32UI:
      return {GL_RED_INTEGER, GL_UNSIGNED_INT};
    case GL_R8:
      return {GL_RED, GL_UNSIGNED_BYTE};
    case GL_R32F:
      return {GL_RED, GL_FLOAT};
    case GL_RG32F:
      return {GL_RG, GL_FLOAT};
    case GL_RGBA32F:
      return {GL_RGBA, GL_FLOAT};
    case GL_RGBA8:
      return {GL_RGBA, GL_UNSIGNED_BYTE};
  }
  throw GlError("RenderTarget: unsupported internal format " + std::to_string(internalFormat));
}

}  // namespace

RenderTarget::RenderTarget(glm::ivec2 size, GLenum internalFormat, bool withDepthStencil)
    : size_(size), internalFormat_(internalFormat) {
  texture_ = createTexture();
  const FormatInfo info = uploadFormat(internalFormat);
  VSIL_GL(glBindTexture(GL_TEXTURE_2D, texture_.id()));
  VSIL_GL(glTexImage2D(GL_TEXTURE_2D, 0, GLint(internalFormat), size.x, size.y, 0, info.format,
                       info.type, nullptr));
  // Screen passes read their inputs with texelFetch; nearest keeps any sampler read exact too.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  framebuffer_ = createFramebuffer();
  VSIL_GL(glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id()));
  VSIL_GL(glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_.id(),
                                 0));
  if (withDepthStencil) {
    depthStencil_ = createRenderbuffer();
    VSIL_GL(glBindRenderbuffer(GL_RENDERBUFFER, depthStencil_.id()));
    VSIL_GL(glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, size.x, size.y));
    VSIL_GL(glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                      depthStencil_.id()));
  }
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("RenderTarget " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                  " format " + std::to_string(internalFormat) + " is incomplete (status " +
                  std::to_string(status) + ")");
  }
  VSIL_GL(glBindFramebuffer(GL_FRAMEBUFFER, 0));
}

void RenderTarget::bindForDrawing() const {
  VSIL_GL(glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id()));
}

EmptyFramebuffer::EmptyFramebuffer(glm::ivec2 size, GLuint depthStencilRenderbuffer) : size_(size) {
  framebuffer_ = createFramebuffer();
  VSIL_GL(glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id()));
  VSIL_GL(glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, size.x));
  VSIL_GL(glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, size.y));
  if (depthStencilRenderbuffer != 0) {
    VSIL_GL(glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                      depthStencilRenderbuffer));
  }
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("EmptyFramebuffer is incomplete (status " + std::to_string(status) + ")");
  }
  VSIL_GL(glBindFramebuffer(GL_FRAMEBUFFER, 0));
}

void EmptyFramebuffer::bindForDrawing() const {
  VSIL_GL(glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id()));
}

void bindImage(GLuint unit, const RenderTarget& target) {
  VSIL_GL(glBindImageTexture(unit, target.texture(), 0, GL_FALSE, 0, GL_READ_WRITE,
                             target.internalFormat()));
}

}  // namespace vsil::gl
