#pragma once
// The file readers behind loadVolume(), one per format, each in its own file. Each validates
// the header and the payload size before allocating, and throws InputError naming the path.
#include <filesystem>
#include <string>

#include "core/volume.h"
#include "io/volume_loader.h"

namespace vsil::io {

Volume readNrrd(const std::string& path, const VolumeLimits& limits);       // .nrrd, .nhdr
Volume readVti(const std::string& path, const VolumeLimits& limits);        // VTK XML ImageData
Volume readLegacyVtk(const std::string& path, const VolumeLimits& limits);  // STRUCTURED_POINTS
Volume readRaw(const std::string& path, const RawLayout& layout, const VolumeLimits& limits);

// A volume's identity: name = the file's base name without extension, source = the path.
inline Volume namedVolume(const std::string& path) {
  Volume volume;
  volume.name = std::filesystem::path(path).stem().string();
  volume.source = path;
  return volume;
}

}  // namespace vsil::io
