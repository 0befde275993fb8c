// Random numbers and the directions drawn from them. Each pixel sample draws its own
// numbers, seeded by (pixel, sample), so an image does not depend on the thread count.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>

#include "generate/city/random.h"
#include "render/vec.h"

namespace render {

// Sample k of a pixel draws its numbers in slots, a 1D or a 2D draw each, in the order the
// path tracer makes them. The first kStratifiedSlots (for a pinhole camera in clear air
// with the sun up, the first surface's sun, sky, bounce direction and lobe; a thin lens
// takes the first slot, haze its free flights, and with the sun down the others move up)
// come from Sobol's first two dimensions, shuffled and Owen scrambled per pixel and slot
// (Burley 2020, "Practical Hash-based Owen Scrambling"): the first 2^m samples of each half
// (below) cover each of those domains evenly, and the direct light and first bounce
// converge faster than with independent numbers (on the Cycles comparison's view, 30% less
// squared error at 64 samples; deeper slots measured no better). The rest are independent. The even- and the odd-numbered
// samples are two sequences with their own scrambles, so the denoiser's two halves
// (Image::halves) stay independent estimates.
class Sampler {
 public:
  static constexpr int kStratifiedSlots = 4;

  Sampler(std::uint64_t pixel, std::uint64_t sample) : Sampler(exacity::mix(pixel), sample, 0) {}

  float next() {  // [0, 1)
    if (slot_ < kStratifiedSlots) return stratified(slot_++).first;
    return static_cast<float>(stream_.next() >> 40) * 0x1.0p-24f;  // a float's 24 bits
  }
  std::pair<float, float> next2() {
    if (slot_ < kStratifiedSlots) return stratified(slot_++);
    const float u = next();
    return {u, next()};
  }

 private:
  // The pixel's hash, taken once for both seeds.
  Sampler(std::uint64_t pixel_hash, std::uint64_t sample, int)
      : half_seed_(exacity::mix(pixel_hash ^ ((sample & 1) + 1))),
        reversed_index_(reverse_bits(static_cast<std::uint32_t>(sample >> 1))),
        stream_(exacity::mix(pixel_hash ^ (sample * 0x9e3779b97f4a7c15ull))) {}

  static constexpr std::uint32_t reverse_bits(std::uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
  }
  // Owen scrambling of a base-2 fraction held bit-reversed (its first digit in the lowest
  // bit): each digit is flipped by a hash of the digits before it (Laine and Karras 2011,
  // with Burley's constants); reversed back, the scrambled fraction.
  static std::uint32_t owen_scramble_reversed(std::uint32_t x, std::uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return reverse_bits(x);
  }
  // Sobol's second dimension, bit-reversed: the index's bits pick columns of the Pascal
  // matrix (mod 2), XORed a byte at a time from tables.
  struct PascalTables {
    std::uint32_t byte[4][256];
    constexpr PascalTables() : byte{} {
      std::uint32_t column = 1u << 31;
      for (int b = 0; b < 32; ++b, column ^= column >> 1)
        for (int v = 0; v < 256; ++v)
          if (v >> (b % 8) & 1) byte[b / 8][v] ^= reverse_bits(column);
    }
  };
  static std::uint32_t sobol_second_reversed(std::uint32_t index) {
    static constexpr PascalTables kTables;
    return kTables.byte[0][index & 0xff] ^ kTables.byte[1][index >> 8 & 0xff] ^ kTables.byte[2][index >> 16 & 0xff] ^
           kTables.byte[3][index >> 24];
  }
  std::pair<float, float> stratified(int slot) const {
    const std::uint64_t h = exacity::mix(half_seed_ + static_cast<std::uint64_t>(slot));
    // The index shuffled by an Owen scramble of its own, read from its top bit: the first
    // 2^m samples take 2^m consecutive points, still a net, and each slot other ones.
    const std::uint32_t j = owen_scramble_reversed(reversed_index_, static_cast<std::uint32_t>(h));
    const std::uint32_t x = owen_scramble_reversed(j, static_cast<std::uint32_t>(h >> 32));  // van der Corput: j reversed
    const std::uint32_t y =
        owen_scramble_reversed(sobol_second_reversed(j), static_cast<std::uint32_t>(exacity::mix(h)));
    return {static_cast<float>(x >> 8) * 0x1.0p-24f, static_cast<float>(y >> 8) * 0x1.0p-24f};
  }

  std::uint64_t half_seed_;
  std::uint32_t reversed_index_;
  int slot_ = 0;
  exacity::Random stream_;  // the city's generator
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

// The point at a turn of u (in [0, 1)) round the unit circle, cos and sin of 2 pi u to
// within 5e-8: polynomials over a quarter turn (fitted to it), moved to u's quarter
// without a branch, since the quarter is random. libm's sincosf took 4% of a render.
struct CirclePoint {
  float c, s;
};
inline CirclePoint circle_point(float u) {
  const float quarters = 4 * u;
  const int q = static_cast<int>(quarters) & 3;
  const float x = (quarters - std::floor(quarters)) * (kPi / 2), x2 = x * x;
  const float sin = x * (0.999999977f + x2 * (-0.166666476f + x2 * (0.00833289998f + x2 * (-0.000198009074f + x2 * 2.59050779e-06f))));
  const float cos = 0.999999954f + x2 * (-0.499999054f + x2 * (0.041663586f + x2 * (-0.00138537144f + x2 * 2.31541617e-05f)));
  const bool odd = q & 1;
  const float a = odd ? sin : cos, b = odd ? cos : sin;
  return {(q + 1) & 2 ? -a : a, q & 2 ? -b : b};
}

// Cosine-weighted direction about +z; pdf cos/pi.
inline V3 cosine_hemisphere(float u1, float u2) {
  const float r = std::sqrt(u1);
  const CirclePoint p = circle_point(u2);
  return {r * p.c, r * p.s, std::sqrt(std::max(0.0f, 1 - u1))};
}

// Uniform direction in the cone of half-angle acos(cos_max) about +z; pdf 1/(2pi(1-cos_max)).
inline V3 uniform_cone(float u1, float u2, float cos_max) {
  const float c = 1 - u1 * (1 - cos_max), s = std::sqrt(std::max(0.0f, 1 - c * c));
  const CirclePoint p = circle_point(u2);
  return {s * p.c, s * p.s, c};
}

inline float power_heuristic(float a, float b) { return a * a / (a * a + b * b); }

}  // namespace render
