// Transfer-function files (--tf, core/transfer_function.h): JSON lists of control points.
#include "core/transfer_function.h"
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(tf) {
  const vsil::fuzz::InputFile file(bytes, ".json");
  vsil::loadTransferFunction(file.path());
}
