#include "harness/dataset_choice.h"

#include "core/error.h"
#include "io/volume_loader.h"

namespace vsil::bench {

namespace {
constexpr const char* kNotFound = "not found: ";
constexpr const char* kUnreadable = "cannot be read: ";
}  // namespace

std::string notFound(const std::filesystem::path& path) {
  return kNotFound + path.string() + " (use --datasets DIR)";
}

bool isMissingFile(const std::string& missing) {
  return missing.starts_with(kNotFound) || missing.starts_with(kUnreadable);
}

std::optional<Volume> readDatasetVolume(const std::filesystem::path& path, std::string& missing) {
  if (!std::filesystem::exists(path)) {
    missing = notFound(path);
    return std::nullopt;
  }
  try {
    return loadVolume(path.string());
  } catch (const InputError& e) {
    missing = kUnreadable + std::string(e.what());
    return std::nullopt;
  }
}

}  // namespace vsil::bench
