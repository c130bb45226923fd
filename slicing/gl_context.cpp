#include "slicing/gl_context.h"

#include <cstdlib>
#include <functional>
#include <set>

#include "core/error.h"
#include "core/options.h"
#include "slicing/gl.h"
#include "slicing/gl_backends/backend.h"
#include "slicing/gl_loader.h"

// Which back ends this build has (cmake/Dependencies.cmake sets both on this file only).
#ifndef VSIL_HAVE_OSMESA
#define VSIL_HAVE_OSMESA 0
#endif
#ifndef VSIL_HAVE_EGL
#define VSIL_HAVE_EGL 0
#endif

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

const char* backendName(Backend backend) {
  switch (backend) {
    case Backend::Auto:
      return "auto";
    case Backend::Osmesa:
      return "osmesa";
    case Backend::Egl:
      return "egl";
  }
  return "unknown";
}

Backend parseBackend(const std::string& text, const std::string& where) {
  for (Backend backend : {Backend::Auto, Backend::Osmesa, Backend::Egl}) {
    if (text == backendName(backend)) return backend;
  }
  throw InputError(where + " '" + text + "': expected auto, osmesa or egl");
}

ContextOptions contextOptionsFromEnvironment() {
  ContextOptions options;
  const char* backend = std::getenv("VSIL_GL");
  if (backend && *backend) {
    options.backend = parseBackend(backend, "VSIL_GL");
    options.backendFromEnvironment = true;
  }
  const char* device = std::getenv("VSIL_GL_DEVICE");
  if (device && *device) {
    const std::string text = device;
    if (text.size() > 6 || text.find_first_not_of("0123456789") != std::string::npos) {
      throw InputError("VSIL_GL_DEVICE '" + text + "': expected an EGL device number 0, 1, ...");
    }
    options.eglDevice = std::stoi(text);
    options.deviceFromEnvironment = true;
  }
  return options;
}

std::vector<Backend> builtBackends() {
  std::vector<Backend> backends;
  if (VSIL_HAVE_OSMESA) backends.push_back(Backend::Osmesa);
  if (VSIL_HAVE_EGL) backends.push_back(Backend::Egl);
  return backends;
}

bool backendLibraryLoads(Backend backend) {
#if VSIL_HAVE_OSMESA
  if (backend == Backend::Osmesa) return backends::osmesaLibraryLoads();
#endif
#if VSIL_HAVE_EGL
  if (backend == Backend::Egl) return backends::eglLibraryLoads();
#endif
  return false;
}

std::vector<std::string> describeEglDevices(std::string* whyNone) {
  std::vector<std::string> lines;
#if VSIL_HAVE_EGL
  try {
    for (const backends::EglDevice& device : backends::eglDevices()) {
      lines.push_back(std::to_string(device.index) + ": " + device.name);
    }
    if (lines.empty() && whyNone) *whyNone = "eglQueryDevicesEXT found no device";
  } catch (const backends::Unavailable& e) {
    if (whyNone) *whyNone = e.what();
  }
#else
  if (whyNone) *whyNone = "this vsil was built without EGL (-DVSIL_EGL=OFF)";
#endif
  return lines;
}

namespace {

using backends::BackendContext;
using backends::Unavailable;

// One way to make a context; GlContext tries them in turn.
struct Candidate {
  Backend backend = Backend::Auto;
  std::string where;  // "device 0 (software)", "surfaceless"; "" for OSMesa
  int eglDevice = -1;
  std::function<std::unique_ptr<BackendContext>()> create;

