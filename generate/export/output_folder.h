// Outputs are written into a staging folder beside the target and renamed into place at
// the end, so a failed run leaves no half-written output and an earlier one stays whole.
#pragma once

#include <filesystem>
#include <functional>

namespace exacity {

// Call first in main, before any other thread starts: SIGINT and SIGTERM then remove the
// staging folders of the runs under way and end the process with 128 + the signal.
void clean_up_on_interrupt();

// From then on the first SIGINT or SIGTERM calls `stop` (on the watcher's thread) instead,
// for a program that stops cleanly by itself (exacity serve); a second one still removes the
// staging folders and ends the process at once. Replacing the handler waits until one
// already called has returned.
void on_interrupt(std::function<void(int)> stop);

class OutputFolder {
 public:
  // Throws UserError when `target` is a file, or a non-empty folder that no earlier
  // exacity run wrote (it holds no report.json): nothing of the user's is overwritten.
  // Removes the staging folders that crashed or killed runs left beside `target`.
  explicit OutputFolder(std::filesystem::path target);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& staging() const { return staging_; }
  void commit();

 private:
  std::filesystem::path target_, staging_;
  bool committed_ = false;
};

}  // namespace exacity
