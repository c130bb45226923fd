// Headerless raw samples, laid out as the user says (--dims, --type, --spacing, --endian).
#include "core/error.h"
#include "io/file_access.h"
#include "io/readers.h"
#include "io/sample_codec.h"
#include "io/text_fields.h"

namespace vsil::io {

Volume readRaw(const std::string& path, const RawLayout& layout, const VolumeLimits& limits) {
  checkVolumeSize(path, layout.dims, limits);
  checkSpacing(path, "spacing", layout.spacing);
  const StoredType type = storedTypeOf(layout.type);
  const std::uint64_t size = regularFileSize(path);
  const std::size_t expected = payloadBytes(layout.dims, type);
  if (size != expected) {
    throwInputError(path, "raw file holds " + std::to_string(size) + " bytes, " +
                              std::to_string(expected) + " expected (" +
                              describeLayout(layout.dims, type) + ")");
  }
  Volume volume = namedVolume(path);
  volume.dims = layout.dims;
  volume.spacing = layout.spacing;
  volume.type = layout.type;
  volume.samples = decodeSamples(path, readFileBytes(path, 0, size), type, layout.bigEndian);
  return volume;
}

}  // namespace vsil::io
