#pragma once
// The file readers behind loadVolume(), one per format, each in its own file. Each validates
// the header, checks the volume it will keep against the limits (planVolume) and the payload
// size before allocating or reading any payload, then reads the samples straight into the
// volume's buffer (io/sample_sink.h), and throws InputError naming the path.
#include <filesystem>
#include <string>

#include "core/volume.h"
#include "io/sample_codec.h"
#include "io/sample_sink.h"
#include "io/volume_loader.h"

namespace vsil::io {

class FileReader;

Volume readNrrd(const std::string& path, const LoadOptions& options);       // .nrrd, .nhdr
Volume readVti(const std::string& path, const LoadOptions& options);        // VTK XML ImageData
Volume readLegacyVtk(const std::string& path, const LoadOptions& options);  // STRUCTURED_POINTS
Volume readMetaImage(const std::string& path, const LoadOptions& options);  // .mhd, .mha
Volume readNifti(const std::string& path, const LoadOptions& options);      // .nii, .hdr/.img, .gz
Volume readSlc(const std::string& path, const LoadOptions& options);        // VolVis .slc
Volume readDicomSeries(const std::string& path, const LoadOptions& options);  // folder, slice
Volume readRaw(const std::string& path, const RawLayout& layout, const LoadOptions& options);

// A new volume read from `path`: name = the file's base name without extension, source = the
// path; dims, sample type, spacing (times the stride) and subset from the file's `fileDims`,
// `type` (through `rescale`) and `spacing` and options.region, checked against options.limits
// (planVolume) before its samples are allocated.
Volume startVolume(const std::string& path, glm::ivec3 fileDims, StoredType type,
                   glm::dvec3 spacing, const LoadOptions& options, Rescale rescale = {});
// The subset a volume from startVolume keeps (the whole file when it has none).
VolumeSubset subsetOf(const Volume& volume);
// From the kept samples' indices to the file's (file = lo + stride · kept): a file's
// world-from-index transform times this places the kept samples (Volume::orientations).
glm::dmat4 fileFromKept(const VolumeSubset& subset);

// Reads the samples `sink` keeps from an uncompressed payload at `offset` of `file`: only the
// rows it keeps, each from its first to its last kept sample, in pieces of a few MiB.
void readUncompressed(const FileReader& file, std::uint64_t offset, SampleSink& sink,
                      const LoadOptions& options);

}  // namespace vsil::io
