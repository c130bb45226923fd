#pragma once
// The offscreen OpenGL context: the one place that knows how a context is made. It is OSMesa
// today (Mesa's llvmpipe); a headless EGL back end would replace only this file's .cpp.
// Rendering always goes to framebuffer objects; the context's own buffer is a 1x1 dummy.
#include <memory>
#include <string>

namespace vsil::gl {

class GlContext {
 public:
  // Creates a 4.5 core-profile context and makes it current on this thread.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void makeCurrent();
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vsil::gl
