#pragma once
// What a GL back end gives GlContext (slicing/gl_context.cpp, the only user): a made context
// that can be made current, and the get-proc-address its GL functions come through. Each back
// end opens its library with dlopen on first use and never closes it (Mesa's drivers keep
// thread and exit handlers; unloading them while the process runs is not safe).
//
// Failures are `Unavailable` with a short phrase ("libEGL.so.1 not found"); GlContext turns
// them into the one-line error that names the --gl choices left.
#include <dlfcn.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vsil::gl::backends {

using GlProc = void (*)();
using GetProcAddress = GlProc (*)(const char* name);

class Unavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A library opened with dlopen (never closed) and its functions found by name. error() says
// what was missing first: "libEGL.so.1 not found", "libEGL.so.1 lacks eglInitialize".
class DynamicLibrary {
 public:
  explicit DynamicLibrary(std::string name)
      : name_(std::move(name)), handle_(dlopen(name_.c_str(), RTLD_NOW | RTLD_LOCAL)) {
    if (!handle_) error_ = name_ + " not found";
  }

  template <typename Function>
  void find(const char* symbol, Function& function) {
    function = handle_ ? reinterpret_cast<Function>(dlsym(handle_, symbol)) : nullptr;
    if (!function && error_.empty()) error_ = name_ + " lacks " + symbol;
  }

  const std::string& error() const { return error_; }  // empty while all was found

 private:
  std::string name_;
  void* handle_;
  std::string error_;
};

class BackendContext {
 public:
  virtual ~BackendContext() = default;
  virtual void makeCurrent() = 0;  // throws Unavailable
  // Leaves the calling thread with no current context, so that another thread may make this one
  // current (EGL refuses a context current on another thread). Never throws.
  virtual void releaseCurrent() noexcept = 0;
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
