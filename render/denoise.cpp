#include "render/denoise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "generate/cancel.h"
#include "render/primary_layer.h"

namespace render {
namespace {

constexpr float kB3[5] = {1 / 16.0f, 1 / 4.0f, 3 / 8.0f, 1 / 4.0f, 1 / 16.0f};  // the B3 spline's taps

// Albedo below this is not divided out: black surfaces would blow their noise up.
constexpr float kLeastAlbedo = 0.01f;

inline bool is_sky(const Image& img, std::size_t i) { return !std::isfinite(img.depth[i]); }

// f(i) for every pixel, in parallel: on two cores a serial pass over the image costs
// twice its share of the filter's time. Each pixel's result is its own, so the output is
// the same whatever the threads.
template <typename F>
void each_pixel(std::size_t n, const F& f) {
  const exacity::CancelCheck cancel;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    cancel.check();
    for (std::size_t i = r.begin(); i < r.end(); ++i) f(i);
  });
}

V3 dividable(V3 a) { return {std::max(a.x, kLeastAlbedo), std::max(a.y, kLeastAlbedo), std::max(a.z, kLeastAlbedo)}; }

// One estimate of the image: the light arriving at the first hits, less the sun's next
// event there, with the albedo divided out (so a texture's detail and the sun's shadows
// are put back unblurred afterwards; the sky's albedo is white), the variance of its
// luminance, and what puts the beauty back together: the albedo and the sun's part, the
// estimate's own, and finer ones that add the primary layer's rays where there are some.
struct Estimate {
  std::vector<V3> light, albedo, sun;
  std::vector<V3> finer_albedo, finer_sun;
  std::vector<float> variance;
  float share = 1;  // of the image's samples
};

// `sun` may be empty (none split off).
Estimate estimate_of(const std::vector<V3>& beauty, const std::vector<V3>& albedo, const std::vector<V3>& sun,
                     const std::vector<float>& variance, float share) {
  const std::size_t n = beauty.size();
  Estimate e{std::vector<V3>(n), std::vector<V3>(n), sun.empty() ? std::vector<V3>(n) : sun, {}, {},
             std::vector<float>(n, 0), share};
  each_pixel(n, [&](std::size_t i) {
    const V3 a = dividable(albedo[i]), rest = beauty[i] - e.sun[i];
    e.light[i] = {rest.x / a.x, rest.y / a.y, rest.z / a.z}, e.albedo[i] = a;
    const float la = luminance(a);
    // A part of the samples is noisier than all of them by their ratio.
    if (!variance.empty()) e.variance[i] = variance[i] / share / (la * la);
  });
  return e;
}

// The mean over `samples` path samples (their mean `own`) and the primary layer's rays
// (their sum `extra`).
std::vector<V3> with_extra(const std::vector<V3>& own, int samples, const std::vector<V3>& extra, int extra_samples) {
  std::vector<V3> mean(own.size());
  const float all = static_cast<float>(samples + extra_samples);
  for (std::size_t i = 0; i < mean.size(); ++i) mean[i] = (own[i] * static_cast<float>(samples) + extra[i]) / all;
  return mean;
}

std::vector<V3> dividable(std::vector<V3> albedo) {
  for (V3& a : albedo) a = dividable(a);
  return albedo;
}

