// Illustration style files (--style FILE.json, core/illustration.h): effects, parameters, a
// transfer function inline or by file name, colours, lights.
#include "core/illustration.h"
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(style) {
  const vsil::fuzz::InputFile file(bytes, ".json");
  vsil::loadStyle(file.path());
}
