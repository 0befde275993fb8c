// The two kinds of failure the exacity command reports (docs/design.md, Conventions).
#pragma once

#include <stdexcept>
#include <string>

namespace exacity {

// Something wrong with what the user gave. The message is one line: file, feature, what
// is wrong, what to do. Exit code 2.
struct UserError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A failed internal check. Exit code 3.
struct InternalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace exacity