// The estimates the filter works on: the two halves of the samples where the image has
// them (Image::halves), else the image alone (from elsewhere, or one sample), divided by
// the path samples' own mean albedo, or the centre's.
std::vector<Estimate> estimates(const Image& img) {
  const int all = img.halves[0].samples + img.halves[1].samples;
  if (img.halves[0].samples > 0 && img.halves[1].samples > 0) {
    std::vector<Estimate> halves;
    for (const Image::Half& h : img.halves) {
      Estimate e = estimate_of(h.beauty, h.albedo, h.sun, img.variance, static_cast<float>(h.samples) / all);
      if (img.extra.samples > 0) {
        e.finer_albedo = dividable(with_extra(h.albedo, h.samples, img.extra.albedo, img.extra.samples));
        e.finer_sun = with_extra(h.sun, h.samples, img.extra.sun, img.extra.samples);
      }
      halves.push_back(std::move(e));
    }
    return halves;
  }
  std::vector<V3> albedo = img.mean_albedo.empty() ? img.albedo : img.mean_albedo;
  if (img.mean_albedo.empty())
    for (std::size_t i = 0; i < albedo.size(); ++i)
      if (is_sky(img, i)) albedo[i] = {1, 1, 1};
  return {estimate_of(img.beauty, albedo, img.first_sun, img.variance, 1)};
}

// The albedo the filter's taps are compared by: the mean over all the pixel's rays where
// it has several (the primary layer's too), so that pixels straddling one edge alike match
// one another, where sample 0's albedo, one side's, told them apart (on the Cycles
// comparison's view, 3% less squared error at 64 samples than sample 0's); else sample 0's.
// The sky counts as white here as in the mean (Image::mean_albedo), where sample 0's has
// it black; the filter never mixes sky and surface pixels anyway.
std::vector<V3> guide_albedo(const Image& img) {
  if (img.mean_albedo.empty()) return img.albedo;
  if (img.extra.samples == 0) return img.mean_albedo;
  return with_extra(img.mean_albedo, img.halves[0].samples + img.halves[1].samples, img.extra.albedo, img.extra.samples);
}

// How fast depth changes around a pixel, in metres a pixel: the larger of its neighbours'
// differences, so a ground plane seen at a grazing angle is still one surface.
std::vector<float> depth_gradients(const Image& img) {
  std::vector<float> g(img.depth.size(), 0);
  tbb::parallel_for(0, img.height, [&](int y) {
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
  });
  return g;
}

// The variance smoothed over 3x3 pixels of the same kind (sky or surface): a few samples'
// variance is itself too noisy to steer the filter alone (Schied et al. 2017).
std::vector<float> smoothed_variance(const Image& img, const std::vector<float>& variance) {
  std::vector<float> out(variance.size(), 0);
  const float k[3] = {0.25f, 0.5f, 0.25f};
  const exacity::CancelCheck cancel;
  tbb::parallel_for(0, img.height, [&](int y) {
    cancel.check();
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
  });
  return out;
}

