// Each stage's CPU seconds (all threads), from its start to the next one's: on a machine
// shared with other work, the wall clock measures the others too.
#pragma once

#include <ctime>
#include <string>

#include <nlohmann/json.hpp>

namespace exacity::bench {

inline double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

class StageCpu {
 public:
  // Called as each stage starts (a StageClock's progress); "" after the last one ends.
  void next(const std::string& stage) {
    const double now = cpu_seconds();
    if (!stage_.empty()) seconds[stage_] = now - start_;
    stage_ = stage, start_ = now;
  }
  nlohmann::ordered_json seconds = nlohmann::ordered_json::object();

 private:
  std::string stage_;
  double start_ = cpu_seconds();
};

}  // namespace exacity::bench
