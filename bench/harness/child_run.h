#pragma once
// Runs this very binary as a child process, for the tables that time whole commands
// (`vsil animate`, the large table's renders) as a user runs them.
#include <filesystem>
#include <string>
#include <vector>

#include "slicing/gl_context.h"

namespace vsil::bench {

struct ChildRun {
  int exitCode = -1;  // 128 + the signal when one ended it
  double seconds = 0;
  double cpuSeconds = 0;         // the child's user + system time, every thread (getrusage)
  double peakResidentBytes = 0;  // the child's peak resident set (getrusage's ru_maxrss)
  std::string error;             // "exit N: <the first line of its stderr>" when it failed
};

// Runs `vsil ARGS`, stdout to /dev/null, stderr to `errFile`, and waits for it; `environment`
// ("NAME=VALUE") is added to this process's.
ChildRun runVsilChild(const std::vector<std::string>& args, const std::filesystem::path& errFile,
                      const std::vector<std::string>& environment = {});

// `--gl BACKEND [--gl-device N]`: the back end the bench was given, for every child it runs.
std::vector<std::string> glArguments(const gl::ContextOptions& gl);

// This very binary's path (/proc/self/exe), for a launcher to start (runChild).
std::string vsilBinary();

// The same for any program, found on PATH when `program` has no slash (e.g. mpirun).
ChildRun runChild(const std::string& program, const std::vector<std::string>& args,
                  const std::filesystem::path& errFile,
                  const std::vector<std::string>& environment = {});

}  // namespace vsil::bench
