#include "cli/cli_volume_options.h"

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
  for (SampleType type :
       {SampleType::UInt8, SampleType::UInt16, SampleType::Int16, SampleType::Float32}) {
    if (name == sampleTypeName(type)) return type;
  }
  throwInputError("--type " + io::quote(name), "expected uint8, uint16, int16 or float32");
}

}  // namespace

void addVolumeOptions(CLI::App& command, VolumeOptions& options) {
  const std::string group = "Raw volume layout (headerless files)";
  command.add_option("--dims", options.dims, "samples along x, y, z, e.g. 256x256x128")
      ->group(group);
  command.add_option("--type", options.type, "sample type")
      ->check(CLI::IsMember({"uint8", "uint16", "int16", "float32"}))
      ->group(group);
  command.add_option("--spacing", options.spacing, "sample spacing along x, y, z (default 1,1,1)")
      ->group(group);
  command
      .add_option("--endian", options.endian, "byte order of multi-byte samples (default little)")
      ->check(CLI::IsMember({"little", "big"}))
      ->group(group);
  command.add_option("--max-memory", options.maxMemoryMiB,
                     "refuse work needing more than this many MiB of memory (default: half the "
                     "physical memory, " +
                         std::to_string(limits::defaultMemoryBytes() >> 20) + ")");
}

LoadOptions toLoadOptions(const VolumeOptions& options) {
  LoadOptions load;
  if (options.maxMemoryMiB) {
    const long long mib = *options.maxMemoryMiB;
    if (mib < 1 || mib > limits::kMaxMemoryMiBFlag) {
      throwInputError(
          "--max-memory " + std::to_string(mib),
          "must be between 1 and " + std::to_string(limits::kMaxMemoryMiBFlag) + " MiB");
    }
    load.limits.maxBytes = std::size_t(mib) << 20;
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
    if (value <= 0 || value > std::numeric_limits<int>::max()) {
      throwInputError("--dims " + io::quote(options.dims), "sizes must be positive integers");
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

}  // namespace vsil::cli
