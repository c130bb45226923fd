#pragma once
// The one path by which vsil reaches GL functions, for every back end: a table with one pointer
// per entry in slicing/gl_functions.h, filled by the back end's get-proc-address
// (OSMesaGetProcAddress or eglGetProcAddress) once per context, and installed into the pointers
// call sites use (slicing/gl.h) whenever that context is made current. Only GlContext calls it.
//
// Why not a loader package from Debian: libepoxy resolves through GLX or EGL and knows nothing
// of OSMesa; GLEW (built for GLX) resolves through glXGetProcAddress; libglbinding-dev is 2.1,
// whose resolver is fixed (3.0 added a user-supplied one) and whose calls and enums live in its
// own namespace; glad (python3-glad) would fit, taking any get-proc-address, but generates all
// ~650 entry points of 4.5 with a Python step at build time. This list is the ~85 functions vsil
// calls, each looked up and checked, so a driver that lacks one is named, not a crash later.
//
// The installed pointers are process-wide, not per thread: vsil makes GL calls on one thread
// at a time, the one its context is current on. A caller with several threads (the Python
// module) takes turns under one lock and releases the context at the end of each turn
// (GlContext::releaseCurrent).
#include <string>
#include <vector>

#include "slicing/gl.h"

namespace vsil::gl {

using GlProc = void (*)();
using GetProcAddress = GlProc (*)(const char* name);

struct EntryPoints {
#define VSIL_GL_MEMBER(name, type) type name = nullptr;
  VSIL_GL_FUNCTIONS(VSIL_GL_MEMBER)
#undef VSIL_GL_MEMBER
};

// Looks up every function of slicing/gl_functions.h. Names that resolve to null are returned in
// `missing` (EGL through glvnd hands out a dispatch stub for any name, so an empty list does not
// prove the driver has them: the context checks the GL version too).
EntryPoints loadEntryPoints(GetProcAddress getProcAddress, std::vector<std::string>& missing);

// Points the functions of slicing/gl.h at `entryPoints` (copied).
void installEntryPoints(const EntryPoints& entryPoints);

// The list of slicing/gl_functions.h as text, for the test that checks each name's type.
struct EntryPointName {
  const char* name;  // e.g. "glDrawArrays"
  const char* type;  // e.g. "PFNGLDRAWARRAYSPROC"
};
std::vector<EntryPointName> entryPointNames();

}  // namespace vsil::gl
