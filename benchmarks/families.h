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
  // What a case's degeneracy level measures; the higher, the nearer the case is to
  // degenerate (the control, `random`, is all level 0).
  std::string level;
};

// One case: its sketch (GeoJSON text) and its degeneracy level.
struct FamilyCase {
  std::string sketch;
  double level = 0;
};

// The families, in report order (the control last).
const std::vector<Family>& families();

// Case `index` of the family. Throws std::invalid_argument for a family that does not exist.
FamilyCase family_case(const std::string& family, int index, std::uint64_t seed);

// The same case's sketch only.
std::string family_sketch(const std::string& family, int index, std::uint64_t seed);

}  // namespace exacity::bench