// e^x for x in [-30, 0], to a relative 1e-4 (2^x's fraction by its Taylor polynomial, its whole
// part put into the exponent's bits): libm's expf was a third of the filter's time.
float exp_taps(float x) {
  const float t = x * 1.44269504f;  // log2(e)
  const float whole = std::floor(t), f = t - whole;
  // 2^f on [0, 1), to degree 5.
  const float p = 1.0f + f * (0.693147182f + f * (0.240226507f + f * (0.0555041086f + f * (0.00961812911f + f * 0.00133335581f))));
  const std::int32_t bits = (static_cast<std::int32_t>(whole) + 127) << 23;
  float scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

float power_128(float c) {
  for (int k = 0; k < 7; ++k) c *= c;
  return c;
}

// One à-trous level of every estimate: the 5x5 B3 kernel with holes of `step` pixels,
// each tap weighed by how alike its pixel is to the centre's, in the guides (shared) and
// in the estimate's own luminance (each its own).
void filter_level(const Image& img, std::vector<Estimate>& estimates, const std::vector<float>& gradients,
                  const std::vector<V3>& albedo, int step, const DenoiseSettings& s) {
  const std::size_t count = estimates.size();
  // Each estimate's luminance, and one over the difference in it that stops a tap.
  std::vector<std::vector<float>> lum(count), inverse_noise(count);
  for (std::size_t e = 0; e < count; ++e) {
    lum[e].resize(img.beauty.size());
    each_pixel(lum[e].size(), [&](std::size_t i) { lum[e][i] = luminance(estimates[e].light[i]); });
    // Without a variance (an image from elsewhere) luminance stops nothing.
    inverse_noise[e].assign(img.beauty.size(), 0);
    if (img.variance.empty()) continue;
    const std::vector<float> v = smoothed_variance(img, estimates[e].variance);
    each_pixel(v.size(), [&](std::size_t i) { inverse_noise[e][i] = 1 / (s.luminance_sigma * std::sqrt(v[i]) + 1e-6f); });
  }
  float distance[5][5];
  for (int v = -2; v <= 2; ++v)
    for (int u = -2; u <= 2; ++u)
      distance[v + 2][u + 2] = static_cast<float>(step) * std::sqrt(static_cast<float>(u * u + v * v));
  // The level's light and variance; the rest of each estimate stays as it is.
  std::vector<std::vector<V3>> light(count, std::vector<V3>(img.beauty.size()));
  std::vector<std::vector<float>> variances(count, std::vector<float>(img.beauty.size()));
  // Row by row: a large image's level takes seconds (generate/cancel.h).
  const exacity::CancelCheck cancel;
  tbb::parallel_for(0, img.height, [&](int y) {
    cancel.check();
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
      const bool sky = is_sky(img, i);
      V3 sum[2] = {};
      float weights[2] = {}, variance[2] = {};
      for (int v = -2; v <= 2; ++v)
        for (int u = -2; u <= 2; ++u) {
          const int px = x + u * step, py = y + v * step;
          if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
          const std::size_t j = static_cast<std::size_t>(py) * img.width + px;
          if (sky != is_sky(img, j)) continue;  // never across the skyline
          // The stopping functions multiply: the guides' (normals, depth, albedo), shared
          // by the estimates, then each estimate's luminance; one exp each.
          float guides = kB3[u + 2] * kB3[v + 2], exponent = 0;
          if (!sky && j != i) {
            const float facing = dot(img.normal[i], img.normal[j]);
            if (facing <= 0) continue;
            const float depth_scale =
                s.depth_sigma * gradients[i] * distance[v + 2][u + 2] + 1e-3f * img.depth[i] + 1e-6f;
            const V3 da = albedo[i] - albedo[j];
            exponent = -std::abs(img.depth[i] - img.depth[j]) / depth_scale -
                       (std::abs(da.x) + std::abs(da.y) + std::abs(da.z)) / s.albedo_sigma;
            if (exponent < -30) continue;  // the guides alone stop it (below)
            // cos^128 by squaring; other powers through pow.
            guides *= s.normal_power == 128 ? power_128(facing) : std::pow(facing, s.normal_power);
          }
          for (std::size_t e = 0; e < count; ++e) {
            const float stop = exponent - std::abs(lum[e][i] - lum[e][j]) * inverse_noise[e][i];
            // Below e^-30 a tap weighs nothing next to the centre's (e^0), and exp's
            // underflow path is slow.
            if (stop < -30) continue;
            const float w = guides * exp_taps(stop);
            const Estimate& in = estimates[e];
            sum[e] += in.light[j] * w, weights[e] += w, variance[e] += w * w * in.variance[j];
          }
        }
      // The centre's own weight is never zero, so neither is the sum.
      for (std::size_t e = 0; e < count; ++e)
        light[e][i] = sum[e] / weights[e], variances[e][i] = variance[e] / (weights[e] * weights[e]);
    }
  });
  for (std::size_t e = 0; e < count; ++e) estimates[e].light.swap(light[e]), estimates[e].variance.swap(variances[e]);
}

