// Determinism (docs/design.md): every random choice draws from a generator seeded by a hash of
// (seed, stage, stable id of the thing generated), never from one shared stream.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace exacity {

// SplitMix64's finaliser: a strong 64-bit mix.
constexpr std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
constexpr std::uint64_t mix(std::uint64_t a, std::uint64_t b) { return mix(a ^ mix(b)); }

// A stable id from a thing's exact content written out (geom::exact_text): FNV-1a, the same
// on every platform, so what is generated from it depends on the thing alone, not on how
// many came before it (docs/design.md, Regions and regenerating).
constexpr std::uint64_t content_id(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

enum class Stage : std::uint64_t { Roads = 1, Lots = 2, Buildings = 3, Clutter = 4 };

class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() { return mix(state_++); }
  // Uniform in [0, 1): the top 53 bits, so the same on every platform.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

// A value drawn from a distribution given at equal steps, smallest to largest (a real
// place's, as --like measures it): linear between its steps; at least two steps.
inline double draw_from_steps(const std::vector<double>& steps, Random& rng) {
  const double at = rng.uniform() * static_cast<double>(steps.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(at), steps.size() - 2);
  return steps[i] + (at - static_cast<double>(i)) * (steps[i + 1] - steps[i]);
}

}  // namespace exacity
