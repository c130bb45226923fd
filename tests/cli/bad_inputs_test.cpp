// The bad-input corpus (tests/bad_inputs/): each case in cases.json runs `vsil` on a hostile
// file or flag and must end with its exit status and its exact one-line error on stderr,
// nothing on stdout, and no file left in the output folder (neither a partial target nor a
// temporary). Placeholders: {DIR} the corpus folder, {OUT} a fresh output folder,
// {TECHNIQUES} the names in the table of techniques (slicing/technique_table.h).
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "reference/test_support.h"
#include "slicing/technique_table.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(VSIL_SOURCE_DIR) / "tests" / "bad_inputs";

struct BadInput {
  std::string name;
  std::string args;
  int exit = 2;
  std::string stderrExact;   // the whole of stderr, or
  std::string stderrPrefix;  // its beginning (for messages that name the machine's memory)
};

// gtest names cases by `name`; this keeps failure messages readable too.
void PrintTo(const BadInput& c, std::ostream* out) {
  *out << c.name << ": vsil " << c.args;
}

std::vector<BadInput> loadCases() {
  std::ifstream in(kCorpus / "cases.json");
  const nlohmann::json cases = nlohmann::json::parse(in);
  std::vector<BadInput> result;
  for (const auto& c : cases) {
    result.push_back({c.at("name"), c.at("args"), c.value("exit", 2), c.value("stderr", ""),
                      c.value("stderr_prefix", "")});
  }
  return result;
}

std::string substitute(std::string text, const std::string& key, const std::string& value) {
  for (std::size_t at = text.find(key); at != std::string::npos;
       at = text.find(key, at + value.size())) {
    text.replace(at, key.size(), value);
  }
  return text;
}

// What a refused input may cost at most: vsil's own (libraries, a GL context, a render of
// the good volume some cases pair with a bad flag) peaked at 30–130 MiB over the corpus
// (2026-12-06); a DICOM file cut short inside 4 GB of declared pixel data once took 4 GB.
constexpr double kMostMemoryForABadInputMib = 512;

class BadInputCase : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputCase, FailsWithItsExactError) {
  const BadInput& c = GetParam();
  const fs::path out = test::scratchDir();
  std::string techniques;
  for (const auto& name : techniqueNames()) techniques += (techniques.empty() ? "" : ", ") + name;
  const auto expand = [&](const std::string& text) {
    return substitute(
        substitute(substitute(text, "{DIR}", kCorpus.string()), "{OUT}", out.string()),
        "{TECHNIQUES}", techniques);
  };
  const test::CommandResult result = test::runVsil(expand(c.args));
  EXPECT_EQ(result.exitCode, c.exit) << c.args << "\nstderr: " << result.err;
  if (!c.stderrExact.empty()) {
    EXPECT_EQ(result.err, expand(c.stderrExact) + "\n");
  }
  if (!c.stderrPrefix.empty()) {
    EXPECT_TRUE(result.err.starts_with(expand(c.stderrPrefix))) << result.err;
  }
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1)
      << "one line: " << result.err;
  EXPECT_EQ(result.out, "") << "nothing on stdout that a script could take for output";
  // Refused before its memory is allocated: a few bytes claiming gigabytes cost none of them.
  EXPECT_LT(result.peakRssMib, kMostMemoryForABadInputMib) << c.args;
  for (const auto& entry : fs::directory_iterator(out)) {
    ADD_FAILURE() << "left behind: " << entry.path();
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputCase, ::testing::ValuesIn(loadCases()),
                         [](const auto& info) { return info.param.name; });

// Not in the table: a file that exists but cannot be read. chmod 000 stops every user but root
// (root reads it anyway, CAP_DAC_OVERRIDE), and the test suite runs as root in CI, so there the
// case is skipped; the message itself comes from io::regularFileSize's open check.
TEST(BadInputs, UnreadableFile) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: chmod 000 does not stop root reading";
  const fs::path dir = test::scratchDir();
  const fs::path file = dir / "locked.nrrd";
  std::ofstream(file) << "NRRD0004\n";
  fs::permissions(file, fs::perms::none);
  const test::CommandResult result = test::runVsil("info " + file.string());
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err,
            "vsil: " + file.string() + ": cannot be opened for reading: Permission denied\n");
  EXPECT_EQ(result.out, "");
}

