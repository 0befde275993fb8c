#include "render/path_tracer.h"

#include <pmmintrin.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <cmath>
#include <mutex>
#include <thread>
#include <tuple>
#include <vector>

#include "generate/cancel.h"
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
  const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
  const CirclePoint p = circle_point(u2);
  return Frame(direction).to_world({sin_theta * p.c, sin_theta * p.s, cos_theta});
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

// What a path is traced through, and where its rays are counted.
struct Tracing {
  const RenderScene& scene;
  const Sky& sky;
  const Haze& haze;
  float sun_pdf;  // of uniform_cone over the sun's disk
  Sampler& rng;
  RayCounts& counts;
  const StreetLights* lights = nullptr;
};

// A path between two vertices: the light gathered so far, the weight of what comes next,
// and how the direction it follows was chosen, which multiple importance sampling weighs
// against next-event estimation.
struct Path {
  V3 o, d;
  V3 L{0, 0, 0}, beta{1, 1, 1};
  float prev_pdf = 0;        // of the sampling that chose d; 0 for a camera ray
  bool prev_surface = true;  // d was chosen at a surface (sky next-event estimation ran there)
  bool prev_diffuse = false;  // d was drawn by a diffuse surface: it takes surfaces' spread light
  V3 prev_normal{0, 0, 1};
};

// Next event towards the sun from the haze the ray crosses before tmax, from a point drawn
// along the stretch in the haze with a density proportional to the light that reaches the
// ray there from the sun: the transmittance back along the ray, e^(-σt), times that
// towards the sun, which grows as the ray climbs, e^(σ d.z t / sun.z): together one
// exponential, e^(-kt), so the point is drawn exactly (Kulla and Fajardo's idea,
// "Importance sampling techniques for path tracing in participating media", 2012, for a
// light at infinity). Every ray through the haze sees the sun this way, where only those
// that scattered did, with weight one, at a point drawn by the transmittance back alone
// (nearest the ground, where the sun is dimmest): a grain in hazy skies. A path that
// scatters takes no next event at its scattering (its stretch's stood for it) and draws its
// new direction from the phase function, which meets the sun disk weighed against this.
// `u` places the point (the first of a stratified pair, render/sampling.h: a pixel's
// samples spread their points along the ray evenly, so shafts and the fade converge).
void add_sun_through_haze(const Tracing& t, Path& path, float tmax, float u) {
  auto [t0, t1] = in_haze(t.haze, path.o, path.d, tmax);
  const auto [u1, u2] = t.rng.next2();
  if (!(t1 > t0) || !t.sky.sun_up()) return;
  const float sigma = t.haze.density, k = sigma * (1 - path.d.z / t.sky.sun_direction().z), span = t1 - t0;
  // The point s past t0 and its density: e^(-ks) normalised over [0, span).
  float s, density;
  if (std::abs(k * span) < 1e-4f) {
    s = u * span, density = 1 / span;
  } else {
    const float mass = -std::expm1(-k * span) / k;  // the integral of e^(-ks) over [0, span)
    s = -std::log1p(-u * k * mass) / k;
    density = std::exp(-k * s) / mass;
  }
  if (!(s >= 0 && s <= span && density > 0)) return;
  const V3 p = path.o + path.d * (t0 + s);
  const V3 wi = t.sky.sun_frame().to_world(uniform_cone(u1, u2, t.sky.sun_cos_max()));
  const float phase = henyey_greenstein(dot(path.d, wi), t.haze.g);
  ++t.counts.shadow;
  if (!t.scene.occluded(p, wi, INFINITY))
    path.L += path.beta * t.sky.sun_radiance() *
              (sigma * std::exp(-sigma * s) / density * phase * transmittance(t.haze, p, wi) *
               power_heuristic(t.sun_pdf, phase) / t.sun_pdf);
}

// The light turns in the haze, ts along the path (no absorption: the weight stays): a new
// direction from the phase function (the sun's next event was its stretch's).
void scatter_in_haze(const Tracing& t, float ts, Path& path) {
  const V3 p = path.o + path.d * ts;
  const auto [u1, u2] = t.rng.next2();
  const V3 next = sample_henyey_greenstein(path.d, t.haze.g, u1, u2);
  path.prev_pdf = henyey_greenstein(dot(path.d, next), t.haze.g);
  path.prev_surface = false, path.prev_diffuse = false;
  path.o = p, path.d = next;
}

