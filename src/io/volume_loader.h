#pragma once
// One entry point for every volume source: files (by extension or content) and generators.
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
};

// `spec` is a path (.nrrd, .nhdr, .vti, .vtk, or any file with options.raw set) or a generator
// `gen:NAME[:N]` (see generators/generators.h). Throws InputError naming the file and problem.
// Readers (src/io/*_reader.cpp): NRRD raw/gzip/ascii, attached or detached; VTK XML ImageData
// ascii/base64/appended, zlib or not; legacy VTK STRUCTURED_POINTS ASCII/BINARY; raw.
// Stored int8 samples load as Int16 and float64 as Float32 (refused unless finite in float).
Volume loadVolume(const std::string& spec, const LoadOptions& options = {});

}  // namespace vsil
