// An interrupted run leaves no partial output and no stray temporary, and a previous good
// output at the target path survives untouched (core/atomic_file.h). A render of a few seconds
// (a 128³ generated volume at 1024x1024, three outputs) is started in a child process and sent
// SIGTERM or SIGINT at points spread over its run time: while generating, rendering, and writing.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "reference/test_support.h"

extern char** environ;

namespace vsil {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kPrevious = "a previous good output, not a PNG";

struct RenderRun {
  int status = 0;
  double seconds = 0;
};

// Runs the big render into `dir`; sends `signal` after `delay` seconds (never, if negative).
RenderRun renderInto(const fs::path& dir, double delay, int signal) {
  const std::string binary = test::vsilBinary().string();
  const std::string out = (dir / "out.png").string(), state = (dir / "state.png").string(),
                    meta = (dir / "meta.json").string();
  std::vector<std::string> args = {
      binary,  "render", "gen:blobs:128", "--size", "1024x1024",  "--width", "4",
      "--out", out,      "--state-out",   state,    "--meta-out", meta};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const auto start = Clock::now();
  EXPECT_EQ(posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  if (delay >= 0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    ::kill(pid, signal);
  }
  RenderRun run;
  EXPECT_EQ(::waitpid(pid, &run.status, 0), pid);
  run.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return run;
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
  const RenderRun full = renderInto(dir, -1, 0);
  ASSERT_TRUE(WIFEXITED(full.status) && WEXITSTATUS(full.status) == 0) << full.status;
  EXPECT_NE(test::readFileBytes(dir / "out.png"), kPrevious);

  // Signals spread over the run, densest near the end where the files are written.
  int killed = 0;
  for (double fraction : {0.1, 0.5, 0.85, 0.95, 0.99}) {
    for (int signal : {SIGTERM, SIGINT}) {
      writePrevious(dir);
      const RenderRun run = renderInto(dir, fraction * full.seconds, signal);
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
