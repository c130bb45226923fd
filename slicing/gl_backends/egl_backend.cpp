// The EGL back end: headless contexts with no surface at all (EGL_KHR_surfaceless_context; vsil
// renders only to framebuffer objects), on the device platform (EGL_EXT_platform_device: a GPU's
// driver, or Mesa's software device) or Mesa's surfaceless platform. libEGL.so.1 (glvnd) is
// opened with dlopen; only the headers are needed to build (libegl-dev).
#define EGL_EGL_PROTOTYPES 0  // every EGL function comes through dlsym / eglGetProcAddress
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <link.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <sstream>

#include "slicing/gl_backends/backend.h"

namespace vsil::gl::backends {
namespace {

// Whole words of a space-separated extension string.
bool hasExtension(const char* extensions, const std::string& name) {
  if (!extensions) return false;
  std::istringstream words(extensions);
  std::string word;
  while (words >> word) {
    if (word == name) return true;
  }
  return false;
}

struct EglLibrary {
  std::string error;  // empty when the core functions below were found
  PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
  PFNEGLGETERRORPROC getError = nullptr;
  PFNEGLQUERYSTRINGPROC queryString = nullptr;
  PFNEGLINITIALIZEPROC initialize = nullptr;
  PFNEGLTERMINATEPROC terminate = nullptr;
  PFNEGLBINDAPIPROC bindApi = nullptr;
  PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
  PFNEGLCREATECONTEXTPROC createContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
  PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
  PFNEGLGETCURRENTCONTEXTPROC getCurrentContext = nullptr;
  // Client extensions, through eglGetProcAddress; null where the client lacks them.
  std::string clientExtensions;
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;  // EGL_EXT_platform_base
  PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;              // EGL_EXT_device_enumeration
  PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;    // EGL_EXT_device_query
  PFNEGLQUERYDEVICEATTRIBEXTPROC queryDeviceAttrib = nullptr;    // EGL_EXT_device_query
};

template <typename Function>
void findExtension(const EglLibrary& library, const char* extension, const char* name,
                   Function& function) {
  if (!hasExtension(library.clientExtensions.c_str(), extension)) return;
  function = reinterpret_cast<Function>(library.getProcAddress(name));
}

const EglLibrary& eglLibrary() {
  static const EglLibrary library = [] {
    EglLibrary l;
    DynamicLibrary library("libEGL.so.1");
    library.find("eglGetProcAddress", l.getProcAddress);
    library.find("eglGetError", l.getError);
    library.find("eglQueryString", l.queryString);
    library.find("eglInitialize", l.initialize);
    library.find("eglTerminate", l.terminate);
    library.find("eglBindAPI", l.bindApi);
    library.find("eglChooseConfig", l.chooseConfig);
    library.find("eglCreateContext", l.createContext);
    library.find("eglDestroyContext", l.destroyContext);
    library.find("eglMakeCurrent", l.makeCurrent);
    library.find("eglGetCurrentContext", l.getCurrentContext);
    l.error = library.error();
    if (!l.error.empty()) return l;
    // Null (and EGL_BAD_DISPLAY) where EGL_EXT_client_extensions is missing: then none of these.
    const char* client = l.queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client) l.getError();
    l.clientExtensions = client ? client : "";
    findExtension(l, "EGL_EXT_platform_base", "eglGetPlatformDisplayEXT", l.getPlatformDisplay);
    findExtension(l, "EGL_EXT_device_enumeration", "eglQueryDevicesEXT", l.queryDevices);
    findExtension(l, "EGL_EXT_device_query", "eglQueryDeviceStringEXT", l.queryDeviceString);
    findExtension(l, "EGL_EXT_device_query", "eglQueryDeviceAttribEXT", l.queryDeviceAttrib);
    return l;
  }();
  return library;
}

const EglLibrary& loadedEglLibrary() {
  const EglLibrary& library = eglLibrary();
  if (!library.error.empty()) throw Unavailable(library.error);
  return library;
}

std::string eglErrorName(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
  }
  std::ostringstream hex;
  hex << "EGL error 0x" << std::hex << error;
  return hex.str();
}

// "eglInitialize failed (EGL_NOT_INITIALIZED)"
Unavailable eglFailure(const EglLibrary& library, const std::string& what) {
  return Unavailable(what + " (" + eglErrorName(library.getError()) + ")");
}

