#include "render/denoise.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "render/albedo_layer.h"

namespace render {
namespace {

constexpr float kB3[5] = {1 / 16.0f, 1 / 4.0f, 3 / 8.0f, 1 / 4.0f, 1 / 16.0f};  // the B3 spline's taps

// Albedo below this is not divided out: black surfaces would blow their noise up.
constexpr float kLeastAlbedo = 0.01f;

bool is_sky(const Image& img, std::size_t i) { return !std::isfinite(img.depth[i]); }

// What the filter smooths: the light arriving at the first hits, with their texture
// divided out, so a texture's detail is put back unblurred afterwards; the sky as it is.
// The albedo over all the pixel's samples where the path tracer kept it, else the centre's.
V3 albedo_divided_out(const Image& img, std::size_t i) {
  if (img.mean_albedo.empty() && is_sky(img, i)) return {1, 1, 1};
  const V3 a = img.mean_albedo.empty() ? img.albedo[i] : img.mean_albedo[i];
  return {std::max(a.x, kLeastAlbedo), std::max(a.y, kLeastAlbedo), std::max(a.z, kLeastAlbedo)};
}

// How fast depth changes around a pixel, in metres a pixel: the larger of its neighbours'
// differences, so a ground plane seen at a grazing angle is still one surface.
std::vector<float> depth_gradients(const Image& img) {
  std::vector<float> g(img.depth.size(), 0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
      if (is_sky(img, i)) continue;
      float most = 0;
      const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
      for (int k = 0; k < 4; ++k) {
        const int u = x + dx[k], v = y + dy[k];
        if (u < 0 || v < 0 || u >= img.width || v >= img.height) continue;
        const std::size_t j = static_cast<std::size_t>(v) * img.width + u;
        if (!is_sky(img, j)) most = std::max(most, std::abs(img.depth[j] - img.depth[i]));
      }
      g[i] = most;
    }
  return g;
}

// The variance smoothed over 3x3 pixels of the same kind (sky or surface): a few samples'
// variance is itself too noisy to steer the filter alone (Schied et al. 2017).
std::vector<float> smoothed_variance(const Image& img, const std::vector<float>& variance) {
  std::vector<float> out(variance.size(), 0);
  const float k[3] = {0.25f, 0.5f, 0.25f};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
      float sum = 0, weights = 0;
      for (int v = -1; v <= 1; ++v)
        for (int u = -1; u <= 1; ++u) {
          const int px = x + u, py = y + v;
          if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
          const std::size_t j = static_cast<std::size_t>(py) * img.width + px;
          if (is_sky(img, i) != is_sky(img, j)) continue;
          sum += k[u + 1] * k[v + 1] * variance[j], weights += k[u + 1] * k[v + 1];
        }
      out[i] = sum / weights;
    }
  return out;
}

struct Level {
  std::vector<V3> light;
  std::vector<float> variance;
};

// One à-trous level: the 5x5 B3 kernel with holes of `step` pixels, each tap weighed by
// how alike its pixel is to the centre's.
Level filter_level(const Image& img, const Level& in, const std::vector<float>& gradients, int step,
                   const DenoiseSettings& s) {
  Level out{std::vector<V3>(in.light.size()), std::vector<float>(in.variance.size())};
  const std::vector<float> variance = img.variance.empty() ? std::vector<float>{} : smoothed_variance(img, in.variance);
  tbb::parallel_for(0, img.height, [&](int y) {
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
      const bool sky = is_sky(img, i);
      const float lp = luminance(in.light[i]);
      // Without a variance (an image from elsewhere) luminance stops nothing.
      const float noise = variance.empty() ? INFINITY : s.luminance_sigma * std::sqrt(variance[i]) + 1e-6f;
      V3 sum{0, 0, 0};
      float weights = 0, var = 0;
      for (int v = -2; v <= 2; ++v)
        for (int u = -2; u <= 2; ++u) {
          const int px = x + u * step, py = y + v * step;
          if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
          const std::size_t j = static_cast<std::size_t>(py) * img.width + px;
          if (sky != is_sky(img, j)) continue;  // never across the skyline
          // The stopping functions multiply, so their exponents add: one exp a tap, the
          // normals' cos^p as p log cos, in place of a pow and three exps.
          float exponent = -std::abs(lp - luminance(in.light[j])) / noise;
          if (!sky && j != i) {
            const float facing = dot(img.normal[i], img.normal[j]);
            if (facing <= 0) continue;
            const float distance = static_cast<float>(step) * std::sqrt(static_cast<float>(u * u + v * v));
            const float depth_scale = s.depth_sigma * gradients[i] * distance + 1e-3f * img.depth[i] + 1e-6f;
            const V3 da = img.albedo[i] - img.albedo[j];
            exponent += s.normal_power * std::log(facing) - std::abs(img.depth[i] - img.depth[j]) / depth_scale -
                        (std::abs(da.x) + std::abs(da.y) + std::abs(da.z)) / s.albedo_sigma;
          }
          // Below e^-30 a tap weighs nothing next to the centre's (e^0), and exp's underflow
          // path is slow.
          if (exponent < -30) continue;
          const float w = kB3[u + 2] * kB3[v + 2] * std::exp(exponent);
          sum += in.light[j] * w, weights += w, var += w * w * in.variance[j];
        }
      // The centre's own weight is never zero, so neither is the sum.
      out.light[i] = sum / weights, out.variance[i] = var / (weights * weights);
    }
  });
  return out;
}

}  // namespace

Image denoise(const Image& img, const DenoiseSettings& s) {
  const std::size_t n = img.beauty.size();
  Level level{std::vector<V3>(n), std::vector<float>(n, 0)};
  for (std::size_t i = 0; i < n; ++i) {
    const V3 a = albedo_divided_out(img, i);
    level.light[i] = {img.beauty[i].x / a.x, img.beauty[i].y / a.y, img.beauty[i].z / a.z};
    const float la = luminance(a);
    if (!img.variance.empty()) level.variance[i] = img.variance[i] / (la * la);
  }
  const std::vector<float> gradients = depth_gradients(img);
  for (int l = 0; l < s.levels; ++l) level = filter_level(img, level, gradients, 1 << l, s);
  Image out = img;
  for (std::size_t i = 0; i < n; ++i) {
    const V3 a = albedo_divided_out(img, i);
    out.beauty[i] = level.light[i] * a;
    const float la = luminance(a);
    out.variance.resize(n);
    out.variance[i] = level.variance[i] * la * la;
  }
  return out;
}

Image denoise_render(Image image, const RenderScene& scene, const Camera& camera, const DenoiseSettings& settings) {
  image.mean_albedo = albedo_layer(scene, camera, image.width, image.height, kAlbedoGrid);
  return denoise(image, settings);
}

}  // namespace render
