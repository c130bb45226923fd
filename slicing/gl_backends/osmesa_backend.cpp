// The OSMesa back end: Mesa's off-screen renderer (llvmpipe), opened with dlopen. Only osmesa.h
// is needed to build it (libosmesa6-dev); the library is looked for when a context is asked for.
#include <GL/osmesa.h>

#include <array>
#include <cstdint>

#include "slicing/gl_backends/backend.h"

namespace vsil::gl::backends {
namespace {

struct OsmesaLibrary {
  std::string error;  // empty when every function below was found
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
};

const OsmesaLibrary& osmesaLibrary() {
  static const OsmesaLibrary library = [] {
    OsmesaLibrary l;
    DynamicLibrary library("libOSMesa.so.8");
    library.find("OSMesaCreateContextAttribs", l.createContextAttribs);
    library.find("OSMesaMakeCurrent", l.makeCurrent);
    library.find("OSMesaDestroyContext", l.destroyContext);
    library.find("OSMesaGetProcAddress", l.getProcAddress);
    l.error = library.error();
    return l;
  }();
  return library;
}

class OsmesaContext : public BackendContext {
 public:
  OsmesaContext() {
    const OsmesaLibrary& library = osmesaLibrary();
    if (!library.error.empty()) throw Unavailable(library.error);
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              4,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              5,
                              0};
    context_ = library.createContextAttribs(attributes, nullptr);
    if (!context_) {
      throw Unavailable("OSMesaCreateContextAttribs gave no OpenGL 4.5 core context");
    }
  }
  ~OsmesaContext() override { osmesaLibrary().destroyContext(context_); }

  void makeCurrent() override {
    if (!osmesaLibrary().makeCurrent(context_, dummyBuffer_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
      throw Unavailable("OSMesaMakeCurrent failed");
    }
  }
  void releaseCurrent() noexcept override {
    osmesaLibrary().makeCurrent(nullptr, nullptr, 0, 0, 0);  // all null: unbind (Mesa's osmesa.c)
  }
  GetProcAddress getProcAddress() const override { return osmesaLibrary().getProcAddress; }

 private:
  OSMesaContext context_ = nullptr;
  std::array<std::uint8_t, 4> dummyBuffer_{};  // 1x1 RGBA: we never draw to it
};

}  // namespace

bool osmesaLibraryLoads() {
  return osmesaLibrary().error.empty();
}

std::unique_ptr<BackendContext> createOsmesaContext() {
  return std::make_unique<OsmesaContext>();
}

}  // namespace vsil::gl::backends
