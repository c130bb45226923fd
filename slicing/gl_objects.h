#pragma once
// Move-only owners of GL objects: each deletes exactly the name it owns, leaves 0 behind when
// moved from, and cannot be copied. A GL context must be current when they are made and destroyed.
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "slicing/gl.h"

namespace vsil::gl {

template <typename Traits>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
  ~GlName() { reset(); }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  GlName(GlName&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlName& operator=(GlName&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Traits::destroy(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

struct TextureTraits {
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct RenderbufferTraits {
  static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct BufferTraits {
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArrayTraits {
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct ProgramTraits {  // programs are built by shader_program.h
  static void destroy(GLuint id) { glDeleteProgram(id); }
};

using TextureName = GlName<TextureTraits>;
using FramebufferName = GlName<FramebufferTraits>;
using RenderbufferName = GlName<RenderbufferTraits>;
using BufferName = GlName<BufferTraits>;
using VertexArrayName = GlName<VertexArrayTraits>;

TextureName createTexture();
FramebufferName createFramebuffer();
RenderbufferName createRenderbuffer();
BufferName createBuffer();
VertexArrayName createVertexArray();

// A 2D texture with a framebuffer that renders into it (and an optional depth-stencil buffer).
class RenderTarget {
 public:
  RenderTarget(glm::ivec2 size, GLenum internalFormat, bool withDepthStencil = false);
  GLuint texture() const { return texture_.id(); }
  GLuint framebuffer() const { return framebuffer_.id(); }
  glm::ivec2 size() const { return size_; }
  GLenum internalFormat() const { return internalFormat_; }
  GLuint depthStencil() const { return depthStencil_.id(); }  // 0 without one
  void bindForDrawing() const;
  // The colour of an R32F or RGBA32F target as floats (1 or 4 a texel, rows from the bottom),
  // read back and written again bit for bit (the MPI relay, the silhouette's slab records).
  std::vector<float> readFloats() const;
  void writeFloats(const std::vector<float>& values) const;

 private:
  glm::ivec2 size_;
  GLenum internalFormat_;
  TextureName texture_;
  FramebufferName framebuffer_;
  RenderbufferName depthStencil_;
};

// A framebuffer without colour attachments, for passes whose only outputs are image stores or
// depth: it sets the raster size and, optionally, shares another target's depth-stencil buffer
// so the pass can be limited (and its pixels marked) by the depth test.
class EmptyFramebuffer {
 public:
  explicit EmptyFramebuffer(glm::ivec2 size, GLuint depthStencilRenderbuffer = 0);
  glm::ivec2 size() const { return size_; }
  void bindForDrawing() const;

 private:
  glm::ivec2 size_;
  FramebufferName framebuffer_;
};

}  // namespace vsil::gl