// The sky, and the sun where d meets its disk, weighted against the next-event estimation
// that could have found them.
void add_sky_seen(const Tracing& t, Path& path) {
  const float sky_pdf = path.prev_surface ? std::max(0.0f, dot(path.d, path.prev_normal)) / kPi : 0.0f;
  path.L += path.beta * t.sky.radiance(path.d) *
            (path.prev_pdf > 0 && sky_pdf > 0 ? power_heuristic(path.prev_pdf, sky_pdf) : 1.0f);
  if (t.sky.sun_up() && dot(path.d, t.sky.sun_direction()) >= t.sky.sun_cos_max())
    path.L += path.beta * t.sky.sun_radiance() * (path.prev_pdf > 0 ? power_heuristic(path.prev_pdf, t.sun_pdf) : 1.0f);
}

// A ray to the sky through the haze: the sky it sees through the haze is added with the
// haze's transmittance, and the path goes on scattered in the haze, its weight times the
// chance it scatters (1 - transmittance), at a distance ts drawn as free flight is, within
// the haze; false (the sky added whole) when it crosses none. Free flight chose one or the
// other, which made hazy skies a grain of pixels that saw the sky and pixels that did not.
bool scatters_before_the_sky(const Tracing& t, Path& path, float u, float& ts) {
  auto [t0, t1] = in_haze(t.haze, path.o, path.d, INFINITY);
  if (!(t1 > t0)) {
    add_sky_seen(t, path);
    return false;
  }
  const float scatters = -std::expm1(-t.haze.density * (t1 - t0));
  Path through = path;
  through.beta = path.beta * (1 - scatters);
  add_sky_seen(t, through);
  path.L = through.L;
  path.beta = path.beta * scatters;
  ts = t0 - std::log1p(-u * scatters) / t.haze.density;
  return true;
}

// The sun's next event from p up to its shadow ray: the direction drawn in the sun's disk
// and the light it adds if nothing is in the way (zero: no shadow ray to cast).
struct SunEvent {
  V3 direction, light;
};
SunEvent sun_event(const Tracing& t, const Material& m, const Frame& frame, V3 wo, V3 p, V3 beta) {
  if (!t.sky.sun_up()) return {{0, 0, 1}, {0, 0, 0}};
  const auto [u1, u2] = t.rng.next2();
  const V3 wi = t.sky.sun_frame().to_world(uniform_cone(u1, u2, t.sky.sun_cos_max()));
  const V3 li = frame.to_local(wi);
  const V3 f = eval(m, wo, li);
  if (max_component(f) <= 0) return {wi, {0, 0, 0}};
  return {wi, beta * f * t.sky.sun_radiance() *
                  (transmittance(t.haze, p, wi) * power_heuristic(t.sun_pdf, pdf(m, wo, li)) / t.sun_pdf)};
}

// Next event: the sun's disk, seen from p; returns the light it adds.
V3 sun_next_event(const Tracing& t, const Material& m, const Frame& frame, V3 wo, V3 p, const Path& path) {
  const SunEvent e = sun_event(t, m, frame, wo, p, path.beta);
  if (max_component(e.light) <= 0) return {0, 0, 0};
  ++t.counts.shadow;
  return t.scene.occluded(p, e.direction, INFINITY) ? V3{0, 0, 0} : e.light;
}

// Next event: the sky, cosine-weighted about the normal.
void add_sky_next_event(const Tracing& t, const Material& m, const Frame& frame, V3 wo, V3 p, Path& path) {
  const auto [u1, u2] = t.rng.next2();
  const V3 li = cosine_hemisphere(u1, u2);
  const V3 wi = frame.to_world(li);
  const float sky_pdf = li.z / kPi;
  const V3 f = eval(m, wo, li);
  if (wi.z > 0 && sky_pdf > 0 && max_component(f) > 0) {
    ++t.counts.shadow;
    if (!t.scene.occluded(p, wi, INFINITY))
      path.L += path.beta * f * t.sky.radiance(wi) *
                (transmittance(t.haze, p, wi) * power_heuristic(sky_pdf, pdf(m, wo, li)) / sky_pdf);
  }
}

