#include "harness/machine_info.h"

#include <cstdlib>
#include <ctime>
#include <fstream>
#include <thread>

#include "core/version.h"
#include "slicing/gl_context.h"

#ifndef VSIL_VERSION
#define VSIL_VERSION "unknown"
#endif
#ifndef VSIL_BUILD_TYPE
#define VSIL_BUILD_TYPE "unknown"
#endif

namespace vsil::bench {
namespace {

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) break;
    const auto start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "unknown" : line.substr(start);
  }
  return "unknown";
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace

MachineInfo collectMachineInfo(const gl::ContextOptions& glOptions) {
  MachineInfo machine;
  machine.cpuModel = cpuModel();
  machine.hardwareThreads = std::thread::hardware_concurrency();
  {
    const gl::ContextInfo info = gl::GlContext(glOptions).info();
    machine.glBackend = std::string(gl::backendName(info.backend)) + " (" + info.platform + ")";
    machine.glVendor = info.vendor;
    machine.glRenderer = info.renderer;
    machine.glVersion = info.version;
  }
  const char* threads = std::getenv("LP_NUM_THREADS");
  machine.lpNumThreads = threads && *threads ? threads : "default";
  machine.vsilVersion = kVsilVersion;
  machine.buildType = VSIL_BUILD_TYPE;
  machine.dateUtc = utcNow();
  return machine;
}

std::string formatMachineInfo(const MachineInfo& machine) {
  return "machine: " + machine.cpuModel + ", " + std::to_string(machine.hardwareThreads) +
         " hardware threads\n"
         "GL: " +
         machine.glBackend + ", " + machine.glVendor + ", " + machine.glRenderer + ", " +
         machine.glVersion + ", LP_NUM_THREADS=" + machine.lpNumThreads +
         "\n"
         "vsil " +
         machine.vsilVersion + " (" + machine.buildType + "), " + machine.dateUtc + "\n";
}

nlohmann::json machineInfoJson(const MachineInfo& machine) {
  return {{"cpu", machine.cpuModel},
          {"hardware_threads", machine.hardwareThreads},
          {"gl_backend", machine.glBackend},
          {"gl_vendor", machine.glVendor},
          {"gl_renderer", machine.glRenderer},
          {"gl_version", machine.glVersion},
          {"lp_num_threads", machine.lpNumThreads},
          {"vsil_version", machine.vsilVersion},
          {"build_type", machine.buildType},
          {"date_utc", machine.dateUtc}};
}

}  // namespace vsil::bench
