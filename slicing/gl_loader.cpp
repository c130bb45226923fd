#include "slicing/gl_loader.h"

namespace vsil::gl {
namespace entry_points {
#define VSIL_GL_DEFINE_POINTER(name, type) type name = nullptr;
VSIL_GL_FUNCTIONS(VSIL_GL_DEFINE_POINTER)
#undef VSIL_GL_DEFINE_POINTER
}  // namespace entry_points

EntryPoints loadEntryPoints(GetProcAddress getProcAddress, std::vector<std::string>& missing) {
  EntryPoints entryPoints;
#define VSIL_GL_LOAD(name, type)                                    \
  entryPoints.name = reinterpret_cast<type>(getProcAddress(#name)); \
  if (!entryPoints.name) missing.push_back(#name);
  VSIL_GL_FUNCTIONS(VSIL_GL_LOAD)
#undef VSIL_GL_LOAD
  return entryPoints;
}

void installEntryPoints(const EntryPoints& entryPoints) {
#define VSIL_GL_INSTALL(name, type) entry_points::name = entryPoints.name;
  VSIL_GL_FUNCTIONS(VSIL_GL_INSTALL)
#undef VSIL_GL_INSTALL
}

std::vector<EntryPointName> entryPointNames() {
  return {
#define VSIL_GL_NAME(name, type) {#name, #type},
      VSIL_GL_FUNCTIONS(VSIL_GL_NAME)
#undef VSIL_GL_NAME
  };
}

}  // namespace vsil::gl
