// What every fuzz target shares: a user's mistake is a UserError and fine; anything else
// escaping (an internal error, a CGAL failure, a JSON library exception) is a finding.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "generate/errors.h"

namespace exacity::fuzz {

template <typename F>
void expect_user_errors_only(F&& f) {
  try {
    f();
  } catch (const UserError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "not a user error: %s\n", e.what());
    std::abort();
  }
}

// A folder of this process's own, emptied for each input.
inline std::filesystem::path scratch() {
  static const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("exacity-fuzz-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

}  // namespace exacity::fuzz