// Next event: one street lamp, chosen among those that reach p (StreetLights::choose), a
// point light: no surface's sampling could find it, so it takes no multiple importance weight.
void add_lamp_next_event(const Tracing& t, const Material& m, const Frame& frame, V3 wo, V3 p, Path& path) {
  float chance = 0;
  const Lamp* lamp = t.lights->choose(p, t.rng.next(), chance);
  if (!lamp || chance <= 0) return;
  const V3 to = lamp->position - p;
  const float d2 = dot(to, to), d = std::sqrt(d2);
  const V3 wi = to / d;
  const V3 f = eval(m, wo, frame.to_local(wi));
  if (max_component(f) <= 0) return;
  ++t.counts.shadow;
  if (!t.scene.occluded(p, wi, d * (1 - 1e-4f)))
    // Nearer than a metre, as from a metre: a lamp's head is no point, and a wall beside
    // it lit as by one made grains of every path that bounced off it.
    path.L += path.beta * f * (lamp_intensity(*lamp, wi * -1, d) / (std::max(d2, 1.0f) * chance));
}

// The surface chooses the next direction, from p; false when it draws none.
bool follow_surface_sample(const Tracing& t, const Surface& s, const Frame& frame, V3 wo, V3 p, Path& path) {
  BsdfSample bs;
  const auto [u1, u2] = t.rng.next2();
  if (!sample(s.material, wo, u1, u2, t.rng.next(), bs)) return false;
  path.beta *= bs.weight;
  path.prev_pdf = bs.pdf;
  path.prev_surface = true;
  path.prev_diffuse = s.material.kind == Material::Diffuse;
  path.prev_normal = s.normal;
  path.o = p;
  path.d = frame.to_world(bs.wi);
  return true;
}

// Russian roulette: a path that carries little ends more often, and one that survives
// carries more, so the estimate stays unbiased.
bool survives_roulette(Sampler& rng, Path& path) {
  const float survive = std::min(0.95f, max_component(path.beta));
  if (rng.next() >= survive) return false;
  path.beta = path.beta / survive;
  return true;
}

// The density of a direction drawn uniformly in the sun's cone.
float sun_cone_pdf(const Sky& sky) { return 1 / (2 * kPi * (1 - sky.sun_cos_max())); }

// Where a surface's rays leave from, and the direction the light leaves it by, in its frame.
V3 leaving_point(const Surface& s) { return s.position + s.normal * kEpsilon; }

// A surface's own light: its emission, then (short of the last bounce) the next events
// towards the sun, the sky and a lamp. The sun's share is added to `sun` too where given;
// `known_sun` is that share where it was found already (a packet's shadow rays).
void add_surface_light(const Tracing& t, const Surface& s, int depth, int max_depth, Path& path, V3* sun = nullptr,
                       const V3* known_sun = nullptr) {
  // A ray a diffuse surface scattered takes a lit facade's window light spread over its
  // wall (render/facade.h): the same light, without the grain of the few rays that hit a pane.
  if (depth == 0 || !s.material.camera_only) path.L += path.beta * (path.prev_diffuse ? s.spread_emission : s.material.emission);
  if (depth >= max_depth) return;
  const Frame frame(s.normal);
  const V3 wo = frame.to_local(path.d * -1);
  const V3 p = leaving_point(s);
  const V3 from_sun = known_sun ? *known_sun : sun_next_event(t, s.material, frame, wo, p, path);
  path.L += from_sun;
  if (sun) *sun += from_sun;
  add_sky_next_event(t, s.material, frame, wo, p, path);
  if (t.lights && !t.lights->empty()) add_lamp_next_event(t, s.material, frame, wo, p, path);
}

// The bounce from a surface whose own light was added; false when the path ends there.
bool bounce_off_surface(const Tracing& t, const Surface& s, int depth, Path& path) {
  const Frame frame(s.normal);
  if (!follow_surface_sample(t, s, frame, frame.to_local(path.d * -1), leaving_point(s), path)) return false;
  return depth < 3 || survives_roulette(t.rng, path);
}

