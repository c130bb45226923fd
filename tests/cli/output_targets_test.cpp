// Where an output may go besides a plain file (core/atomic_file.h): through a link (the file it
// names is replaced, the link stays), into /dev/stdout, a FIFO or a device (the complete bytes
// written into it, never a rename over it: run as root, vsil once put a PNG file in the place
// of /dev/full). Each output's bytes equal those of the same render into a plain file, and
// on standard output they come alone (cli/cli_report.h).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "reference/test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

const std::string kRender = "render gen:sphere:16 --size 32x32 --out ";

// The PNG of kRender into a plain file.
std::string plainRender(const fs::path& dir) {
  const fs::path file = dir / "plain.png";
  const auto result = test::runVsil(kRender + file.string());
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, file.string() + "\n");
  return test::readFileBytes(file);
}

// Points $TMPDIR, where vsil puts the temporary of an output that is not a file, at a folder of
// the test's own while it lives (the other back end's run of a test may have one in the usual
// folder at the same time); the hidden files left there are temporaries left behind.
class OwnTemporaryFolder {
 public:
  explicit OwnTemporaryFolder(fs::path folder) : folder_(std::move(folder)) {
    const char* previous = std::getenv("TMPDIR");
    if (previous) previous_ = previous;
    ::setenv("TMPDIR", folder_.c_str(), 1);
  }
  ~OwnTemporaryFolder() {
    previous_ ? ::setenv("TMPDIR", previous_->c_str(), 1) : ::unsetenv("TMPDIR");
  }
  std::vector<std::string> leftBehind() const {
    std::vector<std::string> hidden;
    for (const auto& entry : fs::directory_iterator(folder_)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with(".")) hidden.push_back(name);
    }
    return hidden;
  }

 private:
  fs::path folder_;
  std::optional<std::string> previous_;
};

bool isCharacterDevice(const char* path) {
  struct stat status;
  return ::lstat(path, &status) == 0 && S_ISCHR(status.st_mode);
}

TEST(OutputTargets, ALinkIsFollowedAndStays) {
  const fs::path dir = test::scratchDir();
  const std::string png = plainRender(dir);
  fs::create_directory(dir / "sub");
  fs::create_symlink("target.png", dir / "link.png");           // to nothing yet
  fs::create_symlink("../chained.png", dir / "sub" / "l.png");  // a chain of two
  fs::create_symlink("sub/l.png", dir / "chain.png");
  for (const char* name : {"link.png", "chain.png"}) {
    SCOPED_TRACE(name);
    const auto result = test::runVsil(kRender + (dir / name).string());
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_TRUE(fs::is_symlink(dir / name));
  }
  EXPECT_TRUE(fs::is_symlink(dir / "sub" / "l.png"));
  EXPECT_EQ(test::readFileBytes(dir / "target.png"), png);
  EXPECT_EQ(test::readFileBytes(dir / "chained.png"), png);
}

// A target's name up to the file system's limit (255 bytes) is written: the hidden temporary
// beside it cuts its copy of the name to fit (round 19: names of 244 bytes and more failed).
TEST(OutputTargets, ANameAtTheFileSystemsLimitIsWritten) {
  const fs::path dir = test::scratchDir();
  const std::string png = plainRender(dir);
  const fs::path longest = dir / (std::string(251, 'a') + ".png");
  const auto result = test::runVsil(kRender + longest.string());
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(test::readFileBytes(longest), png);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
  EXPECT_EQ(files, 2u) << "no temporary left beside the two images";
}

// A loop of links names no file: refused as open() refuses it, and nothing replaces the links.
TEST(OutputTargets, ALoopOfLinksIsRefused) {
  const fs::path dir = test::scratchDir();
  fs::create_symlink("b.png", dir / "a.png");
  fs::create_symlink("a.png", dir / "b.png");
  const auto result = test::runVsil(kRender + (dir / "a.png").string());
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err, "vsil: " + (dir / "a.png").string() +
                            ": cannot write: Too many levels of symbolic links\n");
  EXPECT_EQ(result.out, "");
  EXPECT_TRUE(fs::is_symlink(dir / "a.png") && fs::is_symlink(dir / "b.png"));
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 2) << "a temporary was left behind";
}

TEST(OutputTargets, StandardOutputGetsTheImageAndNothingElse) {
  const std::string png = plainRender(test::scratchDir());
  const auto result = test::runVsil(kRender + "/dev/stdout");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, png) << "the image, without the path line after it";
  EXPECT_EQ(result.err, "");
}

