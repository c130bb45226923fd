#pragma once
// The machine a benchmark ran on, printed above every table: numbers without it are not
// comparable.
#include <string>

#include <nlohmann/json.hpp>

namespace vsil::bench {

struct MachineInfo {
  std::string cpuModel;          // /proc/cpuinfo "model name", or "unknown"
  unsigned hardwareThreads = 0;  // std::thread::hardware_concurrency()
  std::string glRenderer;        // GL_RENDERER of a fresh context
  std::string glVersion;         // GL_VERSION
  std::string lpNumThreads;      // $LP_NUM_THREADS, or "default" (llvmpipe: one thread per core)
  std::string vsilVersion;
  std::string buildType;  // CMAKE_BUILD_TYPE of this binary
  std::string dateUtc;    // ISO 8601, when the run started
};

// Creates (and destroys) an offscreen GL context to ask for the renderer and version.
MachineInfo collectMachineInfo();

std::string formatMachineInfo(const MachineInfo& machine);  // a few "key: value" lines
nlohmann::json machineInfoJson(const MachineInfo& machine);

}  // namespace vsil::bench
