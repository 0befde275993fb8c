// Stage progress on stderr: a bar on a terminal, plain lines otherwise.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace exacity {

class ProgressReport {
 public:
  explicit ProgressReport(bool quiet) : quiet_(quiet), terminal_(isatty(STDERR_FILENO) == 1) {}
  ~ProgressReport() { finish(); }

  void stage(int index, int count, const std::string& name) {
    if (quiet_) return;
    if (!terminal_) {
      std::fprintf(stderr, "exacity: [%d/%d] %s\n", index, count, name.c_str());
      return;
    }
    const int width = 24, filled = width * (index - 1) / count;
    std::string bar(filled, '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r\033[K[%s] %d/%d %s", bar.c_str(), index, count, name.c_str());
    std::fflush(stderr);
    open_line_ = true;
  }

  // Progress within one long stage: a bar with the time left on a terminal; plain lines
  // at each tenth otherwise.
  void fraction(const std::string& name, double done) {
    if (quiet_) return;
    const auto now = std::chrono::steady_clock::now();
    if (name != current_) current_ = name, started_ = now, last_tenth_ = -1;
    if (!terminal_) {
      const int tenth = static_cast<int>(done * 10);
      if (tenth != last_tenth_) std::fprintf(stderr, "exacity: %s %d%%\n", name.c_str(), tenth * 10);
      last_tenth_ = tenth;
      return;
    }
    const double elapsed = std::chrono::duration<double>(now - started_).count();
    const int width = 24, filled = static_cast<int>(width * done);
    std::string bar(filled, '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r\033[K[%s] %s %3d%%", bar.c_str(), name.c_str(), static_cast<int>(done * 100));
    if (done > 0.02 && done < 1) std::fprintf(stderr, ", %.0f s left", elapsed * (1 - done) / done);
    std::fflush(stderr);
    open_line_ = true;
  }

  void finish() {
    if (open_line_) std::fprintf(stderr, "\r\033[K");
    open_line_ = false;
  }

 private:
  bool quiet_, terminal_, open_line_ = false;
  std::string current_;
  std::chrono::steady_clock::time_point started_;
  int last_tenth_ = -1;
};

}  // namespace exacity
