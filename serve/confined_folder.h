// A folder the server may read and write in and nowhere else (docs/design.md, Serving): the
// work folder, and the page's own static files.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace exacity::serve {

class ConfinedFolder {
 public:
  // Creates `root` when `create` is set; the root's own symbolic links are resolved once here.
  explicit ConfinedFolder(const std::filesystem::path& root, bool create = false);

  const std::filesystem::path& root() const { return root_; }

  // The file `relative` names inside the root, with '/' between its parts. Throws PathRefused
  // when name_problem finds one, or for a part that is a symbolic link: nothing reached
  // through a name may be outside the root, whatever the name's encoding was (the caller
  // decodes once; what is checked is what is opened).
  std::filesystem::path resolve(std::string_view relative) const;

  // Whether `file` (absolute, or relative to the root) lies inside the root by the same rules,
  // for paths a sketch names; on false, `why` says what is wrong.
  bool holds(const std::filesystem::path& file, std::string& why) const;

 private:
  std::filesystem::path root_;
};

// Why `relative` cannot name a file inside a folder, by its spelling alone; empty when it
// can. Refused: an empty name or part ("//", a trailing "/"), an absolute name, a ".." or
// hidden (".name", so the staging folders stay private) part, a backslash, a control
// character (NUL among them) and a percent-encoded character ("%2e"): a name is given as
// it is, never encoded.
std::string name_problem(std::string_view relative);
// `name` with its control characters as \xNN, for a message.
std::string printable(const std::string& name);

struct PathRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace exacity::serve
