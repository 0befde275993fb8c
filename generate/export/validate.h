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

// The same with the map of every polygon checked in tiles of about this side (m), rounded
// to the window's 40 m cells (docs/design.md, Validation by tiles); 0 chooses it by the
// city's size, as validate_output does. The problems found do not depend on it.
Validation validate_output(const std::filesystem::path& out_dir, double tile_side);

// Whether the map of every polygon leaves out the lots and buildings proven to pass its
// checks without it (docs/design.md, Validation by tiles: proofs), as validate_output does,
// or holds them all. The problems found are the same either way: tests compare the two.
enum class MapProofs { First, None };
Validation validate_output(const std::filesystem::path& out_dir, double tile_side, MapProofs proofs);

}  // namespace exacity