// A ray to a surface through the haze, as to the sky: the surface's own light, dimmed by the
// haze's transmittance, is added on every such ray, and the path goes on scattered in the
// haze (true, at ts) with the chance it scatters, or from the surface, its weight kept
// either way. Free flight added the surface's light only to the paths that reached it,
// with weight one: a grain of pixels that saw a building and pixels that saw only haze,
// wherever the haze half hid it. `u` draws ts as free flight does (u under the chance to
// scatter: ts short of the surface). `lit`: whether the surface's light was added.
bool scatters_before_the_surface(const Tracing& t, const Surface& s, int depth, int max_depth, Path& path, float u,
                                 float& ts, bool& lit, V3* sun) {
  auto [t0, t1] = in_haze(t.haze, path.o, path.d, s.distance);
  lit = t1 > t0;
  if (!lit) return false;
  const float scatters = -std::expm1(-t.haze.density * (t1 - t0));
  Path through = path;
  through.beta = path.beta * (1 - scatters);
  add_surface_light(t, s, depth, max_depth, through, sun);
  path.L = through.L;
  ts = t0 - std::log1p(-u) / t.haze.density;
  return u < scatters;
}

// A path's radiance from its camera ray (o, d), whose nearest surface `hit` and `s`
// tell (found by one ray or in a packet); as radiance(). `known_sun`: the sun's next event
// at that surface where it was found already (in clear air).
// `medium`, where given, is set to the light gathered after the camera ray scattered in
// the haze (the light scattered more than once; zero when it did not).
V3 radiance_after_camera_ray(const RenderScene& scene, const Sky& sky, V3 o, V3 d, bool hit, Surface s, Sampler& rng,
                             int max_depth, RayCounts& counts, const Haze& haze, V3* first_sun,
                             const V3* known_sun = nullptr, const StreetLights* lights = nullptr,
                             V3* medium = nullptr) {
  V3 scattered_from{0, 0, 0};
  bool scattered = false;
  const Tracing t{scene, sky, haze, sun_cone_pdf(sky), rng, counts, lights};
  Path path{o, d};
  ++counts.camera;
  for (int depth = 0;; ++depth) {
    if (depth > 0) {
      ++counts.bounce;
      hit = scene.intersect(path.o, path.d, INFINITY, s);
    }
    // Past the first surface a smooth coat is taken rougher (path regularisation, Kaplanyan
    // and Dachsbacher 2013): the sun seen in glass from the street otherwise comes in a few
    // paths of great weight, white grains on shaded asphalt beside a glass tower.
    if (hit && depth > 0 && s.material.kind == Material::Glossy)
      s.material.roughness = std::max(s.material.roughness, 0.3f);
    V3* sun = depth == 0 ? first_sun : nullptr;
    bool lit = false;  // the surface's own light added already, through the haze
    if (haze.density > 0) {
      // One stratified pair a vertex (render/sampling.h): where along the ray the sun is
      // sought, and where the path scatters.
      const auto [u_sun, u_flight] = rng.next2();
      if (depth < max_depth) {
        const V3 before = path.L;
        add_sun_through_haze(t, path, hit ? s.distance : INFINITY, u_sun);
        if (sun) *sun += path.L - before;
      }
      float ts = 0;
      if (!hit ? scatters_before_the_sky(t, path, u_flight, ts)
               : scatters_before_the_surface(t, s, depth, max_depth, path, u_flight, ts, lit, sun)) {
        if (depth >= max_depth) break;
        if (depth == 0) scattered = true, scattered_from = path.L;
        scatter_in_haze(t, ts, path);
        continue;
      }
      if (!hit) break;
    }
    if (!hit) {
      add_sky_seen(t, path);
      break;
    }
    if (!lit) add_surface_light(t, s, depth, max_depth, path, sun, depth == 0 ? known_sun : nullptr);
    if (depth >= max_depth || !bounce_off_surface(t, s, depth, path)) break;
  }
  if (medium) *medium = scattered ? path.L - scattered_from : V3{0, 0, 0};
  return path.L;
}