// The mean of `values` over (2r+1)^2 pixels (fewer at the borders): a box filter, its
// rows then its columns.
std::vector<float> box_mean(const std::vector<float>& values, int width, int height, int r) {
  std::vector<float> rows(values.size()), out(values.size());
  const exacity::CancelCheck cancel;
  tbb::parallel_for(0, height, [&](int y) {
    cancel.check();
    for (int x = 0; x < width; ++x) {
      float sum = 0;
      const int x0 = std::max(0, x - r), x1 = std::min(width - 1, x + r);
      for (int u = x0; u <= x1; ++u) sum += values[static_cast<std::size_t>(y) * width + u];
      rows[static_cast<std::size_t>(y) * width + x] = sum / static_cast<float>(x1 - x0 + 1);
    }
  });
  tbb::parallel_for(0, height, [&](int y) {
    const int y0 = std::max(0, y - r), y1 = std::min(height - 1, y + r);
    for (int x = 0; x < width; ++x) {
      float sum = 0;
      for (int v = y0; v <= y1; ++v) sum += rows[static_cast<std::size_t>(v) * width + x];
      out[static_cast<std::size_t>(y) * width + x] = sum / static_cast<float>(y1 - y0 + 1);
    }
  });
  return out;
}

// The beauty an estimate gives at pixel i: its light times its own albedo plus its own
// sun, or the finer ones.
V3 beauty_of(const Estimate& e, std::size_t i, bool finer) {
  return finer ? e.light[i] * e.finer_albedo[i] + e.finer_sun[i] : e.light[i] * e.albedo[i] + e.sun[i];
}

float squared(V3 d) { return dot(d, d); }

// The error each pixel of the halves' filtered estimates would have, up to a term the
// same at every level, told by cross-validation: each half filtered against the other
// half unfiltered, which is independent of it, less the filtered halves' own spread,
// smoothed over the pixel's neighbourhood.
std::vector<float> level_error(const Image& img, const std::vector<Estimate>& filtered, bool finer, int radius) {
  std::vector<float> error(img.beauty.size());
  const std::vector<V3>& raw_a = img.halves[0].beauty;
  const std::vector<V3>& raw_b = img.halves[1].beauty;
  tbb::parallel_for(std::size_t{0}, error.size(), [&](std::size_t i) {
    const V3 a = beauty_of(filtered[0], i, finer), b = beauty_of(filtered[1], i, finer);
    error[i] = (squared(a - raw_b[i]) + squared(b - raw_a[i])) / 2 - squared(a - b) / 4;
  });
  return box_mean(error, img.width, img.height, radius);
}

// The haze's in-scatter (Image::inscatter) smoothed: four à-trous levels of the B3 kernel
// (30 pixels each way), each tap weighed by how alike the haze's transmittance to the two
// pixels' first surfaces is, and by nothing else, across the skyline too (far ground and
// sky are both all haze). The light scattered in more than once changes slowly with the
// ray's direction (the light shafts and the sun's glow are the light scattered once, which
// the sun's layer keeps sharp) and with the haze in front of the surface, which the
// transmittance tells; noise it has plenty, a random walk's, which a filter stopped by
// luminance, as the rest is, left as blotches. Six levels left a little less grain on
// tests/render_quality_test.cpp's haze but flattened its sky's brightness across the
// frame by up to 12% over blocks of 8x8 pixels; four, 9%, where the samples' own mean
// errs by 3%.
constexpr int kInscatterLevels = 4;
constexpr float kSeenSigma = 0.05f;
std::vector<V3> smoothed_inscatter(const Image& img) {
  std::vector<V3> light = img.inscatter, next(light.size());
  const exacity::CancelCheck cancel;
  for (int level = 0; level < kInscatterLevels; ++level) {
    const int step = 1 << level;
    tbb::parallel_for(0, img.height, [&](int y) {
      cancel.check();
      for (int x = 0; x < img.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
        V3 sum{0, 0, 0};
        float weights = 0;
        for (int v = -2; v <= 2; ++v)
          for (int u = -2; u <= 2; ++u) {
            const int px = x + u * step, py = y + v * step;
            if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
            const std::size_t j = static_cast<std::size_t>(py) * img.width + px;
            const float w = kB3[u + 2] * kB3[v + 2] * exp_taps(-std::abs(img.seen[i] - img.seen[j]) / kSeenSigma);
            sum += light[j] * w, weights += w;
          }
        next[i] = sum / weights;
      }
    });
    light.swap(next);
  }
  return light;
}

}  // namespace