  std::string platform() const {  // ContextInfo::platform
    return std::string(backendName(backend)) + (where.empty() ? "" : " " + where);
  }
};

// The candidates the options allow, in the order to try them, and why each failed, or why
// some could not even be listed (a library missing, a back end not built). Under auto every
// reason names its back end; under egl or osmesa that is already said.
class Plan {
 public:
  explicit Plan(const ContextOptions& options) : named_(options.backend == Backend::Auto) {
    bool eglListed = false;
    if (options.eglDevice) {
      named_ = false;
      addEglDevice(*options.eglDevice);
    } else if (options.backend == Backend::Osmesa) {
      addOsmesa();
    } else if (options.backend == Backend::Egl) {
      addEglDevices(true, eglListed);
      addEglDevices(false, eglListed);
      addEglSurfaceless();
    } else {  // auto: a GPU first, then OSMesa, then EGL on llvmpipe
      addEglDevices(true, eglListed);
      addOsmesa();
      addEglDevices(false, eglListed);
      addEglSurfaceless();
    }
  }

  const std::vector<Candidate>& candidates() const { return candidates_; }
  void failed(const Candidate& candidate, const std::string& reason) {
    fail(candidate.backend, candidate.where, reason);
  }
  std::string failures() const { return joined(failures_, "; "); }

 private:
  void fail(Backend backend, const std::string& where, const std::string& reason) {
    std::string label = named_ ? backendName(backend) : "";
    if (!where.empty()) label += (label.empty() ? "" : " ") + where;
    failures_.push_back(label.empty() ? reason : label + ": " + reason);
  }

  void addOsmesa() {
#if VSIL_HAVE_OSMESA
    if (!backends::osmesaLibraryLoads())
      return fail(Backend::Osmesa, "", "libOSMesa.so.8 not found");
    candidates_.push_back({Backend::Osmesa, "", -1, backends::createOsmesaContext});
#else
    fail(Backend::Osmesa, "", "this vsil was built without OSMesa (-DVSIL_OSMESA=OFF)");
#endif
  }

  // The hardware or the software EGL devices; `listed` reports an enumeration failure once.
  void addEglDevices(bool hardware, bool& listed) {
    const bool first = !listed;
    listed = true;
#if VSIL_HAVE_EGL
    if (!backends::eglLibraryLoads()) {
      if (first) fail(Backend::Egl, "", "libEGL.so.1 not found");
      return;
    }
    try {
      for (const backends::EglDevice& device : backends::eglDevices()) {
        if (device.software != hardware) candidates_.push_back(deviceCandidate(device));
      }
    } catch (const Unavailable& e) {
      if (first) fail(Backend::Egl, "devices", e.what());
    }
#else
    if (first) fail(Backend::Egl, "", "this vsil was built without EGL (-DVSIL_EGL=OFF)");
    (void)hardware;
#endif
  }

  void addEglSurfaceless() {
#if VSIL_HAVE_EGL
    if (!backends::eglLibraryLoads()) return;  // said by addEglDevices
    candidates_.push_back({Backend::Egl, "surfaceless", -1, backends::createEglSurfacelessContext});
#endif
  }

  void addEglDevice(int index) {
#if VSIL_HAVE_EGL
    if (!backends::eglLibraryLoads()) return fail(Backend::Egl, "", "libEGL.so.1 not found");
    try {
      const std::vector<backends::EglDevice> devices = backends::eglDevices();
      if (index < int(devices.size())) {
        candidates_.push_back(deviceCandidate(devices[std::size_t(index)]));
        return;
      }
      std::vector<std::string> names;
      for (const auto& device : devices) {
        names.push_back(std::to_string(device.index) + " " + device.name);
      }
      fail(Backend::Egl, "",
           "there is no EGL device " + std::to_string(index) + " (found " +
               std::to_string(devices.size()) + (names.empty() ? "" : ": " + joined(names, ", ")) +
               ")");
    } catch (const Unavailable& e) {
      fail(Backend::Egl, "", e.what());
    }
#else
    (void)index;
    fail(Backend::Egl, "", "this vsil was built without EGL (-DVSIL_EGL=OFF)");
#endif
  }

#if VSIL_HAVE_EGL
  static Candidate deviceCandidate(const backends::EglDevice& device) {
    return {Backend::Egl, "device " + std::to_string(device.index) + " (" + device.name + ")",
            device.index, [device] { return backends::createEglDeviceContext(device); }};
  }
#endif