// The sun's next event at the surface `s` a camera ray of direction d met in clear air, up
// to its shadow ray: the light radiance() adds to `first_sun` there when that ray is
// unblocked.
struct SunShadowRay {
  V3 origin, direction, light;  // light zero: no ray to cast
};
SunShadowRay first_hit_sun(const RenderScene& scene, const Sky& sky, V3 d, const Surface& s, Sampler& rng) {
  const Haze clear;
  RayCounts uncounted;
  const Tracing t{scene, sky, clear, sun_cone_pdf(sky), rng, uncounted};
  const Frame frame(s.normal);
  const V3 p = leaving_point(s);
  const SunEvent e = sun_event(t, s.material, frame, frame.to_local(d * -1), p, {1, 1, 1});
  return {p, e.direction, e.light};
}

}  // namespace

V3 radiance(const RenderScene& scene, const Sky& sky, V3 o, V3 d, Sampler& rng, int max_depth, RayCounts& counts,
            Surface* first, const Haze& haze, V3* first_sun, const StreetLights* lights) {
  Surface s;
  const bool hit = scene.intersect(o, d, INFINITY, s);
  if (first && hit) *first = s;
  return radiance_after_camera_ray(scene, sky, o, d, hit, s, rng, max_depth, counts, haze, first_sun, nullptr, lights);
}

float haze_transmittance(const Haze& h, V3 o, V3 d, float t) {
  if (h.density <= 0) return 1;
  auto [t0, t1] = in_haze(h, o, d, t);
  return t1 > t0 ? std::exp(-h.density * (t1 - t0)) : 1.0f;
}

float Haze::air_transmittance(V3 o, V3 d, float t) const {
  if (air_density <= 0) return 1;
  // The integral of air_density e^(-(z - air_ground) / H) along z = o.z + d.z s, s in [0, t].
  const float H = kAirScaleHeight, k = d.z / H;
  const float at_o = air_density * std::exp(-(o.z - air_ground) / H);
  float length;
  if (std::abs(k * t) < 1e-4f) {
    length = t;
  } else {
    if (!std::isfinite(t)) return k > 0 ? std::exp(-at_o / k) : 0;
    length = -std::expm1(-k * t) / k;
  }
  return std::exp(-at_o * length);
}

void trace_camera_packet(const RenderScene& scene, const Sky& sky, const Lens& lens, int x, int y, std::size_t pixel,
                         int k0, int n, bool with_sun, std::vector<Sampler>& rngs, CameraPacket& p, RayCounts& counts,
                         const Haze& air) {
  p.n = n;
  rngs.clear();
  for (int j = 0; j < n; ++j) {
    const auto k = static_cast<std::uint64_t>(k0 + j);
    Sampler& rng = rngs.emplace_back(pixel, k);
    // The first sample goes through the pixel's centre, for clean data layers.
    float jx, jy;
    pixel_jitter(k, jx, jy);
    // A thin lens draws its point after the pixel's (and the first sample takes the
    // lens's centre too); a pinhole draws nothing, so its images stay as they were.
    // It draws its slot all the same, so that the slots after it stay the same for every
    // sample and each remains one stratified sequence (render/sampling.h).
    float lu = 0.5f, lv = 0.5f;
    if (lens.thin_lens()) {
      const auto [u, v] = rng.next2();
      if (k > 0) lu = u, lv = v;
    }
    lens.ray(static_cast<float>(x) + jx, static_cast<float>(y) + jy, lu, lv, p.o[j], p.d[j]);
  }
  scene.intersect_packet(p.o, p.d, n, p.hits, p.found);
  for (int j = 0; j < n; ++j) {
    p.fade[j] = 1, p.inscattered[j] = {0, 0, 0};
    if (!p.found[j] || air.density > 0 || air.air_density <= 0) continue;
    p.fade[j] = air.air_transmittance(p.o[j], p.d[j], p.hits[j].distance);
    // The light scattered in is the horizon's sky in the ray's direction.
    const V3 horizon = normalize(V3{p.d[j].x, p.d[j].y, std::max(std::abs(p.d[j].z), 0.05f)});
    p.inscattered[j] = sky.radiance(horizon) * (1 - p.fade[j]);
  }
  if (!with_sun) return;
  V3 from[CameraPacket::kSize], towards[CameraPacket::kSize];
  int ray_of[CameraPacket::kSize], rays = 0;
  for (int j = 0; j < n; ++j) {
    p.sun[j] = {0, 0, 0};
    if (!p.found[j]) continue;
    const SunShadowRay r = first_hit_sun(scene, sky, p.d[j], p.hits[j], rngs[j]);
    p.sun[j] = r.light;
    if (max_component(r.light) <= 0) continue;
    from[rays] = r.origin, towards[rays] = r.direction, ray_of[rays++] = j;
  }
  bool blocked[CameraPacket::kSize];
  scene.occluded_packet(from, towards, rays, blocked);
  counts.shadow += static_cast<std::uint64_t>(rays);
  for (int q = 0; q < rays; ++q)
    if (blocked[q]) p.sun[ray_of[q]] = {0, 0, 0};
}

