// NRRD with an attached payload: header fields, raw/gzip/ascii payloads, the limits.
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(nrrd) {
  const vsil::fuzz::InputFile file(bytes, ".nrrd");
  vsil::loadVolume(file.path(), vsil::fuzz::fuzzLoadOptions());
}