// An output into standard output comes there alone: the command's report (the path line, the
// text summary, a table) goes to stderr instead, so `--json /dev/stdout | jq .` reads JSON.
TEST(OutputTargets, AReportMakesWayForAnOutputOnStandardOutput) {
  const fs::path dir = test::scratchDir();
  const std::string out = (dir / "o.png").string(), depth = (dir / "d.png").string();
  const auto render = test::runVsil("render gen:sphere:32 --size 64x64 --width 3 --out " + out +
                                    " --depth-out " + depth + " --meta-out /dev/stdout");
  ASSERT_EQ(render.exitCode, 0) << render.err;
  EXPECT_TRUE(nlohmann::json::parse(render.out).contains("camera")) << render.out;
  EXPECT_EQ(render.err, out + "\n");

  const std::string measure = "measure-width " + out + " --depth " + depth;
  const auto toFile = test::runVsil(measure + " --json " + (dir / "w.json").string());
  ASSERT_EQ(toFile.exitCode, 0) << toFile.err;
  ASSERT_TRUE(toFile.out.starts_with("samples ")) << toFile.out;
  const auto toStdout = test::runVsil(measure + " --json /dev/stdout");
  ASSERT_EQ(toStdout.exitCode, 0) << toStdout.err;
  EXPECT_EQ(toStdout.out, test::readFileBytes(dir / "w.json"));
  EXPECT_EQ(toStdout.err, toFile.out) << "the text report, on stderr";
}

// A command that fails prints nothing on stdout, not even the part of its report it had: the
// width summary came out before a --depth image of another size was refused.
TEST(OutputTargets, AFailedMeasurementPrintsNoReport) {
  const fs::path dir = test::scratchDir();
  const std::string out = (dir / "o.png").string(), depth = (dir / "d.png").string();
  ASSERT_EQ(test::runVsil("render gen:sphere:16 --size 32x32 --out " + out).exitCode, 0);
  ASSERT_EQ(test::runVsil("render gen:sphere:16 --size 40x40 --out " + (dir / "o40.png").string() +
                          " --depth-out " + depth)
                .exitCode,
            0);
  const auto result = test::runVsil("measure-width " + out + " --depth " + depth);
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err, "vsil: " + depth + ": is not the size of " + out + "\n");
  EXPECT_EQ(result.out, "");
}

// A pipe whose reader has gone ends vsil by SIGPIPE, as it ends any writer, and leaves no
// temporary behind.
TEST(OutputTargets, APipeWithoutAReaderLeavesNoTemporary) {
  const fs::path dir = test::scratchDir();
  const OwnTemporaryFolder temporaries(dir);
  // `true` leaves without reading, long before the render is ready to write.
  test::runVsil(kRender + "/dev/stdout 2>" + (dir / "vsil.err").string() + " | true");
  EXPECT_EQ(test::readFileBytes(dir / "vsil.err"), "");
  EXPECT_EQ(temporaries.leftBehind(), std::vector<std::string>{});
}

TEST(OutputTargets, AFifoGetsTheImageAndStaysAFifo) {
  const fs::path dir = test::scratchDir();
  const std::string png = plainRender(dir);
  ASSERT_LT(png.size(), 4096u) << "it must fit the FIFO's buffer: nobody reads while vsil writes";
  const fs::path fifo = dir / "pipe.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Open at both ends here, so that neither this open nor vsil's waits for the other end.
  const int end = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(end, 0);
  const auto result = test::runVsil(kRender + fifo.string());
  EXPECT_EQ(result.exitCode, 0) << result.err;
  std::string received(png.size() + 1, '\0');
  const ssize_t got = ::read(end, received.data(), received.size());
  received.resize(got > 0 ? std::size_t(got) : 0);
  ::close(end);
  EXPECT_EQ(received, png);
  EXPECT_EQ(fs::symlink_status(fifo).type(), fs::file_type::fifo);
}

TEST(OutputTargets, DevicesAreWrittenIntoNeverReplaced) {
  ASSERT_TRUE(isCharacterDevice("/dev/null") && isCharacterDevice("/dev/full"));
  const OwnTemporaryFolder temporaries(test::scratchDir());
  const auto toNull = test::runVsil(kRender + "/dev/null");
  EXPECT_EQ(toNull.exitCode, 0) << toNull.err;
  const auto toFull = test::runVsil(kRender + "/dev/full");
  EXPECT_EQ(toFull.exitCode, 2);
  EXPECT_EQ(toFull.err, "vsil: /dev/full: cannot write: No space left on device\n");
  EXPECT_EQ(toFull.out, "");
  EXPECT_TRUE(isCharacterDevice("/dev/null"));
  EXPECT_TRUE(isCharacterDevice("/dev/full"));
  EXPECT_EQ(temporaries.leftBehind(), std::vector<std::string>{});
}

// A report that cannot reach standard output (a full disk behind `> info.json`, a closed
// stdout) is a failure: exit 2 and one line, not exit 0 with the report lost.
TEST(OutputTargets, AReportThatCannotBeWrittenFails) {
  const fs::path err = test::scratchDir() / "vsil.err";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {">/dev/full", "No space left on device"}, {">&-", "Bad file descriptor"}};
  for (const auto& [redirect, reason] : cases) {
    // The shell's own redirections follow "exit": they do not reach vsil.
    const auto result =
        test::runVsil("info gen:sphere:8 --json " + redirect + " 2>" + err.string() + "; exit $?");
    EXPECT_EQ(result.exitCode, 2) << redirect;
    EXPECT_EQ(test::readFileBytes(err), "vsil: standard output: cannot write: " + reason + "\n")
        << redirect;
  }
}

}  // namespace
}  // namespace vsil
