#include "render/path_tracer.h"

#include <pmmintrin.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <cmath>
#include <mutex>
#include <thread>

#include "render/sampling.h"

namespace render {
namespace {

constexpr int kTile = 16;
constexpr float kEpsilon = 1e-3f;  // m: rays leave surfaces this far along the normal

}  // namespace

float henyey_greenstein(float cos_theta, float g) {
  const float d = 1 + g * g - 2 * g * cos_theta;
  return (1 - g * g) / (4 * kPi * d * std::sqrt(d));
}

V3 sample_henyey_greenstein(V3 direction, float g, float u1, float u2) {
  float cos_theta;
  if (std::abs(g) < 1e-3f) {
    cos_theta = 1 - 2 * u1;
  } else {
    const float s = (1 - g * g) / (1 - g + 2 * g * u1);
    cos_theta = (1 + g * g - s * s) / (2 * g);
  }
  const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta)), phi = 2 * kPi * u2;
  return Frame(direction).to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
}

namespace {

// Where the ray runs inside the haze layer, up to tmax: [t0, t1], empty when t1 <= t0.
std::pair<float, float> in_haze(const Haze& h, V3 o, V3 d, float tmax) {
  float t0 = 0, t1 = tmax;
  if (o.z > h.top) {
    if (d.z >= 0) return {0, 0};
    t0 = (h.top - o.z) / d.z;
  }
  if (d.z > 0) t1 = std::min(t1, (h.top - o.z) / d.z);
  return {t0, t1};
}

// The light that crosses the haze unscattered along a shadow ray, which leaves upwards
// (one going down meets the ground and is occluded anyway).
float transmittance(const Haze& h, V3 o, V3 d) {
  if (h.density <= 0 || o.z >= h.top) return 1;
  if (d.z <= 0) return 0;
  return std::exp(-h.density * (h.top - o.z) / d.z);
}

}  // namespace

V3 radiance(const RenderScene& scene, const Sky& sky, V3 o, V3 d, Sampler& rng, int max_depth, RayCounts& counts,
            Surface* first, const Haze& haze) {
  V3 L{0, 0, 0}, beta{1, 1, 1};
  float prev_pdf = 0;        // of the sampling that chose d; 0 for a camera ray
  bool prev_surface = true;  // d was chosen at a surface (sky next-event estimation ran there)
  V3 prev_normal{0, 0, 1};
  const float sun_pdf = 1 / (2 * kPi * (1 - sky.sun_cos_max()));
  for (int depth = 0;; ++depth) {
    Surface s;
    ++(depth == 0 ? counts.camera : counts.bounce);
    const bool hit = scene.intersect(o, d, INFINITY, s);
    if (depth == 0 && first && hit) *first = s;

    // The haze: a distance drawn by free flight; scattering before the surface means the
    // light turns there (no absorption: the weight stays).
    if (haze.density > 0) {
      auto [t0, t1] = in_haze(haze, o, d, hit ? s.distance : INFINITY);
      const float ts = t0 - std::log(1 - rng.next()) / haze.density;
      if (t1 > t0 && ts < t1) {
        if (depth >= max_depth) break;
        const V3 p = o + d * ts;
        if (sky.sun_up()) {
          const V3 wi = sky.sun_frame().to_world(uniform_cone(rng.next(), rng.next(), sky.sun_cos_max()));
          const float phase = henyey_greenstein(dot(d, wi), haze.g);
          ++counts.shadow;
          if (!scene.occluded(p, wi, INFINITY))
            L += beta * sky.sun_radiance() *
                 (phase * transmittance(haze, p, wi) * power_heuristic(sun_pdf, phase) / sun_pdf);
        }
        const V3 next = sample_henyey_greenstein(d, haze.g, rng.next(), rng.next());
        prev_pdf = henyey_greenstein(dot(d, next), haze.g);
        prev_surface = false;
        o = p, d = next;
        continue;
      }
    }

    if (!hit) {
      // The sky, and the sun where d meets its disk, weighted against next-event estimation.
      const float sky_pdf = prev_surface ? std::max(0.0f, dot(d, prev_normal)) / kPi : 0.0f;
      L += beta * sky.radiance(d) * (prev_pdf > 0 && sky_pdf > 0 ? power_heuristic(prev_pdf, sky_pdf) : 1.0f);
      if (sky.sun_up() && dot(d, sky.sun_direction()) >= sky.sun_cos_max())
        L += beta * sky.sun_radiance() * (prev_pdf > 0 ? power_heuristic(prev_pdf, sun_pdf) : 1.0f);
      break;
    }
    L += beta * s.material.emission;
    if (depth >= max_depth) break;
    const Frame frame(s.normal);
    const V3 wo = frame.to_local(d * -1);
    const V3 p = s.position + s.normal * kEpsilon;

    // Next event: the sun's disk.
    if (sky.sun_up()) {
      const V3 wi = sky.sun_frame().to_world(uniform_cone(rng.next(), rng.next(), sky.sun_cos_max()));
      const V3 li = frame.to_local(wi);
      const V3 f = eval(s.material, wo, li);
      if (max_component(f) > 0) {
        ++counts.shadow;
        if (!scene.occluded(p, wi, INFINITY))
          L += beta * f * sky.sun_radiance() *
               (transmittance(haze, p, wi) * power_heuristic(sun_pdf, pdf(s.material, wo, li)) / sun_pdf);
      }
    }
    // Next event: the sky, cosine-weighted about the normal.
    {
      const V3 li = cosine_hemisphere(rng.next(), rng.next());
      const V3 wi = frame.to_world(li);
      const float sky_pdf = li.z / kPi;
      const V3 f = eval(s.material, wo, li);
      if (wi.z > 0 && sky_pdf > 0 && max_component(f) > 0) {
        ++counts.shadow;
        if (!scene.occluded(p, wi, INFINITY))
          L += beta * f * sky.radiance(wi) *
               (transmittance(haze, p, wi) * power_heuristic(sky_pdf, pdf(s.material, wo, li)) / sky_pdf);
      }
    }
    // The surface chooses the next direction.
    BsdfSample bs;
    if (!sample(s.material, wo, rng.next(), rng.next(), rng.next(), bs)) break;
    beta *= bs.weight;
    prev_pdf = bs.pdf;
    prev_surface = true;
    prev_normal = s.normal;
    o = p;
    d = frame.to_world(bs.wi);
    if (depth >= 3) {
      const float survive = std::min(0.95f, max_component(beta));
      if (rng.next() >= survive) break;
      beta = beta / survive;
    }
  }
  return L;
}

