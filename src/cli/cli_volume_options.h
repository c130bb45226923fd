#pragma once
// The volume flags every command that loads a volume shares (info, render, ...): the layout of
// a headerless raw file, the part of the volume to read (--crop, --stride) and the memory limit.
// Usage in a command's setup:
//
//   auto options = std::make_shared<VolumeOptions>();
//   addVolumeOptions(*command, *options);
//   command->callback([options, ...] { Volume v = loadVolume(path, toLoadOptions(*options)); });
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "io/volume_loader.h"

namespace vsil::cli {

struct VolumeOptions {
  std::string dims;                        // --dims XxYxZ (raw files)
  std::string type;                        // --type uint8|uint16|int16|float32 (raw files)
  std::string spacing;                     // --spacing a,b,c (raw files; default 1,1,1)
  std::string endian;                      // --endian little|big (raw files; default little)
  std::optional<long long> maxMemoryMiB;   // --max-memory MiB; unset keeps VolumeLimits' default
  std::string crop;                        // --crop X0:X1,Y0:Y1,Z0:Z1 (half-open voxel ranges)
  std::optional<long long> stride;         // --stride N (every Nth sample per axis)
  std::optional<long long> maxTextureMiB;  // --max-texture-mib N (the largest brick texture)
  std::string series;                      // --series UID (DICOM folders with several series)
};

// Adds --dims, --type, --spacing, --endian (group "Raw volume layout"), --crop, --stride,
// --max-texture-mib, --series and --max-memory.
void addVolumeOptions(CLI::App& command, VolumeOptions& options);

// --max-memory MiB alone (commands without a volume: measure-width), and its value in bytes:
// the default (half the physical memory) when not given; InputError outside 1 MiB .. 1 TiB.
void addMaxMemoryOption(CLI::App& command, std::optional<long long>& mib);
std::size_t maxMemoryBytes(const std::optional<long long>& mib);

// Checks the flags together and turns them into LoadOptions. Throws InputError naming the flag
// (e.g. "--dims '12x12': expected XxYxZ"); --spacing/--endian without --dims and --type, or
// only one of --dims/--type, are errors. A --crop range beyond the file is found when its
// header is read (resolveRegion).
LoadOptions toLoadOptions(const VolumeOptions& options);

// "X0:X1,Y0:Y1,Z0:Z1" -> the crop of a ReadRegion; throws InputError naming --crop.
ReadRegion parseCrop(const std::string& text);

// For `info --json` and `render --meta-out`: what of the file a volume holds and how its
// samples were converted, {"file_type", "inexact_samples", "file_dims", "crop", "stride"} as
// they apply; null when it holds all of the file as stored.
template <typename Json>
Json describeRead(const Volume& volume) {
  Json read = Json::object();
  if (!volume.fileType.empty()) {
    read["file_type"] = volume.fileType;
    read["inexact_samples"] = volume.inexactSamples;
  }
  if (volume.subset) {
    const VolumeSubset& subset = *volume.subset;
    read["file_dims"] = {subset.fileDims.x, subset.fileDims.y, subset.fileDims.z};
    read["crop"] = {
        {subset.lo.x, subset.hi.x}, {subset.lo.y, subset.hi.y}, {subset.lo.z, subset.hi.z}};
    read["stride"] = subset.stride;
  }
  return read.empty() ? Json() : read;
}

// For `info --json` and `render --meta-out`: what the file said about itself, {"format",
// "rescale": {"slope", "intercept"}, "orientations": [{"name", "space", "axes",
// "world_from_index" (4 rows of 4)}]} as they apply; null for generated volumes.
template <typename Json>
Json describeFile(const Volume& volume) {
  Json file = Json::object();
  if (!volume.format.empty()) file["format"] = volume.format;
  if (volume.rescale) {
    file["rescale"] = {{"slope", volume.rescale->slope}, {"intercept", volume.rescale->intercept}};
  }
  for (const Orientation& o : volume.orientations) {
    Json rows = Json::array();
    for (int r = 0; r < 4; ++r) {
      rows.push_back({o.worldFromIndex[0][r], o.worldFromIndex[1][r], o.worldFromIndex[2][r],
                      o.worldFromIndex[3][r]});
    }
    file["orientations"].push_back(
        {{"name", o.name}, {"space", o.space}, {"axes", o.axes}, {"world_from_index", rows}});
  }
  return file.empty() ? Json() : file;
}

// Prints warnings to stderr, "vsil: warning: ..." each.
void printWarnings(const std::vector<std::string>& warnings);
// Prints the volume's reading warnings so.
void printVolumeWarnings(const Volume& volume);

}  // namespace vsil::cli
