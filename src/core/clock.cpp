#include "core/clock.h"

#include <ctime>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace vsil {

double processCpuMilliseconds() {
  timespec now{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now) != 0) return 0.0;
  return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

std::optional<double> millisecondsSinceProcessStart() {
  // /proc/self/stat field 22: the start time in clock ticks after boot (CLOCK_BOOTTIME). The
  // command name, field 2, is in parentheses and may hold spaces: count after its last ')'.
  std::ifstream file("/proc/self/stat");
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream fields(text.substr(close + 1));
  std::string field;
  for (int index = 3; index <= 22 && fields >> field; ++index) {
    if (index < 22) continue;
    const long ticksPerSecond = sysconf(_SC_CLK_TCK);
    timespec now{};
    if (ticksPerSecond <= 0 || clock_gettime(CLOCK_BOOTTIME, &now) != 0) return std::nullopt;
    const double startMs = std::stod(field) * 1e3 / double(ticksPerSecond);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6 - startMs;
  }
  return std::nullopt;
}

}  // namespace vsil
