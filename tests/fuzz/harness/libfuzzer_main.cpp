// The libFuzzer entry point of a fuzz_<name> binary: exactly one target is linked in.
#include <cstdio>
#include <cstdlib>

#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const vsil::fuzz::FuzzTarget& target = []() -> const vsil::fuzz::FuzzTarget& {
    if (vsil::fuzz::targets().size() != 1) {
      std::fprintf(stderr, "a fuzz binary must link exactly one target\n");
      std::abort();
    }
    return vsil::fuzz::targets().front();
  }();
  vsil::fuzz::runInput(target, {data, size});
  return 0;
}