Image denoise(const Image& img, const DenoiseSettings& s) {
  if (!img.inscatter.empty()) {
    // In haze: the rest filtered as in clear air, the in-scatter smoothed apart.
    Image rest = img;
    rest.inscatter.clear(), rest.seen.clear();
    for (std::size_t i = 0; i < img.beauty.size(); ++i) rest.beauty[i] = rest.beauty[i] - img.inscatter[i];
    for (Image::Half& h : rest.halves) {
      if (h.inscatter.empty()) continue;
      for (std::size_t i = 0; i < h.beauty.size(); ++i) h.beauty[i] = h.beauty[i] - h.inscatter[i];
      h.inscatter.clear();
    }
    Image out = denoise(rest, s);
    const std::vector<V3> inscatter = smoothed_inscatter(img);
    for (std::size_t i = 0; i < out.beauty.size(); ++i) out.beauty[i] += inscatter[i];
    out.inscatter = img.inscatter, out.seen = img.seen;
    return out;
  }
  const std::size_t n = img.beauty.size();
  std::vector<Estimate> level = estimates(img);
  const std::vector<float> gradients = depth_gradients(img);
  const std::vector<V3> albedo = guide_albedo(img);
  Image out = img;
  out.variance.resize(n);
  if (level.size() == 1) {
    // One estimate: nothing to tell the levels apart by; the last.
    for (int l = 0; l < s.levels; ++l) filter_level(img, level, gradients, albedo, 1 << l, s);
    for (std::size_t i = 0; i < n; ++i) {
      const float la = luminance(level[0].albedo[i]);
      out.beauty[i] = beauty_of(level[0], i, false), out.variance[i] = level[0].variance[i] * la * la;
    }
    return out;
  }
  // Two halves: each pixel takes the level, and the remodulation, whose error the halves
  // tell is least, the unfiltered image (level 0) included, so a converged pixel stays as
  // it is.
  const int all = img.halves[0].samples + img.halves[1].samples;
  std::vector<V3> finer_albedo, finer_sun;
  if (img.extra.samples > 0) {
    finer_albedo = dividable(albedo);  // the guide's: the mean over all the rays
    finer_sun = with_extra(img.first_sun, all, img.extra.sun, img.extra.samples);
  }
  std::vector<float> least = level_error(img, level, false, s.selection_radius);
  for (int l = 0; l <= s.levels; ++l) {
    if (l > 0) filter_level(img, level, gradients, albedo, 1 << (l - 1), s);
    for (const bool finer : {false, true}) {
      if ((l == 0 && !finer) || (finer && finer_albedo.empty())) continue;
      const std::vector<float> error = level_error(img, level, finer, s.selection_radius);
      each_pixel(n, [&](std::size_t i) {
        if (!(error[i] < least[i])) return;
        least[i] = error[i];
        V3 light{0, 0, 0}, own{0, 0, 0};
        float variance = 0;
        for (const Estimate& e : level) {
          const float la = luminance(e.albedo[i]);
          light += e.light[i] * e.share, own += beauty_of(e, i, false) * e.share;
          variance += e.share * e.share * e.variance[i] * la * la;
        }
        out.beauty[i] = finer ? light * finer_albedo[i] + finer_sun[i] : own, out.variance[i] = variance;
      });
    }
  }
  return out;
}

int primary_rays(int samples, const DenoiseSettings& settings) {
  return std::clamp(samples / 2, std::min(8, settings.primary_rays), settings.primary_rays);
}

