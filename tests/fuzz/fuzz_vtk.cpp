// Legacy VTK STRUCTURED_POINTS: the text header, ascii and binary payloads.
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(vtk) {
  const vsil::fuzz::InputFile file(bytes, ".vtk");
  vsil::loadVolume(file.path(), vsil::fuzz::fuzzLoadOptions());
}
