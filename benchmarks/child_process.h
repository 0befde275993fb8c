// A program run as a child process, as the benchmarks run exacity's builds: its output into
// a log, killed past a time limit, and what it cost (wait4's resource usage).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace exacity::bench {

struct Run {
  enum Status { Exited, Signalled, TimedOut } status = Exited;
  int code = 0;  // exit code, or signal
  double seconds = 0;            // wall
  double cpu_seconds = 0;        // user and system
  double peak_mib = 0;           // the child's largest resident set
};

// Runs args[0] (a path) with its output into `log`, killed after `limit` seconds.
Run run_child(const std::vector<std::string>& args, const std::filesystem::path& log, double limit);

}  // namespace exacity::bench
