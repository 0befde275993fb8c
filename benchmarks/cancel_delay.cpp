// How long a generation takes to stop once cancelled, at times spread over the whole run:
// every stage of build_city and write_city, as the server's job runs them (its tiles
// aside). Measures; asserts nothing (generate/cancel_test.cpp tests that every stage stops).
//
//   build/release/benchmarks/exacity_cancel_delay SKETCH [--scale K] [--tries N]
//
// One uncancelled run gives the length T; then try i sets the flag at T * (i + 0.5) / N and
// prints how long after that the run ended, in wall and in the process's CPU seconds (on a
// loaded machine the wall time is the CPU time stretched by the others' share), in which stage.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <unistd.h>

#include "benchmarks/scaled_sketch.h"
#include "generate/cancel.h"
#include "generate/pipeline.h"
#include "generate/sketch/sketch.h"

using namespace exacity;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

// Builds and writes the city into `dir` under `flag`; the stage it was in when it ended.
std::string generate(const Sketch& sketch, const fs::path& dir, const std::atomic<bool>& flag) {
  std::mutex m;
  std::string stage;
  StageClock clock(
      [&](int, int, const std::string& name) {
        std::lock_guard lock(m);
        stage = name;
      },
      kCityStages + kWriteStages);
  const CancelScope scope(flag);
  try {
    fs::remove_all(dir);
    fs::create_directories(dir);
    const City city = build_city(sketch, clock);
    write_city(sketch, city, dir, clock);
    return "(finished)";
  } catch (const Cancelled&) {
    std::lock_guard lock(m);
    return stage;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SKETCH [--scale K] [--tries N]\n", argv[0]);
    return 2;
  }
  double k = 1;
  int tries = 20;
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--scale") && i + 1 < argc) k = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--tries") && i + 1 < argc) tries = std::stoi(argv[++i]);
  }
  const Sketch sketch = parse_sketch(bench::scaled_sketch(argv[1], k).dump(), argv[1]);
  const fs::path dir = fs::temp_directory_path() / ("exacity-cancel-delay." + std::to_string(::getpid()));

  std::atomic<bool> never{false};
  const auto start = Clock::now();
  generate(sketch, dir, never);
  const double whole = seconds(Clock::now() - start);
  std::printf("whole run %.2f s\n| cancelled at s | stopped after s | CPU s | stage |\n|---|---|---|---|\n", whole);
  double worst = 0, worst_cpu = 0;
  for (int i = 0; i < tries; ++i) {
    std::atomic<bool> flag{false};
    std::string stage;
    Clock::time_point set;
    std::thread run([&] { stage = generate(sketch, dir, flag); });
    const double at = whole * (i + 0.5) / tries;
    std::this_thread::sleep_for(std::chrono::duration<double>(at));
    set = Clock::now();
    const double cpu = cpu_seconds();
    flag = true;
    run.join();
    const double delay = seconds(Clock::now() - set), delay_cpu = cpu_seconds() - cpu;
    worst = std::max(worst, delay);
    worst_cpu = std::max(worst_cpu, delay_cpu);
    std::printf("| %.2f | %.3f | %.3f | %s |\n", at, delay, delay_cpu, stage.c_str());
    std::fflush(stdout);
  }
  std::printf("worst %.3f s, %.3f CPU s\n", worst, worst_cpu);
  fs::remove_all(dir);
  return 0;
}
