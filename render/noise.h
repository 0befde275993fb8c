// Perlin's improved gradient noise in 2D and its fractal sum, for grass (docs/design.md, Algorithms: path tracing).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace render {

class Noise {
 public:
  Noise() {
    for (int i = 0; i < 256; ++i) perm_[i] = static_cast<std::uint8_t>(i);
    std::uint32_t s = 2463534242u;  // a fixed shuffle: the same grass on every run
    for (int i = 255; i > 0; --i) {
      s ^= s << 13, s ^= s >> 17, s ^= s << 5;
      std::swap(perm_[i], perm_[s % (i + 1)]);
    }
  }
  // In [-1, 1] roughly.
  float operator()(float x, float y) const {
    const float fx = std::floor(x), fy = std::floor(y);
    const int xi = static_cast<int>(fx) & 255, yi = static_cast<int>(fy) & 255;
    x -= fx, y -= fy;
    const float u = fade(x), v = fade(y);
    auto h = [&](int i, int j) { return perm_[(perm_[(xi + i) & 255] + yi + j) & 255]; };
    const float a = lerp(u, grad(h(0, 0), x, y), grad(h(1, 0), x - 1, y));
    const float b = lerp(u, grad(h(0, 1), x, y - 1), grad(h(1, 1), x - 1, y - 1));
    return lerp(v, a, b);
  }
  // Octaves of halving amplitude and doubling frequency.
  float fractal(float x, float y, int octaves = 4) const {
    float sum = 0, amplitude = 0.5f;
    for (int i = 0; i < octaves; ++i, x *= 2.03f, y *= 2.03f, amplitude *= 0.5f) sum += amplitude * (*this)(x, y);
    return sum;
  }

 private:
  static float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }
  static float lerp(float t, float a, float b) { return a + t * (b - a); }
  // One of eight gradients, from a table: a switch on the hash mispredicts most times.
  static float grad(int hash, float x, float y) {
    static constexpr float kX[8] = {1, -1, 1, -1, 1, -1, 0, 0}, kY[8] = {1, 1, -1, -1, 0, 0, 1, -1};
    return kX[hash & 7] * x + kY[hash & 7] * y;
  }
  std::array<std::uint8_t, 256> perm_;
};

}  // namespace render
