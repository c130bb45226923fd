// Validate-only mode (cli::setValidateOnly), the mode the cli fuzz target parses in: every
// command checks its flags, refuses bad ones as it always does, and stops before any work. Given
// arguments that would succeed, it prints nothing and writes nothing. Every registered command
// must have a case here, so a new command (animate, rules) is held to the same rule.
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>

#include "cli/commands.h"
#include "core/error.h"
#include "test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

// While it lives: validate-only mode on, stdout and stderr captured. Restores both when it
// ends, also when a command throws something unexpected (gtest then reports it).
class ValidateOnlyScope {
 public:
  ValidateOnlyScope()
      : oldOut_(std::cout.rdbuf(out_.rdbuf())), oldErr_(std::cerr.rdbuf(err_.rdbuf())) {
    cli::setValidateOnly(true);
  }
  ~ValidateOnlyScope() {
    cli::setValidateOnly(false);
    std::cout.rdbuf(oldOut_);
    std::cerr.rdbuf(oldErr_);
  }
  ValidateOnlyScope(const ValidateOnlyScope&) = delete;
  ValidateOnlyScope& operator=(const ValidateOnlyScope&) = delete;
  std::string out() const { return out_.str(); }
  std::string err() const { return err_.str(); }

 private:
  std::ostringstream out_, err_;
  std::streambuf* oldOut_;
  std::streambuf* oldErr_;
};

struct ValidateOnlyRun {
  std::string error;  // the refusal of bad flags; empty: the flags were accepted
  std::string out, err;
};

// `vsil <arguments>` in this process, in validate-only mode.
ValidateOnlyRun runValidateOnly(const std::vector<std::string>& arguments) {
  std::vector<const char*> argv{"vsil"};
  for (const auto& argument : arguments) argv.push_back(argument.c_str());
  ValidateOnlyRun run;
  const ValidateOnlyScope scope;
  CLI::App app{"vsil"};
  cli::setUpApp(app);
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    run.error = std::string("CLI11: ") + e.what();
  } catch (const InputError& e) {
    run.error = e.what();
  }
  run.out = scope.out();
  run.err = scope.err();
  return run;
}

std::string joined(const std::vector<std::string>& arguments) {
  std::string text;
  for (const auto& argument : arguments) text += (text.empty() ? "" : " ") + argument;
  return text;
}

// A command and arguments that would do work: read a volume or an image, render, print, write
// files (all under `out`).
struct WorkingCase {
  std::string command;
  std::function<std::vector<std::string>(const fs::path& out)> arguments;
};

void PrintTo(const WorkingCase& c, std::ostream* out) {
  *out << "vsil " << c.command;
}

const std::vector<WorkingCase>& workingCases() {
  static const std::vector<WorkingCase> cases = {
      {"render",
       [](const fs::path& out) -> std::vector<std::string> {
         return {"render",     "gen:spheres:32",          "--size",      "64x64",
                 "--out",      (out / "r.png").string(),  "--state-out", (out / "s.png").string(),
                 "--meta-out", (out / "m.json").string(), "--depth-out", (out / "d.png").string()};
       }},
      // The frames' folder does not exist: validate-only mode must not create it.
      {"animate",
       [](const fs::path& out) -> std::vector<std::string> {
         return {"animate",   "gen:spheres:32",
                 "--size",    "64x64",
                 "--frames",  "3",
                 "--orbit",   "90",
                 "--sweep",   "iso=0.3:0.6",
                 "--out-dir", (out / "frames").string(),
                 "--video",   (out / "movie.avi").string()};
       }},
      {"info",
       [](const fs::path&) -> std::vector<std::string> {
         return {"info", test::datasetPath("neghip_64x64x64_uint8.nhdr").string(), "--json"};
       }},
      {"measure-width",
       [](const fs::path& out) -> std::vector<std::string> {
         // Two black strokes on white: lines to measure.
         cv::Mat3b image(32, 32, cv::Vec3b(255, 255, 255));
         image(cv::Rect(8, 8, 16, 2)).setTo(cv::Vec3b(0, 0, 0));
         image(cv::Rect(8, 8, 2, 16)).setTo(cv::Vec3b(0, 0, 0));
         cv::imwrite((out / "lines.png").string(), image);
         return {"measure-width", (out / "lines.png").string(), "--json",
                 (out / "w.json").string()};
       }},
      {"rules",
       [](const fs::path&) -> std::vector<std::string> {
         return {"rules", (fs::path(VSIL_SOURCE_DIR) / "src/core/rules/fig6-cube.rules").string(),
                 "--glsl"};
       }},
      // Small on purpose: if bench ever ran here, the test fails in a second instead of hanging.
      // Plain `bench` (every table, minutes) is replayed by the fuzz suite
      // (tests/fuzz/regressions/cli/timeout-bench) under the fuzzer's time limit.
      {"bench",
       [](const fs::path& out) -> std::vector<std::string> {
         return {"bench",
                 "--table=nk3,fft",
                 "--only=neghip",
                 "--sizes=32",
                 "--frames=1",
                 "--warmup=0",
                 "--json=" + (out / "b.json").string(),
                 "--markdown=" + (out / "b.md").string(),
                 "--plot=" + (out / "b.png").string()};
       }},
      // The sweep file is written before the run: only what the sweep writes counts.
      {"sweep",
       [](const fs::path& out) -> std::vector<std::string> {
         std::ofstream(out / "sweep.json")
             << R"({"render": {"input": "gen:spheres:32", "size": "32x32"},)"
             << R"( "axes": {"width": [1, 2]}})";
         return {"sweep", (out / "sweep.json").string(), "--json",    (out / "rows.json").string(),
                 "--csv", (out / "rows.csv").string(),   "--out-dir", (out / "images").string()};
       }},
      // If serve ever ran here, it would listen: the test would hang until ctest's timeout.
      {"serve",
       [](const fs::path&) -> std::vector<std::string> {
         return {"serve", "gen:spheres:32", "--size", "64x64", "--port", "0"};
       }},
  };
  return cases;
}

