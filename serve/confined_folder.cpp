#include "serve/confined_folder.h"

#include <system_error>

namespace exacity::serve {
namespace fs = std::filesystem;

ConfinedFolder::ConfinedFolder(const fs::path& root, bool create) {
  std::error_code ec;
  if (create) fs::create_directories(root, ec);
  root_ = fs::canonical(root, ec);
  if (ec || !fs::is_directory(root_)) throw PathRefused(root.string() + ": not a folder that can be opened");
}

fs::path ConfinedFolder::resolve(std::string_view relative) const {
  const std::string name(relative);
  if (name.empty()) throw PathRefused("an empty path");
  if (name.find('\0') != std::string::npos || name.find('\\') != std::string::npos)
    throw PathRefused(name + ": a path with a NUL or a backslash");
  if (name.front() == '/') throw PathRefused(name + ": an absolute path; give one inside the folder");
  fs::path at = root_;
  std::size_t start = 0;
  while (start <= name.size()) {
    std::size_t end = name.find('/', start);
    if (end == std::string::npos) end = name.size();
    const std::string part = name.substr(start, end - start);
    if (part.empty()) throw PathRefused(name + ": an empty part (\"//\" or a trailing \"/\")");
    if (part == "..") throw PathRefused(name + ": \"..\" would leave the folder");
    if (part.front() == '.') throw PathRefused(name + ": \"" + part + "\" is hidden");
    at /= part;
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(at, ec))) throw PathRefused(name + ": \"" + part + "\" is a symbolic link");
    start = end + 1;
  }
  return at;
}

bool ConfinedFolder::holds(const fs::path& file, std::string& why) const {
  const std::string name = file.generic_string();
  if (file.is_absolute()) {
    // An absolute path is accepted only when it spells a path inside the root.
    const fs::path relative = file.lexically_relative(root_);
    if (relative.empty() || *relative.begin() == "..") {
      why = name + ": outside the work folder; put the file in it and name it relative to the sketch";
      return false;
    }
    return holds(relative, why);
  }
  try {
    resolve(name);
    return true;
  } catch (const PathRefused& e) {
    why = std::string(e.what()) + "; name a file inside the work folder, relative to the sketch";
    return false;
  }
}

}  // namespace exacity::serve
