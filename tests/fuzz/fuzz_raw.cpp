// Headerless raw samples with a given layout. Input: 5 layout bytes (dims x, y, z as 1 + byte,
// sample type, endianness), then the file's bytes.
#include "fuzz_target.h"

VSIL_FUZZ_TARGET(raw) {
  if (bytes.size() < 5) return;
  vsil::RawLayout layout;
  layout.dims = {1 + bytes[0], 1 + bytes[1], 1 + bytes[2]};
  const vsil::SampleType types[] = {vsil::SampleType::UInt8, vsil::SampleType::UInt16,
                                    vsil::SampleType::Int16, vsil::SampleType::Float32};
  layout.type = types[bytes[3] % 4];
  layout.bigEndian = bytes[4] & 1;
  vsil::LoadOptions options = vsil::fuzz::fuzzLoadOptions();
  options.raw = layout;
  const vsil::fuzz::InputFile file(bytes.subspan(5), ".raw");
  vsil::loadVolume(file.path(), options);
}
