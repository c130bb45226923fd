// An interrupted run leaves no partial output and no stray temporary, and a previous good
// output at the target path survives untouched (core/atomic_file.h). A render of a few seconds
// (a 128³ generated volume at 1024x1024, three outputs) is started in a child process and sent
// SIGTERM or SIGINT at points spread over its run time: while generating, rendering, and writing.
#include <signal.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "reference/test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

const std::string kPrevious = "a previous good output, not a PNG";

// Runs the big render into `dir`; sends `signal` after `delay` seconds (never, if negative).
test::InterruptedRun renderInto(const fs::path& dir, double delay, int signal) {
  return test::runVsilInterrupted(
      {"render", "gen:blobs:128", "--size", "1024x1024", "--width", "4", "--out",
       (dir / "out.png").string(), "--state-out", (dir / "state.png").string(), "--meta-out",
       (dir / "meta.json").string()},
      delay, signal);
}

void writePrevious(const fs::path& dir) {
  for (const char* name : {"out.png", "state.png", "meta.json"}) {
    std::ofstream(dir / name, std::ios::binary) << kPrevious;
  }
}

TEST(InterruptedRender, LeavesThePreviousOutputsAndNoTemporaries) {
  const fs::path dir = test::scratchDir();
  // Uninterrupted: how long the whole run takes here, and that it replaces the outputs.
  writePrevious(dir);
  const test::InterruptedRun full = renderInto(dir, -1, 0);
  ASSERT_TRUE(WIFEXITED(full.status) && WEXITSTATUS(full.status) == 0) << full.status;
  EXPECT_NE(test::readFileBytes(dir / "out.png"), kPrevious);

  // Signals spread over the run, densest near the end where the files are written.
  int killed = 0;
  for (double fraction : {0.1, 0.5, 0.85, 0.95, 0.99}) {
    for (int signal : {SIGTERM, SIGINT}) {
      writePrevious(dir);
      const test::InterruptedRun run = renderInto(dir, fraction * full.seconds, signal);
      SCOPED_TRACE("signal " + std::to_string(signal) + " after " +
                   std::to_string(fraction * full.seconds) + " s");
      std::vector<std::string> names;
      for (const auto& entry : fs::directory_iterator(dir)) {
        names.push_back(entry.path().filename().string());
      }
      EXPECT_EQ(names.size(), 3u) << "a temporary was left behind";
      if (WIFSIGNALED(run.status)) {
        ++killed;
        EXPECT_EQ(WTERMSIG(run.status), signal);
        // Each output is either the previous one or a complete new one (a signal after some
        // renames but before the last), never a partial file.
        for (const char* name : {"out.png", "state.png"}) {
          const std::string bytes = test::readFileBytes(dir / name);
          if (bytes != kPrevious) {
            EXPECT_EQ(bytes.substr(1, 3), "PNG") << name;
            EXPECT_EQ(bytes.substr(bytes.size() - 8, 4), "IEND") << name << " is incomplete";
          }
        }
      } else {
        EXPECT_TRUE(WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) << run.status;
      }
    }
  }
  // Timing varies with load (the full run was timed once); the early signals always land.
  EXPECT_GE(killed, 4) << "few signals arrived while the render was running";
}

}  // namespace
}  // namespace vsil