Film::Film(int width, int height) {
  layers.width = width, layers.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  layers.normal.assign(n, {}), layers.albedo.assign(n, {});
  layers.depth.assign(n, INFINITY), layers.id.assign(n, 0);
  sum.assign(n, {}), albedo_sum.assign(n, {}), luminance_squares.assign(n, 0);
  sun_sum.assign(n, {}), even_sum.assign(n, {}), even_albedo_sum.assign(n, {}), even_sun_sum.assign(n, {});
}

namespace {

std::vector<V3> mean_of(const std::vector<V3>& sum, float count) {
  std::vector<V3> mean(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) mean[i] = sum[i] / count;
  return mean;
}

}  // namespace

Image Film::image() const {
  Image img = layers;
  const std::size_t n = sum.size();
  img.beauty.assign(n, {}), img.variance.assign(n, 0), img.mean_albedo.assign(n, {}), img.first_sun.assign(n, {});
  if (samples == 0) return img;
  const float count = static_cast<float>(samples);
  for (std::size_t i = 0; i < n; ++i) {
    img.beauty[i] = sum[i] / count, img.mean_albedo[i] = albedo_sum[i] / count, img.first_sun[i] = sun_sum[i] / count;
    const double mean = luminance(img.beauty[i]);
    img.variance[i] = static_cast<float>(std::max(0.0, luminance_squares[i] / samples - mean * mean) / samples);
  }
  if (!inscatter_sum.empty()) {
    img.inscatter = mean_of(inscatter_sum, count), img.seen.resize(n);
    for (std::size_t i = 0; i < n; ++i) img.seen[i] = seen_sum[i] / count;
  }
  if (samples < 2) return img;
  const int even = (samples + 1) / 2, odd = samples / 2;
  Image::Half& e = img.halves[0];
  Image::Half& o = img.halves[1];
  e.samples = even, o.samples = odd;
  for (Image::Half* h : {&e, &o}) h->beauty.resize(n), h->albedo.resize(n), h->sun.resize(n);
  const float ne = static_cast<float>(even), no = static_cast<float>(odd);
  for (std::size_t i = 0; i < n; ++i) {
    e.beauty[i] = even_sum[i] / ne, e.albedo[i] = even_albedo_sum[i] / ne, e.sun[i] = even_sun_sum[i] / ne;
    o.beauty[i] = (sum[i] - even_sum[i]) / no, o.albedo[i] = (albedo_sum[i] - even_albedo_sum[i]) / no;
    o.sun[i] = (sun_sum[i] - even_sun_sum[i]) / no;
  }
  if (!inscatter_sum.empty()) {
    e.inscatter = mean_of(even_inscatter_sum, ne), o.inscatter.resize(n);
    for (std::size_t i = 0; i < n; ++i) o.inscatter[i] = (inscatter_sum[i] - even_inscatter_sum[i]) / no;
  }
  return img;
}

