// `exacity bench scale`: the sketch tiled to several sizes, each generated in a child process
// (as a user runs it), timed and measured per stage from its report.json, with the growth
// against the linear extrapolation from the smallest size (docs/benchmarks.md, Scale).
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace exacity::bench {

struct ScaleOptions {
  std::filesystem::path sketch = "benchmarks/city_10km.geojson";
  std::vector<int> sizes{1, 4, 9};  // areas in copies of the sketch; each a square number (9: a million buildings)
  int threads = 0;                   // generate's --threads (0: one per core)
  int runs = 1;                      // runs per size; medians printed
  std::filesystem::path out = "scale";
  std::filesystem::path program;     // the exacity to run
};

// The sketch's features copied k x k times (k * k = size), each copy moved by whole widths
// and heights of the sketch's bounding box plus a street's gap, names suffixed with the copy.
std::string tiled_sketch(const std::filesystem::path& sketch, int size);

// Runs every size, writes scale.json, scale.md and scale.svg into options.out, and prints the
// table to `log`. Throws std::runtime_error when a run fails.
void run_scale(const ScaleOptions& options, std::ostream& log);

}  // namespace exacity::bench
