// Each stage's CPU seconds (all threads), from its start to the next one's: on a machine
// shared with other work, the wall clock measures the others too.
#pragma once

#include <ctime>
#include <string>

#include <sys/resource.h>

#include <nlohmann/json.hpp>

namespace exacity::bench {

inline double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The process's system CPU seconds and page faults so far: on a virtual machine a page
// fault can cost microseconds of system time, so the faults explain the system seconds.
struct KernelUse {
  double system_s = 0;
  long faults = 0;
};
inline KernelUse kernel_use() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return {static_cast<double>(r.ru_stime.tv_sec) + 1e-6 * static_cast<double>(r.ru_stime.tv_usec),
          r.ru_minflt + r.ru_majflt};
}

class StageCpu {
 public:
  // Called as each stage starts (a StageClock's progress); "" after the last one ends.
  void next(const std::string& stage) {
    const double now = cpu_seconds();
    const KernelUse k = kernel_use();
    if (!stage_.empty()) {
      seconds[stage_] = now - start_;
      system_s[stage_] = k.system_s - kernel_start_.system_s;
      faults[stage_] = k.faults - kernel_start_.faults;
    }
    stage_ = stage, start_ = now, kernel_start_ = k;
  }
  // CPU seconds (user and system), system seconds and page faults of each stage.
  nlohmann::ordered_json seconds = nlohmann::ordered_json::object(), system_s = nlohmann::ordered_json::object(),
                         faults = nlohmann::ordered_json::object();

 private:
  std::string stage_;
  double start_ = cpu_seconds();
  KernelUse kernel_start_ = kernel_use();
};

}  // namespace exacity::bench
