// PNG inputs (--sphere-map, a rule base's sphere strips, measure-width's images;
// core/image_file.h): the header checks, the chunk walk, then libpng's decode (its errors jump
// back through setjmp). The callers refuse a declared size past their limits before decoding;
// the target does as they do, with a small one (1024² pixels), so that a valid header asking
// for much is not an allocation finding.
#include "core/error.h"
#include "core/image_file.h"
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(png) {
  const vsil::fuzz::InputFile file(bytes, ".png");
  const cv::Size size = vsil::readPngSize(file.path());
  if (std::int64_t(size.width) * size.height > std::int64_t(1) << 20) {
    throw vsil::InputError("over the fuzz target's size limit");
  }
  vsil::readPng(file.path());
}
