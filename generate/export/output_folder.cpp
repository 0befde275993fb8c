#include "generate/export/output_folder.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <mutex>
#include <set>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

#include <cpl_string.h>

#include "generate/errors.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

// Staging folders of runs under way in this process, for the interrupt watcher.
std::mutex staging_mutex;
std::set<fs::path> staging_folders;
// Held while the stop handler runs, so that replacing it (on_interrupt) waits until a handler
// already called returns: the handler uses its caller's locals.
std::mutex interrupt_mutex;
std::function<void(int)> interrupt_stop;  // under interrupt_mutex

void remove_tree(const fs::path& p) {
  std::error_code ec;
  for (int attempt = 0; attempt < 3 && fs::exists(p, ec); ++attempt) fs::remove_all(p, ec);
}

// A staging (".NAME.partial-PID") or replaced (".NAME.old-PID") folder that a run which is
// no longer alive left beside `target`: it crashed or was killed.
bool left_by_dead_run(const fs::path& entry, const fs::path& target) {
  const std::string name = entry.filename().string(), base = "." + target.filename().string();
  for (const char* suffix : {".partial-", ".old-"}) {
    const std::string prefix = base + suffix;
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) return false;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    return pid != getpid() && kill(pid, 0) != 0 && errno == ESRCH;
  }
  return false;
}

}  // namespace

void clean_up_on_interrupt() {
  sigset_t signals;
  sigemptyset(&signals);
  for (int signal : {SIGINT, SIGTERM}) {
    struct sigaction now {};
    sigaction(signal, nullptr, &now);
    if (now.sa_handler != SIG_IGN) sigaddset(&signals, signal);  // a shell's background job ignores SIGINT: so do we
  }
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // threads started later inherit the mask
  std::thread([signals] {
    int signal = 0;
    sigwait(&signals, &signal);
    bool stopped = false;
    {
      std::lock_guard lock(interrupt_mutex);
      if (std::function<void(int)> stop = std::exchange(interrupt_stop, nullptr)) stop(signal), stopped = true;
    }
    if (stopped) sigwait(&signals, &signal);
    std::lock_guard lock(staging_mutex);
    for (const fs::path& p : staging_folders) remove_tree(p);
    const char message[] = "exacity: interrupted; the output folder is as it was before this run\n";
    [[maybe_unused]] auto written = write(STDERR_FILENO, message, sizeof message - 1);
    std::_Exit(128 + signal);
  }).detach();
}

void on_interrupt(std::function<void(int)> stop) {
  std::lock_guard lock(interrupt_mutex);
  interrupt_stop = std::move(stop);
}

OutputFolder::OutputFolder(fs::path target) : target_(fs::absolute(std::move(target)).lexically_normal()) {
  if (target_.filename().empty()) target_ = target_.parent_path();
  const std::string t = target_.string();
  if (!CPLIsUTF8(t.c_str(), -1))  // the outputs name files in JSON, which holds only UTF-8
    throw UserError(t + ": the output path is not UTF-8 text, which the outputs naming their files cannot hold; "
                        "choose a name in UTF-8 with -o");
  if (fs::exists(target_) && !fs::is_directory(target_))
    throw UserError(t + ": the output path exists and is a file; choose a folder path with -o");
  if (fs::is_directory(target_) && !fs::is_empty(target_) && !fs::exists(target_ / "report.json"))
    throw UserError(t + ": the output folder holds files exacity did not write; choose a new or empty folder with -o");
  std::error_code ec;
  fs::create_directories(target_.parent_path(), ec);
  for (const auto& entry : fs::directory_iterator(target_.parent_path(), ec))
    if (left_by_dead_run(entry.path(), target_)) remove_tree(entry.path());
  staging_ = target_.parent_path() / ("." + target_.filename().string() + ".partial-" + std::to_string(getpid()));
  remove_tree(staging_);
  if (!fs::create_directory(staging_, ec))
    throw UserError(t + ": cannot create the output folder (" + ec.message() + "); check the path and permissions");
  std::lock_guard lock(staging_mutex);
  staging_folders.insert(staging_);
}

OutputFolder::~OutputFolder() {
  std::lock_guard lock(staging_mutex);
  staging_folders.erase(staging_);
  if (!committed_) remove_tree(staging_);
}

void OutputFolder::commit() {
  std::lock_guard lock(staging_mutex);  // an interrupt waits until the folders are in place
  fs::path old = target_.parent_path() / ("." + target_.filename().string() + ".old-" + std::to_string(getpid()));
  if (fs::exists(target_)) fs::rename(target_, old);
  fs::rename(staging_, target_);
  committed_ = true;
  staging_folders.erase(staging_);
  remove_tree(old);
}

}  // namespace exacity
