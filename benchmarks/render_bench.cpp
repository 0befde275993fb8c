// The renderer at scale: Embree scene build time and memory for a city, raw rtcIntersect1
// throughput beside the path tracer's own ray rate on the same scene (their ratio is the
// figure), and the time of a still. Measures; asserts nothing.
//
//   build/release/benchmarks/exacity_render_bench [SKETCH] [--size WxH] [--spp N] [--threads N] [--models LIBRARY]
//                                                 [--camera SPEC]
//
// With --denoise-figure, the denoiser's figure instead (render/README.md, Denoising): the
// default view at --spp (16) raw and denoised, and raw at 4x and 16x the samples, each
// against a --reference (1024) sample render of the same view, as display_rmse and the
// seconds each took.

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "generate/pipeline.h"
#include "render/denoise.h"
#include "render/image_error.h"
#include "render/path_tracer.h"
#include "render/render.h"
#include "render/sampling.h"
#include "render/scene.h"

using namespace render;
namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

struct BenchOptions {
  fs::path sketch_path = fs::path(EXACITY_SOURCE_DIR) / "benchmarks" / "city_10km.geojson", models;
  int width = 1920, height = 1080, spp = 64, threads = 0;
  bool denoise_figure = false;
  std::string camera;  // --camera SPEC (render/camera.h), city coordinates; default: default_camera
  int reference_spp = 1024;
};

BenchOptions parse_options(int argc, char** argv) {
  BenchOptions o;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--size") && i + 1 < argc) std::sscanf(argv[++i], "%dx%d", &o.width, &o.height);
    else if (!std::strcmp(argv[i], "--spp") && i + 1 < argc) o.spp = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) o.threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--models") && i + 1 < argc) o.models = argv[++i];
    else if (!std::strcmp(argv[i], "--denoise-figure")) o.denoise_figure = true;
    else if (!std::strcmp(argv[i], "--camera") && i + 1 < argc) o.camera = argv[++i];
    else if (!std::strcmp(argv[i], "--reference") && i + 1 < argc) o.reference_spp = std::atoi(argv[++i]);
    else o.sketch_path = argv[i];
  }
  return o;
}

exacity::City load_and_build_city(const BenchOptions& o) {
  exacity::Sketch sketch = exacity::load_sketch(o.sketch_path);
  if (!o.models.empty()) sketch.models = fs::absolute(o.models);

  auto t = std::chrono::steady_clock::now();
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  exacity::City city = exacity::build_city(sketch, clock);
  std::printf("city %s: %zu buildings, built in %.1f s; peak memory %.0f MiB\n", o.sketch_path.filename().c_str(),
              city.buildings.size(), seconds_since(t), exacity::peak_resident_mib());
  return city;
}

void report_scene(const RenderScene& scene, double build_s, double rss_before) {
  int culled = 0, simple = 0;
  for (const auto& tl : scene.tiles) culled += tl.level == "culled", simple += tl.level == "simple";
  std::printf("scene: %.2f s, %zu triangles, %zu instances, %zu tiles (%d culled, %d simple); Embree held %.0f MiB at "
              "most; process peak %.0f MiB (%.0f before the scene)\n",
              build_s, scene.triangles, scene.instances, scene.tiles.size(), culled, simple,
              static_cast<double>(scene.embree_peak_bytes()) / (1 << 20), exacity::peak_resident_mib(), rss_before);
}

struct Rays {
  std::vector<V3> origins, directions;
};

// One camera ray and one random upward bounce ray per pixel, the same kinds of rays the
// path tracer casts.
Rays camera_and_bounce_rays(const RenderScene& scene, const Camera& camera, int width, int height) {
  Rays rays;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      V3 o, d;
      camera.ray(x + 0.5f, y + 0.5f, width, height, o, d);
      rays.origins.push_back(o), rays.directions.push_back(d);
      Surface s;
      if (scene.intersect(o, d, INFINITY, s)) {
        Sampler rng(static_cast<std::uint64_t>(y) * width + x, 0);
        rays.origins.push_back(s.position + s.normal * 1e-3f);
        rays.directions.push_back(Frame(s.normal).to_world(cosine_hemisphere(rng.next(), rng.next())));
      }
    }
  return rays;
}

