#include "slicing/gl_objects.h"

#include <stdexcept>
#include <string>

namespace vsil::gl {

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
    case GL_RGBA16F:
      return {GL_RGBA, GL_FLOAT};
    case GL_RG16F:
      return {GL_RG, GL_FLOAT};
    case GL_R16F:
      return {GL_RED, GL_FLOAT};
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

namespace {
// The pixel format of a float target's colour: GL_RED for R32F, GL_RGBA for RGBA32F.
GLenum floatFormat(GLenum internalFormat) {
  if (internalFormat == GL_R32F) return GL_RED;
  if (internalFormat == GL_RGBA32F) return GL_RGBA;
  throw std::logic_error("RenderTarget: floats only from R32F and RGBA32F targets");
}
}  // namespace

std::vector<float> RenderTarget::readFloats() const {
  const GLenum format = floatFormat(internalFormat_);
  std::vector<float> values(std::size_t(size_.x) * std::size_t(size_.y) *
                            (format == GL_RGBA ? 4 : 1));
  VSIL_GL(glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id()));
  VSIL_GL(glReadBuffer(GL_COLOR_ATTACHMENT0));
  VSIL_GL(glPixelStorei(GL_PACK_ALIGNMENT, 1));
  VSIL_GL(glReadPixels(0, 0, size_.x, size_.y, format, GL_FLOAT, values.data()));
  return values;
}

void RenderTarget::writeFloats(const std::vector<float>& values) const {
  // The active unit's binding back afterwards: the passes may have bound their inputs there.
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  VSIL_GL(glBindTexture(GL_TEXTURE_2D, texture_.id()));
  VSIL_GL(glPixelStorei(GL_UNPACK_ALIGNMENT, 1));
  VSIL_GL(glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, size_.x, size_.y, floatFormat(internalFormat_),
                          GL_FLOAT, values.data()));
  VSIL_GL(glBindTexture(GL_TEXTURE_2D, GLuint(bound)));
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

}  // namespace vsil::gl
