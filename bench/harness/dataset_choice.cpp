#include "harness/dataset_choice.h"

#include "core/error.h"
#include "io/volume_loader.h"

namespace vsil::bench {

std::string notFound(const std::filesystem::path& path) {
  return "not found: " + path.string() + " (use --datasets DIR)";
}

std::optional<Volume> readDatasetVolume(const std::filesystem::path& path, std::string& missing) {
  if (!std::filesystem::exists(path)) {
    missing = notFound(path);
    return std::nullopt;
  }
  try {
    return loadVolume(path.string());
  } catch (const InputError& e) {
    missing = std::string("cannot be read: ") + e.what();
    return std::nullopt;
  }
}

}  // namespace vsil::bench
