// Each stage's peak of live heap bytes, sampled every 5 ms from tcmalloc's count of the
// bytes the program holds. The resident peak (getrusage, report.json's peak_memory_mib)
// says only when the process first reached a size: tcmalloc keeps freed pages, so a stage
// that frees before it allocates shows no growth there however much it holds. Without
// tcmalloc (the sanitizer builds) there is no count and no peaks.
#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <thread>

// tcmalloc's C interface, weak so that a build without tcmalloc links (and finds it null).
extern "C" int MallocExtension_GetNumericProperty(const char* property, std::size_t* value) __attribute__((weak));

namespace exacity::bench {

class HeapPeaks {
 public:
  HeapPeaks() {
    if (available()) sampler_ = std::thread([this] { sample(); });
  }
  HeapPeaks(const HeapPeaks&) = delete;
  HeapPeaks& operator=(const HeapPeaks&) = delete;
  ~HeapPeaks() { stop(); }

  static bool available() { return MallocExtension_GetNumericProperty != nullptr; }

  // Called as each stage starts; "" after the last one ends.
  void next(const std::string& stage) {
    std::lock_guard<std::mutex> lock(mutex_);
    stage_ = stage;
    if (!stage.empty()) peak_mib[stage] = std::max(peak_mib[stage], held_mib());
  }
  // Stops sampling; the peaks are final.
  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopped_ = true;
    }
    woken_.notify_all();
    if (sampler_.joinable()) sampler_.join();
  }

  std::map<std::string, double> peak_mib;  // by stage; read after stop()

 private:
  static double held_mib() {
    std::size_t bytes = 0;
    MallocExtension_GetNumericProperty("generic.current_allocated_bytes", &bytes);
    return static_cast<double>(bytes) / (1 << 20);
  }
  void sample() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!woken_.wait_for(lock, std::chrono::milliseconds(5), [this] { return stopped_; }))
      if (!stage_.empty()) peak_mib[stage_] = std::max(peak_mib[stage_], held_mib());
  }

  std::mutex mutex_;
  std::condition_variable woken_;
  std::string stage_;
  bool stopped_ = false;
  std::thread sampler_;
};

}  // namespace exacity::bench