// A loop of links where a file or folder is looked at (the NIfTI pair's image, the input, the
// outputs' folders): one line naming it, exit 2, no output. std::filesystem's throwing calls
// once made these "internal error" (exit 1).
TEST(BadInputs, LoopsOfLinksAreRefusedInOneLine) {
  const fs::path dir = test::scratchDir();
  fs::copy_file(kCorpus / "nifti_pair_no_img.hdr", dir / "pair.hdr");
  fs::create_symlink("pair.img", dir / "pair.img");
  fs::create_symlink("b", dir / "a");
  fs::create_symlink("a", dir / "b");
  std::ofstream(dir / "sweep.json")
      << R"({"render": {"input": "gen:sphere:16", "size": "16x16"}, "axes": {"zoom": [1, 2]}})";
  const std::string loop = ": cannot be examined: Too many levels of symbolic links\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"info " + (dir / "pair.hdr").string(), (dir / "pair.img").string() + loop},
      {"render " + (dir / "a").string() + " --out " + (dir / "o.png").string(),
       (dir / "a").string() + loop},
      {"animate gen:sphere:16 --size 16x16 --frames 2 --out-dir " + (dir / "a").string(),
       "--out-dir " + (dir / "a").string() + loop},
      {"animate gen:sphere:16 --size 16x16 --frames 2 --out-dir " + (dir / "a" / "new").string(),
       "--out-dir " + (dir / "a" / "new").string() + loop},
      {"animate gen:sphere:16 --size 16x16 --frames 2 --video " + (dir / "a" / "v.mp4").string(),
       "--video " + (dir / "a" / "v.mp4").string() + loop},
      {"sweep " + (dir / "sweep.json").string() + " --json " + (dir / "o.json").string() +
           " --out-dir " + (dir / "a").string(),
       "--out-dir " + (dir / "a").string() + loop},
  };
  for (const auto& [arguments, error] : cases) {
    const test::CommandResult result = test::runVsil(arguments);
    EXPECT_EQ(result.exitCode, 2) << arguments;
    EXPECT_EQ(result.err, "vsil: " + error) << arguments;
  }
  EXPECT_FALSE(fs::exists(dir / "o.png"));
  EXPECT_FALSE(fs::exists(dir / "o.json"));
}

// Outputs of one run are committed together: with --meta-out unwritable, the --out file that
// existed before keeps its bytes and no temporary is left (the table's cases start from an
// empty folder; this one from a previous render's file).
TEST(BadInputs, AFailedOutputLeavesEveryPreviousOutputUntouched) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "o.png") << "previous";
  const test::CommandResult result =
      test::runVsil("render gen:sphere:16 --size 32x32 --out " + (dir / "o.png").string() +
                    " --meta-out " + (dir / "missing" / "m.json").string());
  EXPECT_EQ(result.exitCode, 2) << result.err;
  std::ifstream in(dir / "o.png");
  const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, "previous");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1) << "a temporary was left behind";
}

// An output naming a file the command reads (the volume, a header's detached data file through a
// link, measure-width's image, the sweep file) is refused, and the file keeps its bytes.
TEST(BadInputs, AnOutputNamingAnInputIsRefused) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "v.nhdr") << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\n"
                                   "encoding: raw\ndata file: v.raw\n\n";
  const std::string samples(64, '\x40');
  std::ofstream(dir / "v.raw") << samples;
  fs::create_symlink(dir / "v.raw", dir / "link.png");
  const std::string volume = (dir / "v.nhdr").string();
  const auto header = test::readFileBytes(dir / "v.nhdr");
  const test::CommandResult self = test::runVsil("render " + volume + " --out " + volume);
  EXPECT_EQ(self.exitCode, 2);
  EXPECT_EQ(self.err, "vsil: --out " + volume +
                          ": names a file this command reads; give the output its own file\n");
  EXPECT_EQ(test::readFileBytes(dir / "v.nhdr"), header);
  const test::CommandResult data =
      test::runVsil("render " + volume + " --size 16x16 --out " + (dir / "link.png").string());
  EXPECT_EQ(data.exitCode, 2);
  EXPECT_TRUE(data.err.starts_with("vsil: --out " + (dir / "link.png").string() + ": names ") &&
              data.err.ends_with("v.raw, a file this command reads; give the output its own "
                                 "file\n"))
      << data.err;
  EXPECT_EQ(test::readFileBytes(dir / "v.raw"), samples);

  const std::string image = (dir / "lines.png").string();
  ASSERT_EQ(test::runVsil("render gen:sphere:16 --size 32x32 --out " + image).exitCode, 0);
  const auto lines = test::readFileBytes(image);
  const test::CommandResult measured = test::runVsil("measure-width " + image + " --json " + image);
  EXPECT_EQ(measured.exitCode, 2);
  EXPECT_TRUE(measured.err.ends_with("a file this command reads; give the output its own file\n"))
      << measured.err;
  EXPECT_EQ(test::readFileBytes(image), lines);

  const std::string plan = (dir / "sweep.json").string();
  std::ofstream(plan) << R"({"render": {"input": "gen:sphere:16", "size": "16x16"},
                             "axes": {"width": [1, 2]}})";
  const auto planBytes = test::readFileBytes(plan);
  // Refused before any task runs: no task image in --out-dir (they were all rendered first).
  const test::CommandResult swept =
      test::runVsil("sweep " + plan + " --json " + plan + " --out-dir " + (dir / "tasks").string());
  EXPECT_EQ(swept.exitCode, 2);
  EXPECT_TRUE(swept.err.ends_with("a file this command reads; give the output its own file\n"))
      << swept.err;
  EXPECT_EQ(test::readFileBytes(plan), planBytes);
  EXPECT_FALSE(fs::exists(dir / "tasks"));
}

