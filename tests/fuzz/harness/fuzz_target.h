#pragma once
// The fuzzing harness: every parser of outside input is a fuzz target, one small file
// tests/fuzz/fuzz_<name>.cpp holding
//
//   VSIL_FUZZ_TARGET(name) {   // `bytes`: the input, a std::span<const std::uint8_t>
//     const vsil::fuzz::InputFile file(bytes, ".ext");
//     parseTheThing(file.path());
//   }
//
// plus seeds in tests/fuzz/seeds/<name>/ and a dictionary tests/fuzz/dicts/<name>.dict. CMake
// globs fuzz_*.cpp: each becomes a libFuzzer binary `fuzz_<name>` (VSIL_FUZZ=ON, clang,
// scripts/fuzz.sh) and joins the regression suite (tests/fuzz/regression_test.cpp), which feeds
// every seed and every input under tests/fuzz/regressions/<name>/ through the same function.
//
// The contract checked: a target either returns or throws vsil::InputError (the user's input is
// bad, exit status 2). Any other exception is a finding; so is whatever ASan/UBSan report, an
// allocation beyond the fuzzer's RSS limit, or a run beyond its time limit.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "io/volume_loader.h"

namespace vsil::fuzz {

using FuzzFunction = void (*)(std::span<const std::uint8_t> bytes);

struct FuzzTarget {
  std::string name;
  FuzzFunction run;
};

// Every target linked into this program, in registration order.
const std::vector<FuzzTarget>& targets();
const FuzzTarget* findTarget(const std::string& name);

struct Registration {
  Registration(const char* name, FuzzFunction run);
};

// Runs one input through a target: returns on success and on InputError; anything else escapes.
void runInput(const FuzzTarget& target, std::span<const std::uint8_t> bytes);

// The bytes as a file named input<extension> in a private folder in /dev/shm (else $TMPDIR):
// the readers take paths, and their file checks (size, type, permissions) are part of what is
// fuzzed. The folder is made once per process and the file rewritten for each input.
class InputFile {
 public:
  InputFile(std::span<const std::uint8_t> bytes, const std::string& extension);
  // A second file beside the input (e.g. a detached NRRD header's data file).
  static std::string writeBeside(const std::string& name, std::span<const std::uint8_t> bytes);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Load options for fuzzing: a 64 MiB memory limit and 256 samples per axis, so that a valid
// header asking for much is refused by the limits (which are under test too) instead of
// exhausting the fuzzer's memory.
LoadOptions fuzzLoadOptions();

}  // namespace vsil::fuzz

#define VSIL_FUZZ_TARGET(name)                                                                \
  static void vsilFuzzTarget_##name(std::span<const std::uint8_t> bytes);                     \
  static const ::vsil::fuzz::Registration vsilFuzzRegistration_##name(#name,                  \
                                                                      vsilFuzzTarget_##name); \
  static void vsilFuzzTarget_##name(std::span<const std::uint8_t> bytes)