  bool named_;
  std::vector<Candidate> candidates_;
  std::vector<std::string> failures_;
};

// True while GlContext tries a choice only to name it in another's error (no nested naming).
bool probingChoices = false;

// Whether `options` make a context here: an error names only the choices that work.
bool works(const ContextOptions& options) {
  probingChoices = true;
  bool made = true;
  try {
    GlContext probe(options);
  } catch (const std::exception&) {
    made = false;
  }
  probingChoices = false;
  return made;
}

// The back end or device as the user chose it: "--gl egl" or "VSIL_GL=egl", "--gl-device 1" or
// "VSIL_GL_DEVICE=1".
std::string backendChoice(const ContextOptions& options) {
  return (options.backendFromEnvironment ? "VSIL_GL=" : "--gl ") +
         std::string(backendName(options.backend));
}
std::string deviceChoice(const ContextOptions& options) {
  return (options.deviceFromEnvironment ? "VSIL_GL_DEVICE=" : "--gl-device ") +
         std::to_string(options.eglDevice.value_or(-1));
}

// "; try --gl osmesa", or what to install when no choice is left. Tries each choice it names.
std::string remainingChoices(const ContextOptions& options) {
  std::vector<std::string> choices;
  if (options.eglDevice && works({Backend::Egl, std::nullopt})) {
    choices.push_back(options.deviceFromEnvironment ? "--gl egl with VSIL_GL_DEVICE unset"
                                                    : "--gl egl without --gl-device");
  }
  if (options.backend != Backend::Auto || options.eglDevice) {  // auto tried every back end
    for (Backend other : builtBackends()) {
      if (other == options.backend || (other == Backend::Egl && options.eglDevice)) continue;
      if (works({other, std::nullopt}))
        choices.push_back("--gl " + std::string(backendName(other)));
    }
  }
  if (!choices.empty()) return "; try " + joined(choices, ", or ");
  return "; no other --gl choice works here (vsil needs OpenGL 4.5 core: libosmesa6, or libegl1 "
         "with libegl-mesa0, or a GPU driver's EGL)";
}

std::string failureHeader(const ContextOptions& options) {
  if (options.eglDevice) return deviceChoice(options);
  switch (options.backend) {
    case Backend::Osmesa:
      return backendChoice(options) + ": no OSMesa OpenGL 4.5 core context";
    case Backend::Egl:
      return backendChoice(options) +
             ": no EGL device or surfaceless platform gave an OpenGL 4.5 core context";
    case Backend::Auto:
      break;
  }
  return backendChoice(options) + ": no back end gave an OpenGL 4.5 core context";
}

std::string glString(GLenum name) {
  const GLubyte* text = glGetString(name);
  return text ? reinterpret_cast<const char*>(text) : "";
}

// The entry points installed in slicing/gl.h belong to this context (an Impl), or none.
const void* installedOwner = nullptr;

}  // namespace

struct GlContext::Impl {
  std::unique_ptr<BackendContext> backend;
  EntryPoints entryPoints;
  ContextInfo info;

  // Makes the candidate's context current, loads its GL functions and checks that it is 4.5
  // core. Throws Unavailable; on failure nothing of it stays installed.
  void open(const Candidate& candidate) {
    try {
      backend = candidate.create();
      backend->makeCurrent();
      std::vector<std::string> missing;
      entryPoints = loadEntryPoints(backend->getProcAddress(), missing);
      if (!missing.empty()) {
        throw Unavailable("the driver lacks " + std::to_string(missing.size()) +
                          " GL functions vsil calls, " + missing.front() + " first");
      }
      install();
      GLint major = 0, minor = 0, profile = 0;
      glGetIntegerv(GL_MAJOR_VERSION, &major);
      glGetIntegerv(GL_MINOR_VERSION, &minor);
      glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
      info.backend = candidate.backend;
      info.platform = candidate.platform();
      info.eglDevice = candidate.eglDevice;
      info.vendor = glString(GL_VENDOR);
      info.renderer = glString(GL_RENDERER);
      info.version = glString(GL_VERSION);
      info.glslVersion = glString(GL_SHADING_LANGUAGE_VERSION);
      while (glGetError() != GL_NO_ERROR) {
      }
      if (major * 10 + minor < 45 || !(profile & GL_CONTEXT_CORE_PROFILE_BIT)) {
        throw Unavailable("its context is '" + info.version + "', not 4.5 core");
      }
    } catch (...) {
      uninstall();
      backend.reset();
      throw;
    }
  }