// Two outputs naming one file through a symlink or a hard link: refused before any work.
TEST(BadInputs, OutputsNamingOneFileThroughALink) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "o.png") << "previous";
  fs::create_symlink(dir / "o.png", dir / "symlink.png");
  fs::create_hard_link(dir / "o.png", dir / "hardlink.png");
  for (const char* other : {"symlink.png", "hardlink.png"}) {
    const test::CommandResult result =
        test::runVsil("render gen:sphere:16 --size 32x32 --out " + (dir / "o.png").string() +
                      " --state-out " + (dir / other).string());
    EXPECT_EQ(result.exitCode, 2) << other;
    EXPECT_EQ(result.err, "vsil: --state-out " + (dir / other).string() +
                              ": names the same file as --out " + (dir / "o.png").string() +
                              "; give each output its own file\n");
  }
  std::ifstream in(dir / "o.png");
  const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, "previous");
}

// A link to a file not there yet names the file it would create: two outputs through it and
// its target would be renamed over one file, the second one's bytes winning.
TEST(BadInputs, OutputsNamingOneNewFileThroughALink) {
  const fs::path dir = test::scratchDir();
  fs::create_symlink("new.png", dir / "link.png");
  const test::CommandResult result =
      test::runVsil("render gen:sphere:16 --size 32x32 --out " + (dir / "link.png").string() +
                    " --depth-out " + (dir / "new.png").string());
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err, "vsil: --depth-out " + (dir / "new.png").string() +
                            ": names the same file as --out " + (dir / "link.png").string() +
                            "; give each output its own file\n");
  EXPECT_FALSE(fs::exists(dir / "new.png"));
}

// A relative name and another spelling of it ("./o.png", "sub/../o.png", the absolute path),
// none of them there yet: one file, refused before any work (weakly_canonical alone left
// "o.png" relative and made the others absolute, so they compared unequal).
TEST(BadInputs, OutputsNamingOneNewFileSpelledTwoWays) {
  const fs::path dir = test::scratchDir();
  fs::create_directory(dir / "sub");
  const fs::path previous = fs::current_path();
  fs::current_path(dir);  // the child runs here: relative outputs
  for (const std::string& other :
       std::vector<std::string>{"./o.png", "sub/../o.png", (dir / "o.png").string()}) {
    const test::CommandResult result =
        test::runVsil("render gen:sphere:16 --size 32x32 --out o.png --meta-out " + other);
    EXPECT_EQ(result.exitCode, 2) << other;
    EXPECT_EQ(result.err, "vsil: --meta-out " + other +
                              ": names the same file as --out o.png; give each output its own "
                              "file\n");
    EXPECT_FALSE(fs::exists(dir / "o.png")) << other;
  }
  fs::current_path(previous);
}

// A write into a special file (/dev/full: no space) fails before any file output replaces its
// target: the PNG beside it is not left behind.
TEST(BadInputs, AFullDeviceAmongTheOutputsLeavesNoFileBehind) {
  ASSERT_TRUE(fs::exists("/dev/full"));
  const fs::path dir = test::scratchDir();
  for (const char* flag : {"--depth-out", "--meta-out"}) {
    const test::CommandResult result =
        test::runVsil("render gen:sphere:16 --size 32x32 --out " + (dir / "o.png").string() + " " +
                      flag + " /dev/full");
    EXPECT_EQ(result.exitCode, 2) << flag;
    EXPECT_EQ(result.err, "vsil: /dev/full: cannot write: No space left on device\n") << flag;
    EXPECT_FALSE(fs::exists(dir / "o.png")) << flag;
  }
}

}  // namespace
}  // namespace vsil
