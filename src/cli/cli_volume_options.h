#pragma once
// The volume flags every command that loads a volume shares (info, render, ...): the layout of
// a headerless raw file and the memory limit. Usage in a command's setup:
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
  std::string dims;                       // --dims XxYxZ (raw files)
  std::string type;                       // --type uint8|uint16|int16|float32 (raw files)
  std::string spacing;                    // --spacing a,b,c (raw files; default 1,1,1)
  std::string endian;                     // --endian little|big (raw files; default little)
  std::optional<long long> maxMemoryMiB;  // --max-memory MiB; unset keeps VolumeLimits' default
};

// Adds --dims, --type, --spacing, --endian (group "Raw volume layout") and --max-memory.
void addVolumeOptions(CLI::App& command, VolumeOptions& options);

// Checks the flags together and turns them into LoadOptions. Throws InputError naming the flag
// (e.g. "--dims '12x12': expected XxYxZ"); --spacing/--endian without --dims and --type, or
// only one of --dims/--type, are errors.
LoadOptions toLoadOptions(const VolumeOptions& options);

}  // namespace vsil::cli