// Keeps the DRI drivers Mesa's EGL has loaded (swrast_dri.so ...) for the process, like the
// libraries vsil opens itself (backend.h): Mesa would unload one at eglTerminate and load it
// again for the next display. Unloaded, the state a driver keeps for the process (a
// pthread_once at eglInitialize) was reported by LeakSanitizer at exit with no module to name.
void keepDriversLoaded() {
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) {
        const std::string name = info->dlpi_name ? info->dlpi_name : "";
        if (name.ends_with("_dri.so")) dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
}

// eglInitialize and eglTerminate are not counted by EGL (the first eglTerminate ends a display
// for every context on it), so contexts share an initialized display through this count.
class Displays {
 public:
  EGLDisplay acquire(EGLenum platform, void* native, EGLint& major, EGLint& minor) {
    const EglLibrary& library = loadedEglLibrary();
    if (!library.getPlatformDisplay) {
      throw Unavailable("libEGL has no EGL_EXT_platform_base (eglGetPlatformDisplayEXT)");
    }
    const EGLDisplay display = library.getPlatformDisplay(platform, native, nullptr);
    if (display == EGL_NO_DISPLAY) throw eglFailure(library, "eglGetPlatformDisplayEXT failed");
    std::lock_guard lock(mutex_);
    Entry& entry = entries_[display];
    if (entry.users == 0) {
      if (!library.initialize(display, &entry.major, &entry.minor)) {
        entries_.erase(display);
        throw eglFailure(library, "eglInitialize failed");
      }
      keepDriversLoaded();
    }
    ++entry.users;
    major = entry.major;
    minor = entry.minor;
    return display;
  }

  void release(EGLDisplay display) {
    std::lock_guard lock(mutex_);
    const auto it = entries_.find(display);
    if (it == entries_.end() || --it->second.users > 0) return;
    entries_.erase(it);
    eglLibrary().terminate(display);
  }

 private:
  struct Entry {
    int users = 0;
    EGLint major = 0, minor = 0;
  };
  std::mutex mutex_;
  std::map<EGLDisplay, Entry> entries_;
};

Displays& displays() {
  static Displays instance;
  return instance;
}

class EglContext : public BackendContext {
 public:
  EglContext(EGLenum platform, void* native) {
    EGLint major = 0, minor = 0;
    display_ = displays().acquire(platform, native, major, minor);
    try {
      create(major, minor);
    } catch (...) {
      displays().release(display_);
      throw;
    }
  }

