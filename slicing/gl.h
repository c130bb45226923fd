#pragma once
// OpenGL entry points (core profile 4.5 prototypes, linked from the context's library) and the
// error check used after every GL call that can fail. Checks are on in every build.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <stdexcept>
#include <string>

namespace vsil::gl {

class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

const char* glErrorName(GLenum error);

// Throws GlError naming `what` (the call) and where it was made, if GL reports an error.
void checkGlError(const char* what, const char* file, int line);

}  // namespace vsil::gl

// VSIL_GL(glTexImage3D(...)): run the call, then check for an error naming it.
#define VSIL_GL(call)                                    \
  do {                                                   \
    call;                                                \
    ::vsil::gl::checkGlError(#call, __FILE__, __LINE__); \
  } while (0)