namespace {

// Rows [y0, y1) of an image with every layer it has.
Image rows_of(const Image& img, int y0, int y1) {
  const std::size_t from = static_cast<std::size_t>(y0) * img.width, to = static_cast<std::size_t>(y1) * img.width;
  auto cut = [&](const auto& v) {
    using Vector = std::decay_t<decltype(v)>;
    return v.empty() ? Vector{} : Vector(v.begin() + static_cast<std::ptrdiff_t>(from), v.begin() + static_cast<std::ptrdiff_t>(to));
  };
  Image out;
  out.width = img.width, out.height = y1 - y0;
  out.beauty = cut(img.beauty), out.depth = cut(img.depth), out.normal = cut(img.normal), out.albedo = cut(img.albedo);
  out.id = cut(img.id), out.variance = cut(img.variance), out.mean_albedo = cut(img.mean_albedo);
  out.first_sun = cut(img.first_sun), out.inscatter = cut(img.inscatter), out.seen = cut(img.seen);
  for (int h = 0; h < 2; ++h)
    out.halves[h] = {cut(img.halves[h].beauty), cut(img.halves[h].albedo), cut(img.halves[h].sun), img.halves[h].samples,
                     cut(img.halves[h].inscatter)};
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

double filter_seconds(const Image& image, bool primary_layer, bool as_it_is, const DenoiseSettings& settings) {
  // Two bands of a sixteenth of the rows each (32 at least), a quarter and three quarters
  // down, timed and scaled: a sky pixel costs the filter less than a surface's, and the top
  // rows of an aerial view are sky.
  const int rows = std::min(image.height, std::max(32, image.height / 16));
  if (rows == 0) return 0;
  double seconds = 0;
  int timed = 0;
  for (const int centre : {image.height / 4, image.height * 3 / 4}) {
    const int y0 = std::clamp(centre - rows / 2, 0, image.height - rows);
    Image band = rows_of(image, y0, y0 + rows);
    // One sample has no halves, nor a variance (it is 0): the filter of two halves, whose
    // time is asked, does more, its taps stopped by noise that is there. Two equal halves
    // and a spread as large as each pixel's light stand in (0: the filter stopped nearly
    // every tap and took a third of its time on two samples).
    if (band.halves[0].samples == 0 && !as_it_is) {
      for (Image::Half& h : band.halves) h = {band.beauty, band.mean_albedo, band.first_sun, 1, band.inscatter};
      for (std::size_t i = 0; i < band.variance.size(); ++i) band.variance[i] = luminance(band.beauty[i]) * luminance(band.beauty[i]);
    }
    // With a primary layer the filter tries every level twice (the path samples' albedo and
    // sun, and all the rays'): a stand-in layer of the band's own albedo and sun, so the
    // time is that work's (without it the forecast was a fifth under the filter's time).
    if (primary_layer && !band.mean_albedo.empty() && !band.first_sun.empty()) {
      const int rays = primary_rays(2, settings);
      band.extra.albedo = band.mean_albedo, band.extra.sun = band.first_sun, band.extra.samples = rays;
      for (V3& a : band.extra.albedo) a = a * static_cast<float>(rays);
      for (V3& s : band.extra.sun) s = s * static_cast<float>(rays);
    }
    const auto start = std::chrono::steady_clock::now();
    denoise(band, settings);
    seconds += seconds_since(start);
    timed += rows;
  }
  return seconds * image.height / timed;
}

Image denoise_render(Image image, const RenderScene& scene, const Sky& sky, const Camera& camera, const Haze& haze,
                     const DenoiseSettings& settings, double* primary_layer_s) {
  const int samples = image.halves[0].samples + image.halves[1].samples;
  const int rays = primary_rays(samples, settings);
  const auto start = std::chrono::steady_clock::now();
  if (rays > 0 && samples >= 2 && haze.density <= 0)
    image.extra = primary_layer(scene, sky, camera, image.width, image.height, samples, rays, haze);
  if (primary_layer_s) *primary_layer_s = seconds_since(start);
  return denoise(image, settings);
}

}  // namespace render
