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

// Whether the maps leave out what is proven to pass their checks without them (docs/design.md,
// Validation by tiles: proofs): the polygons' map the lots, buildings and blocks, the zoning
// map the zoning polygons away from the drawn edges (their outline in their place), and the
// roads' map everything when the centre lines meet only at vertices; as validate_output
// does, or hold them all. The problems found, and the widest sliver, are the same either
// way: tests compare the two.
enum class MapProofs { First, None };
Validation validate_output(const std::filesystem::path& out_dir, double tile_side, MapProofs proofs);

}  // namespace exacity
