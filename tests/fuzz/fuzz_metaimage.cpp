// MetaImage: the header, attached data (ElementDataFile = LOCAL) or a data file beside it. Input:
// the header file's bytes, written whole as an .mha (so LOCAL data follow the header); the bytes
// after its first NUL are also written as "data" beside it (seeds of .mhd files say
// `ElementDataFile = data`, then a NUL, then the data file's bytes).
#include <algorithm>

#include "fuzz_target.h"

VSIL_FUZZ_TARGET(metaimage) {
  const auto split = std::find(bytes.begin(), bytes.end(), std::uint8_t(0));
  const auto data =
      split == bytes.end() ? bytes.last(0) : bytes.subspan(std::size_t(split - bytes.begin()) + 1);
  vsil::fuzz::InputFile::writeBeside("data", data);
  const vsil::fuzz::InputFile file(bytes, ".mha");
  vsil::loadVolume(file.path(), vsil::fuzz::fuzzLoadOptions());
}
