#include "harness/child_run.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>

extern char** environ;

namespace vsil::bench {

std::string vsilBinary() {
  return std::filesystem::read_symlink("/proc/self/exe").string();
}

ChildRun runVsilChild(const std::vector<std::string>& args, const std::filesystem::path& errFile,
                      const std::vector<std::string>& environment) {
  return runChild(vsilBinary(), args, errFile, environment);
}

ChildRun runChild(const std::string& binary, const std::vector<std::string>& args,
                  const std::filesystem::path& errFile,
                  const std::vector<std::string>& environment) {
  std::vector<std::string> all = {binary};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  std::vector<std::string> envText = environment;
  std::vector<char*> envp;
  for (auto& e : envText) envp.push_back(e.data());
  for (char** e = environ; *e; ++e) envp.push_back(*e);
  envp.push_back(nullptr);
  ChildRun run;
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned =
      posix_spawnp(&pid, binary.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  struct rusage usage {};
  if (spawned == 0 && ::wait4(pid, &status, 0, &usage) == pid) {
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.peakResidentBytes = double(usage.ru_maxrss) * 1024.0;  // Linux: KiB
    const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * t.tv_usec; };
    run.cpuSeconds = seconds(usage.ru_utime) + seconds(usage.ru_stime);
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (run.exitCode != 0) {
    run.error = "exit " + std::to_string(run.exitCode);
    if (FILE* in = std::fopen(errFile.c_str(), "r")) {
      char line[512] = "";
      if (std::fgets(line, sizeof line, in)) {
        std::string text(line);
        if (!text.empty() && text.back() == '\n') text.pop_back();
        run.error += ": " + text;
      }
      std::fclose(in);
    }
  }
  return run;
}

std::vector<std::string> glArguments(const gl::ContextOptions& gl) {
  std::vector<std::string> args = {"--gl", gl::backendName(gl.backend)};
  if (gl.eglDevice) args.insert(args.end(), {"--gl-device", std::to_string(*gl.eglDevice)});
  return args;
}

}  // namespace vsil::bench