TEST(ValidateOnly, EveryRegisteredCommandHasACase) {
  CLI::App app{"vsil"};
  cli::setUpApp(app);
  std::set<std::string> covered;
  for (const auto& c : workingCases()) covered.insert(c.command);
  for (const CLI::App* command : app.get_subcommands({})) {
    EXPECT_TRUE(covered.count(command->get_name()))
        << "`vsil " << command->get_name() << "` has no case in workingCases()";
  }
}

class ValidateOnlyCommand : public ::testing::TestWithParam<WorkingCase> {};

TEST_P(ValidateOnlyCommand, AcceptsTheFlagsAndStopsBeforeWork) {
  const fs::path out = test::scratchDir();
  const std::vector<std::string> arguments = GetParam().arguments(out);
  std::set<fs::path> before;
  for (const auto& entry : fs::directory_iterator(out)) before.insert(entry.path());

  const ValidateOnlyRun run = runValidateOnly(arguments);
  EXPECT_EQ(run.error, "") << "vsil " << joined(arguments);
  EXPECT_EQ(run.out, "") << "printed as if it had worked";
  EXPECT_EQ(run.err, "") << "progress or errors on stderr";
  for (const auto& entry : fs::directory_iterator(out)) {
    if (!before.count(entry.path())) ADD_FAILURE() << "wrote " << entry.path();
  }
}

INSTANTIATE_TEST_SUITE_P(Commands, ValidateOnlyCommand, ::testing::ValuesIn(workingCases()),
                         [](const auto& info) {
                           std::string name = info.param.command;
                           for (char& c : name) c = std::isalnum((unsigned char)c) ? c : '_';
                           return name;
                         });

// Bad flags are refused in validate-only mode as in a real run (the fuzz target relies on it).
struct BadFlags {
  const char* name;
  std::vector<std::string> arguments;
  const char* mentions;  // the flag or value the error must name
};

void PrintTo(const BadFlags& c, std::ostream* out) {
  *out << "vsil " << joined(c.arguments);
}

class ValidateOnlyBadFlags : public ::testing::TestWithParam<BadFlags> {};

TEST_P(ValidateOnlyBadFlags, AreRefused) {
  const ValidateOnlyRun run = runValidateOnly(GetParam().arguments);
  EXPECT_NE(run.error.find(GetParam().mentions), std::string::npos)
      << "vsil " << joined(GetParam().arguments) << "\nerror: " << run.error;
  EXPECT_EQ(run.out, "");
}

INSTANTIATE_TEST_SUITE_P(
    Flags, ValidateOnlyBadFlags,
    ::testing::Values(
        BadFlags{"BenchUnknownTable", {"bench", "--table", "nk9"}, "nk9"},
        BadFlags{"BenchUnknownDataset", {"bench", "--only", "bonsia"}, "bonsia"},
        BadFlags{
            "BenchOnlyWithoutDatasets", {"bench", "--table", "fft", "--only", "neghip"}, "--only"},
        BadFlags{"BenchZeroFrames", {"bench", "--frames", "0"}, "--frames"},
        BadFlags{"BenchNegativeWarmup", {"bench", "--warmup", "-1"}, "--warmup"},
        BadFlags{"BenchHugeSize", {"bench", "--sizes", "256,99999"}, "--sizes"},
        BadFlags{"BenchSizeNotANumber", {"bench", "--sizes", "big"}, "--sizes"},
        BadFlags{"BenchMissingDatasets",
                 {"bench", "--datasets", "/nonexistent/vsil"},
                 "/nonexistent/vsil"},
        BadFlags{"BenchMarkdownInMissingFolder",
                 {"bench", "--markdown", "/nonexistent/vsil/x.md"},
                 "--markdown"},
        BadFlags{"BenchPlotNotPng", {"bench", "--plot", "x.jpg"}, "--plot"},
        BadFlags{"RenderBadSize", {"render", "--size", "0x64"}, "--size"},
        BadFlags{"RenderUnknownTechnique", {"render", "--technique", "nope"}, "nope"},
        BadFlags{"AnimateZeroFrames",
                 {"animate", "--frames", "0", "--out-dir", "/nonexistent/vsil"},
                 "--frames"},
        BadFlags{"AnimateUnknownSweep",
                 {"animate", "--frames", "2", "--sweep", "nope=1:2", "--out-dir", "x"},
                 "nope"},
        BadFlags{"AnimateOutDirInMissingFolder",
                 {"animate", "--frames", "2", "--out-dir", "/nonexistent/vsil/frames"},
                 "--out-dir"},
        BadFlags{"AnimateVideoFormat", {"animate", "--frames", "2", "--video", "x.gif"}, "--video"},
        BadFlags{"InfoBadDims", {"info", "v.raw", "--dims", "4x4", "--type", "uint8"}, "--dims"},
        BadFlags{"MeasureWidthBadColour",
                 {"measure-width", "x.png", "--line-color", "nope"},
                 "--line-color"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace vsil
