// Every seed and every stored fuzzer finding (tests/fuzz/regressions/<target>/) through its
// target's function, as in the fuzzer: it must end in success or an InputError, within the
// fuzzer's time limit. Run under VSIL_SANITIZE=ON, ASan/UBSan also check what the inputs do to
// memory.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "fuzz_target.h"

namespace vsil::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = VSIL_FUZZ_DIR;

// scripts/fuzz.sh runs libFuzzer with -timeout=10: an input that takes this long is a finding (a
// hang, or work the target should not do, like `vsil bench` running its tables in validate-only
// mode), and fails here too. Stored inputs take milliseconds, sanitizers and a busy machine
// included; this is a bound on hangs, not a performance assertion.
constexpr double kFuzzerTimeLimitSeconds = 10.0;

struct FuzzInput {
  std::string target;
  fs::path file;
};

std::vector<FuzzInput> storedInputs() {
  std::vector<FuzzInput> inputs;
  for (const FuzzTarget& target : targets()) {
    for (const char* kind : {"seeds", "regressions"}) {
      const fs::path dir = kFuzzDir / kind / target.name;
      if (!fs::is_directory(dir)) continue;
      std::vector<fs::path> files;
      for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
      }
      std::sort(files.begin(), files.end());
      for (const auto& file : files) inputs.push_back({target.name, file});
    }
  }
  return inputs;
}

std::string testName(const ::testing::TestParamInfo<FuzzInput>& info) {
  std::string name = info.param.target + "_" +
                     info.param.file.parent_path().parent_path().filename().string() + "_" +
                     info.param.file.filename().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name + "_" + std::to_string(info.index);
}

class StoredFuzzInput : public ::testing::TestWithParam<FuzzInput> {};

TEST_P(StoredFuzzInput, EndsInSuccessOrInputError) {
  std::ifstream in(GetParam().file, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  const FuzzTarget* target = findTarget(GetParam().target);
  ASSERT_NE(target, nullptr);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NO_THROW(runInput(*target, bytes)) << GetParam().file;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, kFuzzerTimeLimitSeconds)
      << GetParam().file << " ran " << seconds << " s: the fuzzer reports this as a timeout";
}

INSTANTIATE_TEST_SUITE_P(Inputs, StoredFuzzInput, ::testing::ValuesIn(storedInputs()), testName);

// The harness's conventions: each target has seeds and a dictionary; each folder of stored
// findings belongs to a target.
TEST(FuzzHarness, EveryTargetHasSeedsAndADictionary) {
  ASSERT_FALSE(targets().empty());
  for (const FuzzTarget& target : targets()) {
    EXPECT_TRUE(fs::is_directory(kFuzzDir / "seeds" / target.name)) << target.name;
    EXPECT_TRUE(fs::is_regular_file(kFuzzDir / "dicts" / (target.name + ".dict"))) << target.name;
  }
  if (fs::is_directory(kFuzzDir / "regressions")) {
    for (const auto& entry : fs::directory_iterator(kFuzzDir / "regressions")) {
      EXPECT_NE(findTarget(entry.path().filename().string()), nullptr)
          << entry.path() << " names no fuzz target";
    }
  }
}

}  // namespace
}  // namespace vsil::fuzz
