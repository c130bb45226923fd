#include "cli/cli_volume_options.h"

#include "cli/cli_parse.h"

#include <array>
#include <iostream>
#include <limits>

#include "core/error.h"
#include "io/text_fields.h"

namespace vsil::cli {
namespace {

// "a<sep>b<sep>c" -> three tokens, or an error naming the flag.
std::vector<std::string_view> splitThree(const std::string& flag, const std::string& text,
                                         char separator, const char* form) {
  std::vector<std::string_view> parts;
  std::string_view rest = text;
  while (true) {
    const std::size_t at = rest.find(separator);
    parts.push_back(io::trim(rest.substr(0, at)));
    if (at == std::string_view::npos) break;
    rest.remove_prefix(at + 1);
  }
  if (parts.size() != 3)
    throwInputError(flag + " " + io::quote(text), std::string("expected ") + form);
  return parts;
}

SampleType parseSampleType(const std::string& name) {
  for (SampleType type : kSampleTypes) {
    if (name == sampleTypeName(type)) return type;
  }
  throwInputError("--type " + io::quote(name), "expected uint8, uint16, int16 or float32");
}

constexpr const char* kCropForm =
    "X0:X1,Y0:Y1,Z0:Z1, half-open voxel index ranges (X1 excluded, as in Python "
    "slices; an empty bound is the edge), e.g. 0:128,:,64:192";

}  // namespace

ReadRegion parseCrop(const std::string& text) {
  ReadRegion region;
  region.cropText = text;
  const std::string flag = "--crop " + io::quote(text);
  const auto axes = splitThree("--crop", text, ',', kCropForm);
  static const char* kAxes[] = {"x", "y", "z"};
  std::array<ReadRegion::Range, 3> crop;
  for (int axis = 0; axis < 3; ++axis) {
    const std::string_view range = axes[std::size_t(axis)];
    const std::size_t colon = range.find(':');
    if (colon == std::string_view::npos || range.find(':', colon + 1) != std::string_view::npos) {
      throwInputError(flag, std::string("expected ") + kCropForm);
    }
    auto bound = [&](std::string_view token, const char* which) -> std::optional<int> {
      token = io::trim(token);
      if (token.empty()) return std::nullopt;
      const std::int64_t value =
          io::parseInteger(flag, std::string(kAxes[axis]) + " " + which, token);
      if (value < 0 || value > std::numeric_limits<int>::max()) {
        throwInputError(flag,
                        std::string(kAxes[axis]) + " " + which + " " + std::to_string(value) +
                            (value < 0 ? " is not a voxel index (0 or more)" : " is out of range"));
      }
      return int(value);
    };
    ReadRegion::Range& r = crop[std::size_t(axis)];
    r.begin = bound(range.substr(0, colon), "start");
    r.end = bound(range.substr(colon + 1), "end");
    if (r.end && *r.end <= r.begin.value_or(0)) {
      throwInputError(flag, std::string(kAxes[axis]) + " range " +
                                std::to_string(r.begin.value_or(0)) + ":" + std::to_string(*r.end) +
                                " is empty (the end is excluded)");
    }
  }
  region.crop = crop;
  return region;
}

void addVolumeOptions(CLI::App& command, VolumeOptions& options) {
  const std::string group = "Raw volume layout (headerless files)";
  nonEmpty(command.add_option("--dims", options.dims, "samples along x, y, z, e.g. 256x256x128")
               ->group(group));
  command.add_option("--type", options.type, "sample type")
      ->check(CLI::IsMember({"uint8", "uint16", "int16", "float32"}))
      ->group(group);
  nonEmpty(
      command
          .add_option("--spacing", options.spacing, "sample spacing along x, y, z (default 1,1,1)")
          ->group(group));
  command
      .add_option("--endian", options.endian, "byte order of multi-byte samples (default little)")
      ->check(CLI::IsMember({"little", "big"}))
      ->group(group);
  nonEmpty(command.add_option(
      "--crop", options.crop,
      "read only voxels X0..X1-1, Y0..Y1-1, Z0..Z1-1: X0:X1,Y0:Y1,Z0:Z1, half-open "
      "like Python slices, an empty bound is the edge (e.g. 0:128,:,64:)"));
  command.add_option("--stride", options.stride,
                     "read only every Nth sample along each axis (from the crop's start); the "
                     "spacing grows N times");
  command.add_option("--max-texture-mib", options.maxTextureMiB,
                     "cut the volume into 3D textures (bricks) of at most this many MiB (default " +
                         std::to_string(limits::kMaxTextureBytes >> 20) +
                         ", the most one texture holds here); the images are the same");
  nonEmpty(
      command.add_option("--series", options.series,
                         "DICOM: the Series Instance UID to read from a folder holding several (by "
                         "default the series with the most slices; `vsil info` lists the others)"));
  addMaxMemoryOption(command, options.maxMemoryMiB);
}

void addMaxMemoryOption(CLI::App& command, std::optional<long long>& mib) {
  command.add_option("--max-memory", mib,
                     "refuse work needing more than this many MiB of memory (default: half the "
                     "physical memory, " +
                         std::to_string(limits::defaultMemoryBytes() >> 20) + ")");
}

std::size_t maxMemoryBytes(const std::optional<long long>& mib) {
  if (!mib) return limits::defaultMemoryBytes();
  if (*mib < 1 || *mib > limits::kMaxMemoryMiBFlag) {
    throwInputError("--max-memory " + std::to_string(*mib),
                    "must be between 1 and " + std::to_string(limits::kMaxMemoryMiBFlag) + " MiB");
  }
  return std::size_t(*mib) << 20;
}

LoadOptions toLoadOptions(const VolumeOptions& options) {
  LoadOptions load;
  load.limits.maxBytes = maxMemoryBytes(options.maxMemoryMiB);
  if (options.maxTextureMiB) {
    const long long mib = *options.maxTextureMiB;
    const long long most = (long long)(limits::kMaxTextureBytes >> 20);
    if (mib < 1 || mib > most) {
      throwInputError("--max-texture-mib " + std::to_string(mib),
                      "must be between 1 and " + std::to_string(most) + " MiB");
    }
    load.limits.maxTextureBytes = std::uint64_t(mib) << 20;
  }
  if (!options.crop.empty()) load.region = parseCrop(options.crop);
  load.series = options.series;
  if (options.stride) {
    const long long stride = *options.stride;
    if (stride < 1 || stride > limits::kMaxStride) {
      throwInputError("--stride " + std::to_string(stride),
                      "must be a whole number from 1 to " + std::to_string(limits::kMaxStride));
    }
    load.region.stride = int(stride);
  }

  const bool raw = !options.dims.empty() || !options.type.empty();
  if (!raw) {
    if (!options.spacing.empty() || !options.endian.empty()) {
      throw InputError("--spacing and --endian describe raw files: give --dims and --type too");
    }
    return load;
  }
  if (options.dims.empty() || options.type.empty()) {
    throw InputError("a raw file needs both --dims XxYxZ and --type");
  }
  RawLayout layout;
  const auto dims = splitThree("--dims", options.dims, 'x', "XxYxZ, e.g. 256x256x128");
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t value = io::parseInteger("--dims", "size", dims[axis]);
    if (value <= 0) {
      throwInputError("--dims " + io::quote(options.dims), "sizes must be positive integers");
    }
    if (value > std::numeric_limits<int>::max()) {
      throwInputError("--dims " + io::quote(options.dims),
                      "size " + std::to_string(value) + " is out of range");
    }
    layout.dims[axis] = int(value);
  }
  layout.type = parseSampleType(options.type);
  if (!options.spacing.empty()) {
    const auto parts = splitThree("--spacing", options.spacing, ',', "a,b,c, e.g. 1,1,2.5");
    for (int axis = 0; axis < 3; ++axis) {
      layout.spacing[axis] = io::parseReal("--spacing", "spacing", parts[axis]);
    }
    io::checkSpacing("--spacing", "spacing", layout.spacing);
  }
  layout.bigEndian = options.endian == "big";
  load.raw = layout;
  return load;
}

void printWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) std::cerr << "vsil: warning: " << warning << "\n";
}

void printVolumeWarnings(const Volume& volume) {
  printWarnings(volume.warnings);
}

}  // namespace vsil::cli
