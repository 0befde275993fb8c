// The sampler's numbers (render/sampling.h): stratified where it says so, independent
// between slots and between the two halves; and the polynomial circle.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "render/sampling.h"

using namespace render;

namespace {

// Slot `slot`'s 2D point of sample k of pixel `pixel` (earlier slots drawn and dropped).
std::pair<float, float> point(std::uint64_t pixel, std::uint64_t k, int slot) {
  Sampler rng(pixel, k);
  for (int s = 0; s < slot; ++s) rng.next2();
  return rng.next2();
}

}  // namespace

TEST(Sampler, EachHalfsFirstPowerOfTwoSamplesAreANet) {
  // 2^m samples of one half: one point in every elementary interval of area 2^-m
  // (1 x 2^-m, 2^-1 x 2^-(m-1), ..., 2^-m x 1), in every stratified slot and pixel: the
  // first surface's sun, sky, bounce and lobe at least.
  ASSERT_GE(Sampler::kStratifiedSlots, 4);
  for (std::uint64_t pixel : {0ull, 7ull, 123456ull})
    for (int slot = 0; slot < Sampler::kStratifiedSlots; ++slot)
      for (int half = 0; half < 2; ++half)
        for (int m : {2, 4, 6}) {
          const int n = 1 << m;
          for (int a = 0; a <= m; ++a) {
            std::set<std::pair<int, int>> cells;
            for (int j = 0; j < n; ++j) {
              const auto [x, y] = point(pixel, 2 * j + half, slot);
              cells.insert({static_cast<int>(x * (1 << a)), static_cast<int>(y * (1 << (m - a)))});
            }
            EXPECT_EQ(cells.size(), static_cast<std::size_t>(n))
                << "pixel " << pixel << " slot " << slot << " half " << half << " 2^" << m << " split " << a;
          }
        }
}

TEST(Sampler, HalvesSlotsAndPixelsDrawDifferentPoints) {
  auto points = [](std::uint64_t pixel, int half, int slot) {
    std::vector<std::pair<float, float>> p;
    for (int j = 0; j < 16; ++j) p.push_back(point(pixel, 2 * j + half, slot));
    return p;
  };
  EXPECT_NE(points(5, 0, 0), points(5, 1, 0));
  EXPECT_NE(points(5, 0, 0), points(5, 0, 1));
  EXPECT_NE(points(5, 0, 0), points(6, 0, 0));
  // Past the stratified slots: the pixel's independent stream, different per sample.
  EXPECT_NE(point(5, 0, Sampler::kStratifiedSlots), point(5, 2, Sampler::kStratifiedSlots));
}

TEST(Sampler, StratifiedSlotsEstimateASmoothIntegralBetterThanIndependentNumbers) {
  // The mean of x^2 + y^3 (exactly 1/3 + 1/4) over 64 samples in 500 pixels: the squared
  // error with slot 0's points against that with points past the stratified slots.
  const double truth = 1.0 / 3 + 1.0 / 4;
  double stratified = 0, independent = 0, bias = 0;
  for (std::uint64_t pixel = 0; pixel < 500; ++pixel) {
    double a = 0, b = 0;
    for (std::uint64_t k = 0; k < 64; ++k) {
      const auto [x, y] = point(pixel, k, 0);
      const auto [u, v] = point(pixel, k, Sampler::kStratifiedSlots);
      a += x * x + y * y * y, b += u * u + v * v * v;
    }
    stratified += std::pow(a / 64 - truth, 2), independent += std::pow(b / 64 - truth, 2), bias += a / 64 - truth;
  }
  EXPECT_LT(stratified * 20, independent);
  // Unbiased: the pixels' mean error within three standard errors of zero.
  EXPECT_LT(std::abs(bias / 500), 3 * std::sqrt(stratified / 500) / std::sqrt(500.0));
}

TEST(Sampler, CirclePointIsCosAndSinOfTheTurn) {
  for (int i = 0; i < 100000; ++i) {
    const float u = static_cast<float>(i) / 100000;
    const CirclePoint p = circle_point(u);
    const double phi = 2 * M_PI * u;
    // A float turn's own rounding (its angle to 1.2e-7 near a quarter) and the polynomials'.
    ASSERT_NEAR(p.c, std::cos(phi), 3e-7) << u;
    ASSERT_NEAR(p.s, std::sin(phi), 3e-7) << u;
  }
}
