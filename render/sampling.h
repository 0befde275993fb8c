// Random numbers and the directions drawn from them. Each pixel sample draws from its own
// stream, seeded by (pixel, sample), so an image does not depend on the thread count.
#pragma once

#include <cmath>
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

// Where sample k falls within its pixel, in [0, 1)^2: the R2 sequence (Roberts 2018,
// multiples of the plastic number's inverse powers), started at the centre so that
// sample 0 goes through it. Its points cover the pixel evenly at every count, so edges
// and texture finer than a pixel converge faster than with independent jitter (the Cycles
// comparison, benchmarks/cycles/README.md); the same in every pixel and for every pass
// split, since it depends on k alone.
inline void pixel_jitter(std::uint64_t k, float& x, float& y) {
  constexpr double kA1 = 0.75487766624669276, kA2 = 0.56984029099805327;  // 1/g, 1/g^2, g^3 = g + 1
  const double kd = static_cast<double>(k), u = 0.5 + kA1 * kd, v = 0.5 + kA2 * kd;
  x = static_cast<float>(u - std::floor(u)), y = static_cast<float>(v - std::floor(v));
}

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
