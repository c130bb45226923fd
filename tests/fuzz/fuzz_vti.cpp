// VTK XML ImageData: the XML, ascii/base64/appended arrays, zlib block headers and streams.
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(vti) {
  const vsil::fuzz::InputFile file(bytes, ".vti");
  vsil::loadVolume(file.path(), vsil::fuzz::fuzzLoadOptions());
}
