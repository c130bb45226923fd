#pragma once
// What a GL back end gives GlContext (slicing/gl_context.cpp, the only user): a made context
// that can be made current, and the get-proc-address its GL functions come through. Each back
// end opens its library with dlopen on first use and never closes it (Mesa's drivers keep
// thread and exit handlers; unloading them while the process runs is not safe).
//
// Failures are `Unavailable` with a short phrase ("libEGL.so.1 not found"); GlContext turns
// them into the one-line error that names the --gl choices left.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace vsil::gl::backends {

using GlProc = void (*)();
using GetProcAddress = GlProc (*)(const char* name);

class Unavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class BackendContext {
 public:
  virtual ~BackendContext() = default;
  virtual void makeCurrent() = 0;  // throws Unavailable
  virtual GetProcAddress getProcAddress() const = 0;
};

// OSMesa (osmesa_backend.cpp, built with VSIL_OSMESA).
bool osmesaLibraryLoads();
std::unique_ptr<BackendContext> createOsmesaContext();

// EGL (egl_backend.cpp, built with VSIL_EGL).
struct EglDevice {
  int index = 0;          // in eglQueryDevicesEXT's list: what --gl-device N names
  bool software = false;  // Mesa's software device (EGL_MESA_device_software): llvmpipe
  std::string name;       // "software", "/dev/dri/renderD128", "/dev/dri/card1, CUDA device 0"
};
bool eglLibraryLoads();
std::vector<EglDevice> eglDevices();  // throws Unavailable when EGL cannot enumerate devices
std::unique_ptr<BackendContext> createEglDeviceContext(const EglDevice& device);
std::unique_ptr<BackendContext> createEglSurfacelessContext();

}  // namespace vsil::gl::backends
