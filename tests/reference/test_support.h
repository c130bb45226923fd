#pragma once
// Helpers shared by the test suites: where the datasets and the built tool are, scratch folders.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vsil::test {

// ../shared/datasets/<name> beside the checkout (VSIL_SHARED_DIR at configure time).
std::filesystem::path datasetPath(const std::string& name);

// Why the classic datasets cannot be used (the folder is absent), or nothing when they can.
std::optional<std::string> datasetsMissing();
// True under VSIL_REQUIRE_DATASETS=1 (CI sets it): a missing folder fails instead of skipping.
bool datasetsRequired();

// First in a test that reads the classic datasets: a checkout cloned alone skips the test with
// a one-line reason; where the datasets are required (CI), it fails instead.
#define VSIL_REQUIRE_DATASETS()                                     \
  do {                                                              \
    if (const auto vsilMissing = ::vsil::test::datasetsMissing()) { \
      if (::vsil::test::datasetsRequired()) FAIL() << *vsilMissing; \
      GTEST_SKIP() << *vsilMissing;                                 \
    }                                                               \
  } while (0)
// The built `vsil` binary.
std::filesystem::path vsilBinary();
// A fresh, empty folder under the build's temporary area, unique to the calling test (and to the
// back end in $VSIL_GL).
std::filesystem::path scratchDir();

// The whole file as bytes ("" when it cannot be read).
std::string readFileBytes(const std::filesystem::path& path);

struct CommandResult {
  int exitCode = -1;
  std::string out;  // stdout
  std::string err;  // stderr
  // The largest resident set, MiB, of any process of the run (vsil and the children it waited
  // for: the DICOM reader's), from wait4.
  double peakRssMib = 0;
};
// Runs `vsil <arguments>` (arguments passed to /bin/sh, quote as needed).
CommandResult runVsil(const std::string& arguments);

struct InterruptedRun {
  int status = 0;  // as waitpid gives it
  double seconds = 0;
};
// Starts `vsil <arguments>` (stdout and stderr to /dev/null), sends it `signal` after `delay`
// seconds (never, if negative) and waits for it: for the tests of interrupted runs. With
// `ready`, the delay counts from when ready() first holds (polled every 2 ms while the run
// lasts), so that the signal lands at a point of the work, whatever the machine's load.
InterruptedRun runVsilInterrupted(const std::vector<std::string>& arguments, double delay,
                                  int signal, const std::function<bool()>& ready = nullptr);

}  // namespace vsil::test
