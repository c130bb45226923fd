// What every reader does the same way: start the volume it keeps, read uncompressed payloads.
#include <algorithm>
#include <filesystem>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "io/file_access.h"
#include "io/readers.h"

namespace vsil::io {

Volume startVolume(const std::string& path, glm::ivec3 fileDims, StoredType type,
                   glm::dvec3 spacing, const LoadOptions& options, Rescale rescale) {
  const SampleType kept = keptSampleType(type, rescale);
  const VolumeSubset subset = planVolume(path, fileDims, kept, options.limits, options.region);
  Volume volume;
  std::filesystem::path stem = std::filesystem::path(path).stem();
  if (std::filesystem::path(path).extension() == ".gz") stem = stem.stem();  // name.nii.gz
  volume.name = stem.string();
  volume.source = path;
  volume.dims = subset.dims();
  volume.spacing = spacing * double(subset.stride);
  if (type != storedTypeOf(kept)) volume.fileType = storedTypeName(type);
  if (!rescale.identity()) volume.rescale = rescale;
  if (!subset.whole()) volume.subset = subset;
  if (options.sampleMemory) {
    volume.allocateIn(kept, options.sampleMemory(volume.voxelCount() * sampleTypeSize(kept)));
  } else {
    volume.allocate(kept);
  }
  return volume;
}

VolumeSubset subsetOf(const Volume& volume) {
  if (volume.subset) return *volume.subset;
  VolumeSubset whole;
  whole.fileDims = whole.hi = volume.dims;
  return whole;
}

glm::dmat4 fileFromKept(const VolumeSubset& subset) {
  return glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(subset.lo)),
                    glm::dvec3(subset.stride));
}

void readUncompressed(const FileReader& file, std::uint64_t offset, SampleSink& sink,
                      const LoadOptions& options) {
  // A few MiB per read: large enough for the disk, small beside any volume worth reporting.
  constexpr std::uint64_t kPieceBytes = std::uint64_t(4) << 20;
  const std::size_t size = sink.sampleSize();
  std::vector<std::uint8_t> buffer;
  const std::uint64_t total = sink.neededBytes();
  std::uint64_t done = 0;
  sink.forEachRun(kPieceBytes, [&](std::uint64_t first, std::uint64_t count) {
    buffer.resize(std::size_t(count * size));
    file.readAt(offset + first * size, buffer);
    sink.put(first, buffer);
    done += count * size;
    if (options.progress) options.progress(done, total);
  });
  sink.finish();
}

}  // namespace vsil::io
