#pragma once
// One entry point for every volume source: files (by extension or content) and generators.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/volume.h"

namespace vsil {

// How to read a headerless raw file (`--dims`, `--type`, `--spacing`, `--endian`).
struct RawLayout {
  glm::ivec3 dims{0};
  SampleType type = SampleType::UInt8;
  glm::dvec3 spacing{1.0};
  bool bigEndian = false;
};

struct LoadOptions {
  VolumeLimits limits;
  std::optional<RawLayout> raw;  // set: the file is read as raw samples with this layout
  ReadRegion region;             // --crop, --stride: keep (and where possible read) only these
  std::string series;            // DICOM: the Series Instance UID to read (--series)
  // Called now and then while the payload is read, with the bytes read so far and in all
  // (compressed bytes for compressed payloads); from the loading thread.
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
  // Where a reader places the samples: called once with their size in bytes, it returns that
  // much zero-filled memory, which the volume then holds (Volume::allocateIn). Unset, the volume
  // allocates its own. The DICOM child process places them in a memfd that its parent maps.
  std::function<std::shared_ptr<void>(std::size_t bytes)> sampleMemory;
  // DICOM: GDCM reads in a forked child (io/dicom_child.h), so that a malformed file tripping
  // one of its assert()s, or crashing it, is an InputError and not the end of this process.
  // The fuzz targets read in the process itself, where libFuzzer sees GDCM's crashes.
  bool dicomInChildProcess = true;
};

// The files loadVolume reads, for help texts and messages.
inline constexpr const char* kVolumeFileKinds =
    ".nrrd, .nhdr, .vti, .vtk, .mhd, .mha, .nii, .nii.gz, .hdr/.img, .slc, .dcm or a folder of "
    "DICOM slices";

// `spec` is a path (kVolumeFileKinds, or any file with options.raw set) or a generator
// `gen:NAME[:N]` (see generators/generators.h). Throws InputError naming the file and problem.
// Readers (src/io/*_reader.cpp): NRRD raw/gzip/ascii, attached or detached; VTK XML ImageData
// ascii/base64/appended, zlib/LZ4/xz or not; legacy VTK STRUCTURED_POINTS ASCII/BINARY;
// MetaImage .mha/.mhd, raw or zlib, binary or ASCII; NIfTI through nifticlib; DICOM series
// through GDCM; raw. Samples keep their file's type
// (io/sample_codec.h): float64 and 32/64-bit integers are kept as Float32 (float64 refused unless
// finite in float; values that float32 changes counted in Volume::inexactSamples). With
// options.region the volume holds only those samples, its spacing multiplied by the stride, and
// Volume::subset says which; headers are checked against options.limits before any payload is
// read.
Volume loadVolume(const std::string& spec, const LoadOptions& options = {});

}  // namespace vsil
