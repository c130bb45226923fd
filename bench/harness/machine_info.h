#pragma once
// The machine a benchmark ran on, printed above every table: numbers without it are not
// comparable.
#include <string>

#include <nlohmann/json.hpp>

#include "slicing/gl_context.h"

namespace vsil::bench {

struct MachineInfo {
  std::string cpuModel;          // /proc/cpuinfo "model name", or "unknown"
  unsigned hardwareThreads = 0;  // std::thread::hardware_concurrency()
  std::string glBackend;         // back end and platform, e.g. "egl (egl device 0 (software))"
  std::string glVendor;          // GL_VENDOR of a fresh context
  std::string glRenderer;        // GL_RENDERER
  std::string glVersion;         // GL_VERSION
  std::string lpNumThreads;      // $LP_NUM_THREADS, or "default" (llvmpipe: one thread per core)
  std::string vsilVersion;
  std::string buildType;  // CMAKE_BUILD_TYPE of this binary
  std::string dateUtc;    // ISO 8601, when the run started
};

// Creates (and destroys) an offscreen GL context as `gl` asks, for its back end, vendor,
// renderer and version.
MachineInfo collectMachineInfo(const gl::ContextOptions& gl);

std::string formatMachineInfo(const MachineInfo& machine);  // a few "key: value" lines
nlohmann::json machineInfoJson(const MachineInfo& machine);

}  // namespace vsil::bench
