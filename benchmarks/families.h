// The robustness benchmark's families of near-degenerate sketches (docs/benchmarks.md). Each case is
// a small city written as a GeoJSON sketch, a function of (family, case, seed) only.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace exacity::bench {

struct Family {
  std::string name;
  std::string about;  // one line, for the report
};

// The eight families, in report order.
const std::vector<Family>& families();

// Case `index` of the family: a sketch, GeoJSON text. Throws std::invalid_argument for a
// family that does not exist.
std::string family_sketch(const std::string& family, int index, std::uint64_t seed);

}  // namespace exacity::bench