void add_samples(Film& film, const RenderScene& scene, const Sky& sky, const Camera& camera, const TraceSettings& t,
                 RayCounts* counts, const TileProgress& progress) {
  const int width = film.layers.width, height = film.layers.height;
  const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile, tiles = tiles_x * tiles_y;
  const int first = film.samples;
  Image& img = film.layers;
  const bool hazy = t.haze.density > 0;
  if (hazy && film.inscatter_sum.empty()) {
    const std::size_t n = film.sum.size();
    film.inscatter_sum.assign(n, {}), film.even_inscatter_sum.assign(n, {}), film.seen_sum.assign(n, 0);
  }
  const Lens lens(camera, width, height);
  std::atomic<int> done{0};
  std::mutex report;
  const auto caller = std::this_thread::get_id();
  // Checked at every pixel: a tile of many samples a pixel takes seconds, and a job must
  // stop within one of being cancelled (generate/cancel.h).
  const exacity::CancelCheck cancel;
  tbb::parallel_for(0, tiles, [&](int tile) {
    // Denormals only slow the traversal down.
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
    RayCounts tile_counts;
    std::vector<Sampler> rngs;
    rngs.reserve(CameraPacket::kSize);
    CameraPacket packet;
    // The first surfaces' sun in the packet, where a camera ray's first event is its surface
    // (clear air) and the path goes on from it.
    const bool sun_first = t.haze.density <= 0 && t.max_depth > 0;
    for (int y = y0; y < std::min(y0 + kTile, height); ++y)
      for (int x = x0; x < std::min(x0 + kTile, width); ++x) {
        cancel.check();
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        V3 sum = film.sum[i], albedo = film.albedo_sum[i];
        V3 sun = film.sun_sum[i], even_sum = film.even_sum[i], even_albedo = film.even_albedo_sum[i],
           even_sun = film.even_sun_sum[i];
        double squares = film.luminance_squares[i];
        V3 inscatter{0, 0, 0}, even_inscatter{0, 0, 0};
        float seen = 0;
        // The camera rays in packets, each path on alone from its first surface.
        for (int k0 = first, n = 0; k0 < first + t.spp; k0 += n) {
          n = CameraPacket::size_from(k0, first + t.spp);
          trace_camera_packet(scene, sky, lens, x, y, i, k0, n, sun_first, rngs, packet, tile_counts, t.haze);
          for (int j = 0; j < n; ++j) {
            const int k = k0 + j;
            const Surface* first_hit = packet.found[j] ? &packet.hits[j] : nullptr;
            V3 from_sun{0, 0, 0}, medium{0, 0, 0};
            V3 l = radiance_after_camera_ray(scene, sky, packet.o[j], packet.d[j], packet.found[j], packet.hits[j],
                                             rngs[j], t.max_depth, tile_counts, t.haze, &from_sun,
                                             sun_first ? &packet.sun[j] : nullptr, t.lights, &medium);
            if (!std::isfinite(l.x + l.y + l.z)) l = from_sun = medium = {0, 0, 0};
            V3 a = first_hit ? first_hit->material.albedo : V3{1, 1, 1};
            if (hazy) {
              inscatter += medium;
              if (k % 2 == 0) even_inscatter += medium;
              if (first_hit) seen += haze_transmittance(t.haze, packet.o[j], packet.d[j], first_hit->distance);
            }
            packet.through_air(j, l, a, from_sun);
            sum += l, albedo += a, sun += from_sun;
            if (k % 2 == 0) even_sum += l, even_albedo += a, even_sun += from_sun;
            squares += static_cast<double>(luminance(l)) * luminance(l);
            if (k == 0 && first_hit) {
              img.depth[i] = first_hit->distance, img.normal[i] = first_hit->normal;
              img.albedo[i] = first_hit->material.albedo, img.id[i] = first_hit->entity;
            }
          }
        }
        film.sum[i] = sum, film.albedo_sum[i] = albedo, film.luminance_squares[i] = squares;
        film.sun_sum[i] = sun, film.even_sum[i] = even_sum, film.even_albedo_sum[i] = even_albedo;
        film.even_sun_sum[i] = even_sun;
        if (hazy)
          film.inscatter_sum[i] += inscatter, film.even_inscatter_sum[i] += even_inscatter, film.seen_sum[i] += seen;
      }
    const int finished = ++done;
    std::lock_guard<std::mutex> lock(report);
    if (counts) *counts += tile_counts;
    if (progress && std::this_thread::get_id() == caller) progress(finished, tiles);
  });
  film.samples += t.spp;
  if (progress) progress(tiles, tiles);
}

Image trace(const RenderScene& scene, const Sky& sky, const Camera& camera, const TraceSettings& t, RayCounts* counts,
            const TileProgress& progress) {
  Film film(t.width, t.height);
  add_samples(film, scene, sky, camera, t, counts, progress);
  return film.image();
}

}  // namespace render
