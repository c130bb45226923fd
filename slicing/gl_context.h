#pragma once
// The offscreen OpenGL context: the one place that knows how a context is made. Two back ends
// (slicing/gl_backends/), chosen at run time:
//   osmesa  Mesa's OSMesa (llvmpipe on the CPU); gone from Mesa 25.1 on.
//   egl     headless EGL, no window and no X: the device platform (EGL_EXT_platform_device, each
//           device in turn, or the one --gl-device names; a GPU's driver or Mesa's software
//           device), then Mesa's surfaceless platform (EGL_MESA_platform_surfaceless, llvmpipe).
//   auto    a hardware EGL device, else OSMesa, else EGL on llvmpipe.
// Either way the context is 4.5 core, current on the calling thread, renders only to framebuffer
// objects (no surface or pbuffer; OSMesa's own buffer is a 1x1 dummy), and its GL functions come
// through one loader (slicing/gl_loader.h). Neither library is linked: both are opened with
// dlopen when first asked for, so one binary runs where either is installed.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vsil::gl {

enum class Backend { Auto, Osmesa, Egl };

const char* backendName(Backend backend);  // "auto", "osmesa", "egl"
// "auto", "osmesa" or "egl"; anything else throws InputError naming `where` (e.g. "--gl").
Backend parseBackend(const std::string& text, const std::string& where);

struct ContextOptions {
  Backend backend = Backend::Auto;
  // This EGL device only (its index in eglQueryDevicesEXT's list, as `vsil info --gl` prints
  // them); with auto it means egl. Unset: every device in turn.
  std::optional<int> eglDevice;
  // Whether each came from $VSIL_GL and $VSIL_GL_DEVICE rather than --gl and --gl-device: the
  // messages name what the user set ("VSIL_GL_DEVICE=9: there is no EGL device 9 ...").
  bool backendFromEnvironment = false;
  bool deviceFromEnvironment = false;
};

// The choice a front end makes when the user gave none: $VSIL_GL (auto, osmesa, egl) and
// $VSIL_GL_DEVICE (an index); unset or empty: auto, every device. Bad values throw InputError
// naming the variable.
ContextOptions contextOptionsFromEnvironment();
// InputError for choices that contradict each other or cannot name a device (a negative device;
// a device with osmesa), naming them as the user set them. GlContext checks too; a front end
// calls it to refuse before any work.
void checkContextOptions(const ContextOptions& options);

// What was made, for `vsil info --gl`, --meta-out and the benchmark's machine header.
struct ContextInfo {
  Backend backend = Backend::Auto;  // osmesa or egl
  std::string platform;             // "osmesa", "egl device 0 (software)", "egl surfaceless"
  int eglDevice = -1;               // index of the EGL device; -1 when not the device platform
  std::string vendor;               // GL_VENDOR
  std::string renderer;             // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version;              // GL_VERSION
  std::string glslVersion;          // GL_SHADING_LANGUAGE_VERSION
};

// What a context is, for --meta-out and `vsil info --gl --json`: backend, platform, egl_device,
// vendor, renderer, version, glsl_version.
nlohmann::ordered_json contextInfoJson(const ContextInfo& info);

class GlContext {
 public:
  // Makes a 4.5 core-profile context as `options` ask and makes it current on this thread.
  // Throws UnavailableError (core/error.h) when no back end asked for gives one: one line naming
  // what is missing and which --gl choices work here (each tried); InputError for --gl-device
  // with osmesa. Trying makes other contexts current: after a failure, make yours current again.
  // No default: a caller passes the user's choice (--gl, or contextOptionsFromEnvironment());
  // a context made with `{}` where one was given renders on auto under a report of the choice.
  explicit GlContext(const ContextOptions& options);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void makeCurrent();
  // Unbinds the context from the calling thread (and its GL functions from slicing/gl.h), so
  // that another thread can make it current next: what a caller that renders from several
  // threads does at the end of each turn (the Python module). makeCurrent binds it again.
  void releaseCurrent() noexcept;
  const ContextInfo& info() const;
  std::string renderer() const;  // info().renderer
  std::string version() const;   // info().version

  // For a technique that needs more than 4.5 core (none does yet). Makes this context current;
  // throws UnavailableError naming `user` (e.g. "--technique foo"), the missing extensions, this
  // context's renderer and back end, and the other --gl choices that work here.
  void requireExtensions(const std::vector<std::string>& extensions, const std::string& user) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The back ends this binary was built with (CMake VSIL_OSMESA, VSIL_EGL), in the order auto
// tries them last; and whether each one's library can be opened on this machine.
std::vector<Backend> builtBackends();
bool backendLibraryLoads(Backend backend);

// The EGL devices as --gl-device numbers them: "0: software (EGL_MESA_device_software)",
// "1: /dev/dri/renderD128, CUDA device 0". Empty when there are none; a reason when EGL cannot
// enumerate devices (not built, libEGL.so.1 missing, no EGL_EXT_device_enumeration).
std::vector<std::string> describeEglDevices(std::string* whyNone = nullptr);

}  // namespace vsil::gl