  void install() {
    installEntryPoints(entryPoints);
    installedOwner = this;
  }
  void uninstall() {
    if (installedOwner != this) return;
    installEntryPoints(EntryPoints{});  // a call with no context fails at once, not in a library
    installedOwner = nullptr;
  }
};

void checkContextOptions(const ContextOptions& options) {
  if (!options.eglDevice) return;
  if (*options.eglDevice < 0) {
    throw InputError(deviceChoice(options) + ": expected an EGL device number 0, 1, ...");
  }
  if (options.backend == Backend::Osmesa) {
    const std::string others = "it goes with --gl egl or auto, not " + backendChoice(options);
    throw InputError(deviceChoice(options) + " picks an EGL device: " + others);
  }
}

GlContext::GlContext(const ContextOptions& options) : impl_(std::make_unique<Impl>()) {
  checkContextOptions(options);
  Plan plan(options);
  for (const Candidate& candidate : plan.candidates()) {
    try {
      impl_->open(candidate);
      return;
    } catch (const Unavailable& e) {
      plan.failed(candidate, e.what());
    }
  }
  const std::string failures = options.eglDevice ? ": " + plan.failures()  // one candidate
                                                 : " (" + plan.failures() + ")";
  throw UnavailableError(failureHeader(options) + failures +
                         (probingChoices ? "" : remainingChoices(options)));
}

GlContext::~GlContext() {
  impl_->uninstall();
}

void GlContext::makeCurrent() {
  try {
    impl_->backend->makeCurrent();
  } catch (const Unavailable& e) {
    throw GlError(std::string("making the ") + impl_->info.platform +
                  " context current: " + e.what());
  }
  impl_->install();
}

void GlContext::releaseCurrent() noexcept {
  impl_->backend->releaseCurrent();
  impl_->uninstall();
}

const ContextInfo& GlContext::info() const {
  return impl_->info;
}

std::string GlContext::renderer() const {
  return impl_->info.renderer;
}

std::string GlContext::version() const {
  return impl_->info.version;
}

void GlContext::requireExtensions(const std::vector<std::string>& extensions,
                                  const std::string& user) const {
  impl_->backend->makeCurrent();
  impl_->install();
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  std::set<std::string> present;
  for (GLint i = 0; i < count; ++i) {
    const GLubyte* name = glGetStringi(GL_EXTENSIONS, GLuint(i));
    if (name) present.insert(reinterpret_cast<const char*>(name));
  }
  std::vector<std::string> missing;
  for (const auto& extension : extensions) {
    if (!present.count(extension)) missing.push_back(extension);
  }
  if (missing.empty()) return;
  ContextOptions other;
  other.backend = impl_->info.backend;  // what remains besides this back end
  const std::string choices = remainingChoices(other);
  impl_->backend->makeCurrent();  // again: trying the other choices made theirs current
  impl_->install();
  throw UnavailableError(user + " needs " + joined(missing, ", ") + ", which " +
                         impl_->info.renderer + " (--gl " + backendName(impl_->info.backend) +
                         ", " + impl_->info.platform + ") lacks" + choices);
}

nlohmann::ordered_json contextInfoJson(const ContextInfo& info) {
  return {{"backend", backendName(info.backend)},
          {"platform", info.platform},
          {"egl_device", info.eglDevice >= 0 ? nlohmann::ordered_json(info.eglDevice)
                                             : nlohmann::ordered_json(nullptr)},
          {"vendor", info.vendor},
          {"renderer", info.renderer},
          {"version", info.version},
          {"glsl_version", info.glslVersion}};
}

}  // namespace vsil::gl