Image trace(const RenderScene& scene, const Sky& sky, const Camera& camera, const TraceSettings& t, RayCounts* counts,
            const TileProgress& progress) {
  Image img;
  img.width = t.width, img.height = t.height;
  const std::size_t n = static_cast<std::size_t>(t.width) * t.height;
  img.beauty.assign(n, {}), img.normal.assign(n, {}), img.albedo.assign(n, {});
  img.depth.assign(n, INFINITY), img.id.assign(n, 0);
  const int tiles_x = (t.width + kTile - 1) / kTile, tiles_y = (t.height + kTile - 1) / kTile,
            tiles = tiles_x * tiles_y;
  const Lens lens(camera, t.width, t.height);
  std::atomic<int> done{0};
  std::mutex report;
  const auto caller = std::this_thread::get_id();
  tbb::parallel_for(0, tiles, [&](int tile) {
    // Denormals only slow the traversal down.
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
    RayCounts tile_counts;
    for (int y = y0; y < std::min(y0 + kTile, t.height); ++y)
      for (int x = x0; x < std::min(x0 + kTile, t.width); ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * t.width + x;
        V3 sum{0, 0, 0};
        for (int k = 0; k < t.spp; ++k) {
          Sampler rng(i, static_cast<std::uint64_t>(k));
          // The first sample goes through the pixel's centre, for clean data layers.
          const float jx = k == 0 ? 0.5f : rng.next(), jy = k == 0 ? 0.5f : rng.next();
          V3 o, d;
          lens.ray(static_cast<float>(x) + jx, static_cast<float>(y) + jy, o, d);
          Surface first;
          first.distance = -1;
          V3 l = radiance(scene, sky, o, d, rng, t.max_depth, tile_counts, k == 0 ? &first : nullptr, t.haze);
          if (!std::isfinite(l.x + l.y + l.z)) l = {0, 0, 0};
          sum += l;
          if (k == 0 && first.distance >= 0) {
            img.depth[i] = first.distance, img.normal[i] = first.normal, img.albedo[i] = first.material.albedo;
            img.id[i] = first.entity;
          }
        }
        img.beauty[i] = sum / static_cast<float>(t.spp);
      }
    const int finished = ++done;
    std::lock_guard<std::mutex> lock(report);
    if (counts) *counts += tile_counts;
    if (progress && std::this_thread::get_id() == caller) progress(finished, tiles);
  });
  if (progress) progress(tiles, tiles);
  return img;
}

}  // namespace render
