#pragma once
// OpenGL for vsil: the core profile's types and constants from <GL/glcorearb.h>, one function
// pointer per entry point vsil uses (slicing/gl_functions.h), and the error check used after
// every GL call that can fail. Checks are on in every build.
//
// Call sites look like plain GL (`glDrawArrays(...)`): each name is a pointer, filled from the
// context made current last (GlContext::makeCurrent, through slicing/gl_loader.h). Neither back
// end is linked: OSMesa does not export 169 of the 4.5 core functions, and EGL hands out every
// function through eglGetProcAddress, so both go through the same loader.
#ifdef GL_GLEXT_PROTOTYPES
#error "vsil: GL functions come from slicing/gl_functions.h through the loader, not prototypes"
#endif
#include <GL/glcorearb.h>

#include <stdexcept>
#include <string>

#include "slicing/gl_functions.h"

// The pointers live in their own namespace (no clash with the symbols of a GL library in the
// same process), made visible everywhere by the using-directive below: it names GL functions only.
namespace vsil::gl::entry_points {
#define VSIL_GL_DECLARE_POINTER(name, type) extern type name;
VSIL_GL_FUNCTIONS(VSIL_GL_DECLARE_POINTER)
#undef VSIL_GL_DECLARE_POINTER
}  // namespace vsil::gl::entry_points
using namespace vsil::gl::entry_points;

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
