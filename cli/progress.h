// Stage progress on stderr: a bar on a terminal, plain lines otherwise.
#pragma once

#include <unistd.h>

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

  void finish() {
    if (open_line_) std::fprintf(stderr, "\r\033[K");
    open_line_ = false;
  }

 private:
  bool quiet_, terminal_, open_line_ = false;
};

}  // namespace exacity
