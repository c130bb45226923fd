#pragma once
// Wall time for timings (metadata, progress, benchmarks): milliseconds on the steady clock; and
// the process's CPU time beside it, since on a loaded machine wall time also counts the waits
// for a core.
#include <chrono>
#include <optional>

namespace vsil {

inline double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// CPU time of the whole process so far (every thread: llvmpipe's workers too), in ms.
double processCpuMilliseconds();
// Wall time since the process started (exec, dynamic linking and static initialisers included),
// in ms, to the kernel's clock tick (10 ms on Linux); nothing where /proc cannot tell.
std::optional<double> millisecondsSinceProcessStart();

// What one stage of work took: wall time and the process's CPU time.
struct StageTime {
  double wallMs = 0;
  double cpuMs = 0;
  StageTime& operator+=(const StageTime& other) {
    wallMs += other.wallMs;
    cpuMs += other.cpuMs;
    return *this;
  }
  StageTime operator-(const StageTime& other) const {
    return {wallMs - other.wallMs, cpuMs - other.cpuMs};
  }
};

// Times consecutive stages: lap() returns the time since construction or the previous lap.
class StageClock {
 public:
  StageClock() { restart(); }
  void restart() {
    wall_ = std::chrono::steady_clock::now();
    cpuMs_ = processCpuMilliseconds();
  }
  // The time since the start or the previous lap (the stage that just ended); starts the next.
  StageTime lap() {
    const StageTime elapsed = this->elapsed();
    restart();
    return elapsed;
  }
  StageTime elapsed() const {
    return {millisecondsSince(wall_), processCpuMilliseconds() - cpuMs_};
  }

 private:
  std::chrono::steady_clock::time_point wall_;
  double cpuMs_ = 0;
};

}  // namespace vsil
