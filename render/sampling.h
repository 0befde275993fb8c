// Random numbers and the directions drawn from them. Each pixel sample draws from its own
// stream, seeded by (pixel, sample), so an image does not depend on the thread count.
#pragma once

#include <cstdint>

#include "generate/city/random.h"
#include "render/vec.h"

namespace render {

class Sampler {
 public:
  Sampler(std::uint64_t pixel, std::uint64_t sample)
      : stream_(exacity::mix(exacity::mix(pixel) ^ (sample * 0x9e3779b97f4a7c15ull))) {}
  float next() { return static_cast<float>(stream_.next() >> 40) * 0x1.0p-24f; }  // [0, 1)

 private:
  exacity::Random stream_;  // the city's generator; next() keeps the top 24 bits, a float's mantissa
};

// Cosine-weighted direction about +z; pdf cos/pi.
inline V3 cosine_hemisphere(float u1, float u2) {
  float r = std::sqrt(u1), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1 - u1))};
}

// Uniform direction in the cone of half-angle acos(cos_max) about +z; pdf 1/(2pi(1-cos_max)).
inline V3 uniform_cone(float u1, float u2, float cos_max) {
  float c = 1 - u1 * (1 - cos_max), s = std::sqrt(std::max(0.0f, 1 - c * c)), phi = 2 * kPi * u2;
  return {s * std::cos(phi), s * std::sin(phi), c};
}

inline float power_heuristic(float a, float b) { return a * a / (a * a + b * b); }

}  // namespace render
