// NIfTI through nifticlib: vsil's own checks of the raw header (dims, datatype, vox_offset)
// before nifticlib acts on it, then nifticlib's parse and the data read. Input: a .nii file's
// bytes (seeds: tests/io/nifti's fixtures, NIfTI-1 and NIfTI-2, both byte orders).
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(nifti) {
  const vsil::fuzz::InputFile file(bytes, ".nii");
  vsil::loadVolume(file.path(), vsil::fuzz::fuzzLoadOptions());
}
