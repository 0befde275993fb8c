#include "generate/output_folder.h"

#include <unistd.h>

#include <string>
#include <system_error>

#include "generate/errors.h"

namespace exacity {
namespace fs = std::filesystem;

OutputFolder::OutputFolder(fs::path target) : target_(fs::absolute(std::move(target)).lexically_normal()) {
  if (target_.filename().empty()) target_ = target_.parent_path();
  const std::string t = target_.string();
  if (fs::exists(target_) && !fs::is_directory(target_))
    throw UserError(t + ": the output path exists and is a file; choose a folder path with -o");
  if (fs::is_directory(target_) && !fs::is_empty(target_) && !fs::exists(target_ / "report.json"))
    throw UserError(t + ": the output folder holds files exacity did not write; choose a new or empty folder with -o");
  std::error_code ec;
  fs::create_directories(target_.parent_path(), ec);
  staging_ = target_.parent_path() / ("." + target_.filename().string() + ".partial-" + std::to_string(getpid()));
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec))
    throw UserError(t + ": cannot create the output folder (" + ec.message() + "); check the path and permissions");
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

void OutputFolder::commit() {
  fs::path old = target_.parent_path() / ("." + target_.filename().string() + ".old-" + std::to_string(getpid()));
  if (fs::exists(target_)) fs::rename(target_, old);
  fs::rename(staging_, target_);
  committed_ = true;
  std::error_code ec;
  fs::remove_all(old, ec);
}

}  // namespace exacity
