// `exacity validate`: re-reads an output folder and checks its invariants exactly, on the
// coordinates as written.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace exacity {

struct Validation {
  std::vector<std::string> problems;      // one line each; empty when everything holds
  std::map<std::string, int> features;    // per layer
  double widest_sliver = 0;               // m: the widest rounding sliver accepted
  bool ok() const { return problems.empty(); }
};

Validation validate_output(const std::filesystem::path& out_dir);

}  // namespace exacity
