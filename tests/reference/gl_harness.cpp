#include "gl_harness.h"

namespace vsil::test {

gl::GlContext& sharedGlContext() {
  // The back end comes from $VSIL_GL: ctest runs every GL suite once per back end built
  // (tests/CMakeLists.txt), and a suite run by hand takes auto.
  static gl::GlContext context(gl::contextOptionsFromEnvironment());
  return context;
}

RenderResult renderOnce(const Volume& volume, const RenderSettings& settings) {
  Renderer renderer(sharedGlContext());
  renderer.setVolume(volume);
  return renderer.render(settings);
}

}  // namespace vsil::test
