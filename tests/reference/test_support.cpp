#include "test_support.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

extern char** environ;

namespace vsil::test {

std::filesystem::path datasetPath(const std::string& name) {
  return std::filesystem::path(VSIL_SHARED_DIR) / "datasets" / name;
}

std::optional<std::string> datasetsMissing() {
  const auto folder = std::filesystem::path(VSIL_SHARED_DIR) / "datasets";
  if (std::filesystem::is_directory(folder)) return std::nullopt;
  return "the classic datasets are not at " + folder.string() +
         " (clone shared/ beside the checkout, or configure with -DVSIL_SHARED_DIR=...)";
}

bool datasetsRequired() {
  const char* required = std::getenv("VSIL_REQUIRE_DATASETS");
  return required && std::string(required) == "1";
}

std::filesystem::path vsilBinary() {
  return VSIL_BINARY;
}

// The root of the scratch folders: one per build, named by its vsil binary's path, so that two
// builds testing on one machine at once (a clean-clone CI beside a developer's build) do not
// empty each other's folders when they run the same test.
std::filesystem::path scratchRoot() {
  char key[32];
  std::snprintf(key, sizeof key, "vsil-tests-%016zx", std::hash<std::string>{}(VSIL_BINARY));
  return std::filesystem::temp_directory_path() / key;
}

std::filesystem::path scratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "vsil";
  // ctest runs a GL suite once per back end, maybe at the same time: one folder each.
  if (const char* backend = std::getenv("VSIL_GL"); backend && *backend)
    name += "@" + std::string(backend);
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  const auto dir = scratchRoot() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string readFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

CommandResult runVsil(const std::string& arguments) {
  // Not scratchDir(): that would empty the calling test's folder, which holds its inputs.
  const auto dir = scratchRoot() / ("run-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto outPath = dir / "stdout";
  const auto errPath = dir / "stderr";
  std::string command = vsilBinary().string() + " " + arguments + " >" + outPath.string() + " 2>" +
                        errPath.string() + " </dev/null";
  // The shell through posix_spawn and wait4 rather than system(): wait4 gives the usage of the
  // shell and everything it waited for (vsil, and vsil's own children), so the peak is this
  // run's alone.
  std::string shell = "/bin/sh", dashC = "-c";
  char* argv[] = {shell.data(), dashC.data(), command.data(), nullptr};
  pid_t pid = 0;
  CommandResult result;
  if (posix_spawn(&pid, shell.c_str(), nullptr, nullptr, argv, environ) != 0) {
    ADD_FAILURE() << "cannot start /bin/sh for: " << command;
    return result;
  }
  int status = 0;
  struct rusage usage {};
  while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.peakRssMib = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB
  result.out = readFileBytes(outPath);
  result.err = readFileBytes(errPath);
  return result;
}

InterruptedRun runVsilInterrupted(const std::vector<std::string>& arguments, double delay,
                                  int signal, const std::function<bool()>& ready) {
  const std::string binary = vsilBinary().string();
  std::vector<std::string> args = {binary};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  InterruptedRun run;
  bool ended = false;
  if (delay >= 0 && ready) {
    while (!ready()) {
      if (::waitpid(pid, &run.status, WNOHANG) == pid) {
        ended = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  if (delay >= 0 && !ended) {
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    ::kill(pid, signal);
  }
  if (!ended) {
    EXPECT_EQ(::waitpid(pid, &run.status, 0), pid);
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace vsil::test