// Raw Embree, rtcIntersect1 alone: passes over the set until a second has gone, so thread
// start-up does not count. Returns rays per second.
double raw_ray_rate(const RenderScene& scene, const Rays& rays) {
  const std::vector<V3>& origins = rays.origins;
  const std::vector<V3>& directions = rays.directions;
  std::atomic<std::size_t> hits{0};
  std::size_t cast = 0;
  auto t = std::chrono::steady_clock::now();
  while (seconds_since(t) < 1.0) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, origins.size(), 4096), [&](const auto& r) {
      std::size_t h = 0;
      for (std::size_t i = r.begin(); i < r.end(); ++i) h += scene.raw_intersect(origins[i], directions[i]);
      hits += h;
    });
    cast += origins.size();
  }
  const double raw_s = seconds_since(t);
  const double raw_rate = static_cast<double>(cast) / raw_s;
  std::printf("raw rtcIntersect1: %zu rays (camera rays and one bounce each) in %.2f s: %.2f M rays/s\n", cast, raw_s,
              raw_rate / 1e6);
  return raw_rate;
}

void time_still(const RenderScene& scene, const Sky& sky, const Camera& camera, const BenchOptions& o, double raw_rate) {
  const int width = o.width, height = o.height, spp = o.spp;
  RayCounts rays;
  auto t = std::chrono::steady_clock::now();
  Image img = trace(scene, sky, camera, TraceSettings{width, height, spp}, &rays);
  const double still_s = seconds_since(t);
  const double all = static_cast<double>(rays.camera + rays.bounce + rays.shadow);
  const double traced = static_cast<double>(rays.camera + rays.bounce);
  std::printf("path tracer, %dx%d at %d spp: %.1f s; %.0f M rays (camera %.0f M, bounce %.0f M, shadow %.0f M): "
              "%.2f M rays/s, %.0f%% of raw; camera and bounce rays alone %.2f M/s, %.0f%% of raw\n",
              width, height, spp, still_s, all / 1e6, static_cast<double>(rays.camera) / 1e6,
              static_cast<double>(rays.bounce) / 1e6, static_cast<double>(rays.shadow) / 1e6, all / still_s / 1e6,
              100 * all / still_s / raw_rate, traced / still_s / 1e6, 100 * traced / still_s / raw_rate);
}

// RMSE against the reference of raw and denoised renders (render/image_error.h).
void denoise_figure(const RenderScene& scene, const Sky& sky, const Camera& camera, const BenchOptions& o) {
  auto t = std::chrono::steady_clock::now();
  const Image reference = trace(scene, sky, camera, TraceSettings{o.width, o.height, o.reference_spp});
  std::printf("reference: %dx%d at %d spp, %.1f s\n", o.width, o.height, o.reference_spp, seconds_since(t));
  for (int spp : {o.spp, 4 * o.spp, 16 * o.spp}) {
    t = std::chrono::steady_clock::now();
    const Image raw = trace(scene, sky, camera, TraceSettings{o.width, o.height, spp});
    const double trace_s = seconds_since(t);
    std::printf("%4d spp raw:      RMSE %.4f (%.2f s)\n", spp, display_rmse(raw, reference), trace_s);
    if (spp != o.spp) continue;
    t = std::chrono::steady_clock::now();
    const Image filtered = denoise_render(raw, scene, sky, camera, Haze{});
    std::printf("%4d spp denoised: RMSE %.4f (%.2f s + %.2f s denoising)\n", spp, display_rmse(filtered, reference),
                trace_s, seconds_since(t));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const BenchOptions o = parse_options(argc, argv);
  std::unique_ptr<tbb::global_control> limit;
  if (o.threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
  exacity::City city = load_and_build_city(o);

  const Sky sky(200, 40);
  Camera camera = o.camera.empty() ? default_camera(city) : Camera::parse(o.camera, 45);
  SceneOptions options;
  options.view = &camera;
  options.aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
  const double before = exacity::peak_resident_mib();
  auto t = std::chrono::steady_clock::now();
  RenderScene scene(city, sky.sun_direction(), options);
  report_scene(scene, seconds_since(t), before);
  camera = scene.to_scene(camera);

  if (o.denoise_figure) {
    denoise_figure(scene, sky, camera, o);
    return 0;
  }
  const double raw_rate = raw_ray_rate(scene, camera_and_bounce_rays(scene, camera, o.width, o.height));
  time_still(scene, sky, camera, o, raw_rate);
  std::printf("peak memory %.0f MiB\n", exacity::peak_resident_mib());
  return 0;
}