  ~EglContext() override {
    const EglLibrary& library = eglLibrary();
    if (library.getCurrentContext() == context_) {
      library.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    library.destroyContext(display_, context_);
    displays().release(display_);
  }

  void makeCurrent() override {
    const EglLibrary& library = eglLibrary();
    // The bound API is per thread: desktop OpenGL, not OpenGL ES.
    if (!library.bindApi(EGL_OPENGL_API)) throw eglFailure(library, "eglBindAPI(EGL_OPENGL_API)");
    if (!library.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      throw eglFailure(library, "eglMakeCurrent without a surface failed");
    }
  }

  void releaseCurrent() noexcept override {
    const EglLibrary& library = eglLibrary();
    if (library.getCurrentContext() == context_) {
      library.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
  }

  GetProcAddress getProcAddress() const override { return eglLibrary().getProcAddress; }

 private:
  void create(EGLint major, EGLint minor) {
    const EglLibrary& library = eglLibrary();
    const char* extensions = library.queryString(display_, EGL_EXTENSIONS);
    if (!hasExtension(extensions, "EGL_KHR_surfaceless_context")) {
      throw Unavailable("the display lacks EGL_KHR_surfaceless_context");
    }
    if (major * 10 + minor < 15 && !hasExtension(extensions, "EGL_KHR_create_context")) {
      throw Unavailable("EGL " + std::to_string(major) + "." + std::to_string(minor) +
                        " without EGL_KHR_create_context cannot ask for a 4.5 core context");
    }
    if (!library.bindApi(EGL_OPENGL_API)) {
      throw eglFailure(library, "eglBindAPI(EGL_OPENGL_API) failed: no desktop OpenGL");
    }
    // No surface is ever made; a config is chosen only where the display needs one to make a
    // context (NVIDIA's device displays offer pbuffer configs, as VTK chooses them).
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!hasExtension(extensions, "EGL_KHR_no_config_context") &&
        !hasExtension(extensions, "EGL_MESA_configless_context")) {
      const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                               EGL_PBUFFER_BIT, EGL_NONE};
      EGLint count = 0;
      if (!library.chooseConfig(display_, wanted, &config, 1, &count) || count < 1) {
        throw Unavailable("no EGL config renders desktop OpenGL");
      }
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION_KHR,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION_KHR,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR,
                                 EGL_NONE};
    context_ = library.createContext(display_, config, EGL_NO_CONTEXT, attributes);
    if (context_ == EGL_NO_CONTEXT) {
      throw eglFailure(library, "eglCreateContext gave no OpenGL 4.5 core context");
    }
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

// The device handles in eglQueryDevicesEXT's order.
std::vector<EGLDeviceEXT> deviceHandles(const EglLibrary& library) {
  if (!library.queryDevices || !library.queryDeviceString) {
    throw Unavailable("libEGL has no device enumeration (EGL_EXT_device_enumeration)");
  }
  EGLint count = 0;
  if (!library.queryDevices(0, nullptr, &count)) {
    throw eglFailure(library, "eglQueryDevicesEXT failed");
  }
  std::vector<EGLDeviceEXT> handles(std::size_t(std::max(count, 0)));
  if (count > 0 && !library.queryDevices(count, handles.data(), &count)) {
    throw eglFailure(library, "eglQueryDevicesEXT failed");
  }
  handles.resize(std::size_t(std::max(count, 0)));
  return handles;
}

}  // namespace

bool eglLibraryLoads() {
  return eglLibrary().error.empty();
}

std::vector<EglDevice> eglDevices() {
  const EglLibrary& library = loadedEglLibrary();
  std::vector<EglDevice> devices;
  const std::vector<EGLDeviceEXT> handles = deviceHandles(library);
  for (std::size_t i = 0; i < handles.size(); ++i) {
    EglDevice device;
    device.index = int(i);
    const char* extensions = library.queryDeviceString(handles[i], EGL_EXTENSIONS);
    device.software = hasExtension(extensions, "EGL_MESA_device_software");
    const char* file = nullptr;  // asked only where the device says it has one
    if (hasExtension(extensions, "EGL_EXT_device_drm_render_node")) {
      file = library.queryDeviceString(handles[i], EGL_DRM_RENDER_NODE_FILE_EXT);
    }
    if (!file && hasExtension(extensions, "EGL_EXT_device_drm")) {
      file = library.queryDeviceString(handles[i], EGL_DRM_DEVICE_FILE_EXT);
    }
    device.name = device.software ? "software" : file ? file : "unnamed";
    EGLAttrib cuda = -1;
    if (hasExtension(extensions, "EGL_NV_device_cuda") && library.queryDeviceAttrib &&
        library.queryDeviceAttrib(handles[i], EGL_CUDA_DEVICE_NV, &cuda)) {
      device.name += ", CUDA device " + std::to_string(cuda);
    }
    devices.push_back(device);
  }
  return devices;
}

std::unique_ptr<BackendContext> createEglDeviceContext(const EglDevice& device) {
  const EglLibrary& library = loadedEglLibrary();
  if (!hasExtension(library.clientExtensions.c_str(), "EGL_EXT_platform_device")) {
    throw Unavailable("libEGL has no device platform (EGL_EXT_platform_device)");
  }
  const std::vector<EGLDeviceEXT> handles = deviceHandles(library);
  if (device.index < 0 || std::size_t(device.index) >= handles.size()) {
    throw Unavailable("EGL device " + std::to_string(device.index) + " is gone");
  }
  return std::make_unique<EglContext>(EGL_PLATFORM_DEVICE_EXT, handles[device.index]);
}

std::unique_ptr<BackendContext> createEglSurfacelessContext() {
  const EglLibrary& library = loadedEglLibrary();
  if (!hasExtension(library.clientExtensions.c_str(), "EGL_MESA_platform_surfaceless")) {
    throw Unavailable("libEGL has no surfaceless platform (EGL_MESA_platform_surfaceless)");
  }
  return std::make_unique<EglContext>(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY);
}

}  // namespace vsil::gl::backends
