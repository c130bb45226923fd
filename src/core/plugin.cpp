#include "core/plugin.h"

#include <dlfcn.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace vsil {

void* pluginSymbol(const std::string& what, const std::string& file, const char* symbol,
                   const std::string& builtPath) {
  static std::mutex mutex;
  static std::map<std::string, void*> loaded;  // file + symbol -> address
  const std::lock_guard<std::mutex> lock(mutex);
  const std::string key = file + "\n" + symbol;
  if (const auto found = loaded.find(key); found != loaded.end()) return found->second;

  std::error_code ignored;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ignored);
  std::vector<std::filesystem::path> candidates = {
      exe.parent_path() / file, exe.parent_path() / ".." / "lib" / "vsil" / file};
  Dl_info self{};
  if (::dladdr(reinterpret_cast<void*>(&pluginSymbol), &self) != 0 && self.dli_fname) {
    candidates.push_back(std::filesystem::path(self.dli_fname).parent_path() / file);
  }
  if (!builtPath.empty()) candidates.push_back(builtPath);
  std::string tried;
  for (const auto& path : candidates) {
    if (!std::filesystem::exists(path, ignored)) continue;
    if (void* plugin = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
      if (void* address = ::dlsym(plugin, symbol)) return loaded[key] = address;
    }
    tried += " " + path.string() + " (" + ::dlerror() + ")";
  }
  throw std::runtime_error(
      "cannot load the " + what + " plugin " + file +
      (tried.empty() ? " (not found beside vsil nor in ../lib/vsil)" : ":" + tried));
}

}  // namespace vsil
