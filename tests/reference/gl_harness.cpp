#include "gl_harness.h"

namespace vsil::test {

gl::GlContext& sharedGlContext() {
  static gl::GlContext context;
  return context;
}

}  // namespace vsil::test
