// Headerless raw samples, laid out as the user says (--dims, --type, --spacing, --endian).
#include "core/error.h"
#include "io/file_access.h"
#include "io/readers.h"
#include "io/text_fields.h"

namespace vsil::io {

Volume readRaw(const std::string& path, const RawLayout& layout, const LoadOptions& options) {
  // The layout is checked against the limits before the file is even examined.
  planVolume(path, layout.dims, layout.type, options.limits, options.region);
  checkSpacing(path, "spacing", layout.spacing);
  const StoredType type = storedTypeOf(layout.type);
  const std::uint64_t size = regularFileSize(path);
  const std::uint64_t expected = payloadBytes(layout.dims, type);
  if (size != expected) {
    throwInputError(path, "raw file holds " + std::to_string(size) + " bytes, " +
                              std::to_string(expected) + " expected (" +
                              describeLayout(layout.dims, type) + ")");
  }
  Volume volume = startVolume(path, layout.dims, type, layout.spacing, options);
  volume.format = "raw (headerless)";
  SampleSink sink(path, volume, subsetOf(volume), type, layout.bigEndian);
  readUncompressed(FileReader(path), 0, sink, options);
  return volume;
}

}  // namespace vsil::io
