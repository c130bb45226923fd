// DICOM through GDCM: the scan of a folder, the geometry vsil derives from the headers
// (positions, orientation, spacing) and the slice decode. Input: one slice file's bytes, read as
// the series of its folder (seeds: slices of tests/io/dicom's fixtures, raw and compressed,
// and an Enhanced CT multi-frame file).
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(dicom) {
  const vsil::fuzz::InputFile file(bytes, ".dcm");
  vsil::loadVolume(file.path(), vsil::fuzz::fuzzLoadOptions());
}
