// A detached NRRD header and its data file. Input: the header, a NUL byte, the data file's
// bytes (written as "data" beside the header; seeds say `data file: data`).
#include <algorithm>

#include "fuzz_target.h"

VSIL_FUZZ_TARGET(nhdr) {
  const auto split = std::find(bytes.begin(), bytes.end(), std::uint8_t(0));
  const auto header = bytes.first(std::size_t(split - bytes.begin()));
  const auto data = split == bytes.end() ? bytes.last(0) : bytes.subspan(header.size() + 1);
  vsil::fuzz::InputFile::writeBeside("data", data);
  const vsil::fuzz::InputFile file(header, ".nhdr");
  vsil::loadVolume(file.path(), vsil::fuzz::fuzzLoadOptions());
}
