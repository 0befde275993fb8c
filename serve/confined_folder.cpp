#include "serve/confined_folder.h"

#include <cctype>
#include <cstdio>
#include <system_error>

namespace exacity::serve {
namespace fs = std::filesystem;

std::string printable(const std::string& name) {
  std::string out;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7f) {
      out += ch;
      continue;
    }
    char escaped[8];
    std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
    out += escaped;
  }
  return out;
}

ConfinedFolder::ConfinedFolder(const fs::path& root, bool create) {
  std::error_code ec;
  if (create) fs::create_directories(root, ec);
  root_ = fs::canonical(root, ec);
  if (ec || !fs::is_directory(root_)) throw PathRefused(root.string() + ": not a folder that can be opened");
}

std::string name_problem(std::string_view relative) {
  const std::string name(relative);
  if (name.empty()) return "an empty path";
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c == 0x7f) return "a control character in the name";
    if (c == '\\') return "a backslash in the name";
    if (c == '%' && i + 2 < name.size() && std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(name[i + 2])))
      return "a percent-encoded character (\"" + name.substr(i, 3) + "\"); give the name as it is";
  }
  if (name.front() == '/') return "an absolute path; give one inside the folder";
  std::size_t start = 0;
  while (start <= name.size()) {
    std::size_t end = name.find('/', start);
    if (end == std::string::npos) end = name.size();
    const std::string part = name.substr(start, end - start);
    if (part.empty()) return "an empty part (\"//\" or a trailing \"/\")";
    if (part == "..") return "\"..\" would leave the folder";
    if (part.front() == '.') return "\"" + part + "\" is hidden";
    start = end + 1;
  }
  return "";
}

fs::path ConfinedFolder::resolve(std::string_view relative) const {
  const std::string name(relative);
  if (const std::string why = name_problem(name); !why.empty())
    throw PathRefused(name.empty() ? why : printable(name) + ": " + why);
  fs::path at = root_;
  std::size_t start = 0;
  while (start <= name.size()) {
    std::size_t end = name.find('/', start);
    if (end == std::string::npos) end = name.size();
    const std::string part = name.substr(start, end - start);
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
