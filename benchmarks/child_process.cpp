#include "benchmarks/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace exacity::bench {

Run run_child(const std::vector<std::string>& args, const std::filesystem::path& log, double limit) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  // A loaded machine can refuse a process for a moment (EAGAIN, ENOMEM): try again before
  // giving up on the whole run.
  int failed = 0;
  for (int attempt = 0; attempt < 6; ++attempt) {
    failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    if (failed != EAGAIN && failed != ENOMEM) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(250 << attempt));
  }
  posix_spawn_file_actions_destroy(&actions);
  if (failed) throw std::runtime_error("cannot run " + args[0] + ": " + std::strerror(failed));
  Run run;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, WNOHANG, &usage) == 0) {
    if (elapsed() > limit) {
      kill(pid, SIGKILL);
      wait4(pid, &status, 0, &usage);
      run.status = Run::TimedOut;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  run.seconds = elapsed();
  run.cpu_seconds = usage.ru_utime.tv_sec + usage.ru_utime.tv_usec * 1e-6 + usage.ru_stime.tv_sec +
                    usage.ru_stime.tv_usec * 1e-6;
  run.peak_mib = usage.ru_maxrss / 1024.0;
  if (run.status == Run::TimedOut) return run;
  if (WIFSIGNALED(status)) run.status = Run::Signalled, run.code = WTERMSIG(status);
  else run.code = WEXITSTATUS(status);
  return run;
}

}  // namespace exacity::bench
