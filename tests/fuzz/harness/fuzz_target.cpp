#include "fuzz_target.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace vsil::fuzz {
namespace {

std::vector<FuzzTarget>& registry() {
  static std::vector<FuzzTarget> all;
  return all;
}

const std::filesystem::path& scratchFolder() {
  static const std::filesystem::path folder = [] {
    std::error_code error;
    std::filesystem::path base = "/dev/shm";
    if (!std::filesystem::is_directory(base, error)) base = std::filesystem::temp_directory_path();
    const auto dir = base / ("vsil-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
  }();
  return folder;
}

void writeBytes(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + path.string());
}

}  // namespace

const std::vector<FuzzTarget>& targets() {
  return registry();
}

const FuzzTarget* findTarget(const std::string& name) {
  for (const FuzzTarget& target : registry()) {
    if (target.name == name) return &target;
  }
  return nullptr;
}

Registration::Registration(const char* name, FuzzFunction run) {
  registry().push_back({name, run});
}

void runInput(const FuzzTarget& target, std::span<const std::uint8_t> bytes) {
  try {
    target.run(bytes);
  } catch (const InputError&) {
    // The expected answer to bad input.
  }
}

InputFile::InputFile(std::span<const std::uint8_t> bytes, const std::string& extension) {
  const auto path = scratchFolder() / ("input" + extension);
  writeBytes(path, bytes);
  path_ = path.string();
}

std::string InputFile::writeBeside(const std::string& name, std::span<const std::uint8_t> bytes) {
  const auto path = scratchFolder() / name;
  writeBytes(path, bytes);
  return path.string();
}

LoadOptions fuzzLoadOptions() {
  LoadOptions options;
  options.limits.maxBytes = std::size_t(64) << 20;
  options.limits.maxDimension = 256;
  options.dicomInChildProcess = false;  // GDCM's aborts and crashes are findings here
  return options;
}

}  // namespace vsil::fuzz
