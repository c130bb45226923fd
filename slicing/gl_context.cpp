#include "slicing/gl_context.h"

#include <GL/osmesa.h>

#include <array>
#include <cstdint>

#include "slicing/gl.h"

namespace vsil::gl {

const char* glErrorName(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
  }
  return "unknown GL error";
}

void checkGlError(const char* what, const char* file, int line) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  std::string message = std::string(glErrorName(error)) + " from " + what + " at " + file + ":" +
                        std::to_string(line);
  while (glGetError() != GL_NO_ERROR) {
  }  // drain, so the next check reports its own call
  throw GlError(message);
}

struct GlContext::Impl {
  OSMesaContext context = nullptr;
  std::array<std::uint8_t, 4> dummyBuffer{};  // 1x1 RGBA: we never draw to it
};

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            4,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            5,
                            0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!impl_->context) {
    throw GlError("OSMesaCreateContextAttribs could not create an OpenGL 4.5 core context");
  }
  makeCurrent();
}

GlContext::~GlContext() {
  if (impl_->context) OSMesaDestroyContext(impl_->context);
}

void GlContext::makeCurrent() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->dummyBuffer.data(), GL_UNSIGNED_BYTE, 1, 1)) {
    throw GlError("OSMesaMakeCurrent failed");
  }
}

std::string GlContext::renderer() const {
  return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}

std::string GlContext::version() const {
  return reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

}  // namespace vsil::gl
