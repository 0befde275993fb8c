#include "render/render.h"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <optional>

#include <sys/resource.h>

#include "generate/cancel.h"
#include "generate/gis/projection.h"
#include "render/denoise.h"
#include "render/image_io.h"
#include "render/night.h"
#include "render/pass_budget.h"
#include "render/path_tracer.h"
#include "render/scene.h"
#include "render/white_balance.h"

namespace render {
namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The process's CPU seconds (user and system, every thread): on a shared machine the wall
// time says more about the others' load than about the work.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

void line(Rgb8& img, V3 colour, float x0, float y0, float x1, float y1, int thickness) {
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
  for (int i = 0; i <= steps; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(steps);
    const int x = static_cast<int>(std::lround(x0 + (x1 - x0) * t)),
              y = static_cast<int>(std::lround(y0 + (y1 - y0) * t));
    for (int dy = -thickness / 2; dy <= thickness / 2; ++dy)
      for (int dx = -thickness / 2; dx <= thickness / 2; ++dx) img.set(x + dx, y + dy, colour);
  }
}

void disc(Rgb8& img, V3 colour, float cx, float cy, float r) {
  for (int y = static_cast<int>(cy - r); y <= static_cast<int>(cy + r); ++y)
    for (int x = static_cast<int>(cx - r); x <= static_cast<int>(cx + r); ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) img.set(x, y, colour);
}

// What the hour makes of the still (render/night.h): its sun, how far into the night it
// is, and how many stops the camera opens up by for it.
struct Daylight {
  float sun_azimuth, sun_elevation;
  float night = 0;
  float stops = 0;
};
// A night's exposure: as many more stops as bring a street under its lamps to about a
// sunlit street's brightness.
constexpr float kNightStops = 6;
// The lamps' heads' radiance (their light is kLampIntensity, render/night.h), the lit
// windows' radiance and share.
constexpr float kLampHeadRadiance = 40;
constexpr float kWindowLight = 0.015f, kLitWindows = 0.35f;

Daylight daylight(const RenderRequest& request, const SolarPlace& place) {
  if (request.time_of_day < 0) return {request.sun_azimuth, request.sun_elevation};
  const SunPosition sun = sun_at_hour(request.time_of_day, place);
  const float night = night_share(sun.elevation);
  return {sun.azimuth, sun.elevation, night, kNightStops * night};
}

// The still's scene: culled and simplified outside what its camera sees close up; at
// night, its lamps and lit windows.
SceneOptions culled_to_view(const RenderRequest& request, const Daylight& day) {
  SceneOptions options;
  if (day.night > 0) {
    options.lit_windows = kLitWindows * day.night;
    options.window_light = V3{1, 1, 1} * kWindowLight;
    options.lamp_intensity = kLampIntensity, options.lamp_head_radiance = kLampHeadRadiance;
  }
  options.view = &request.camera;
  options.aspect = static_cast<float>(request.width) / static_cast<float>(request.height);
  options.mark_mapped = request.mark_mapped;
  options.landscape_trees = request.landscape_trees;
  return options;
}

// The overview's and the minimap's scene: the whole city, nothing culled.
SceneOptions whole_city(const RenderRequest& request) {
  SceneOptions all;
  all.aspect = 1;
  all.mark_mapped = request.mark_mapped;
  return all;
}

// Clear air unless a visibility is asked for; the haze fills the 500 m over the lowest ground.
// Clear air has its aerial perspective (Haze::air_density) at request.clear_visibility.
Haze haze_layer(const RenderRequest& request, const RenderScene& scene) {
  Haze haze;
  if (request.haze_visibility > 0)
    haze = {Haze::density_for_visibility(request.haze_visibility), scene.ground + 500, 0.7f};
  else if (request.clear_visibility > 0)
    haze.air_density = Haze::density_for_visibility(request.clear_visibility), haze.air_ground = scene.ground;
  return haze;
}

// The exposure and white balance asked for, `metered` stops brighter, applied on the way to
// the 8-bit images only: the EXR keeps linear radiance (render/README.md, Tone mapping).
Rgb8 tone_mapped(const Image& image, const RenderRequest& request, float metered = 0) {
  return tone_map(image, request.exposure * std::exp2(request.exposure_ev + metered),
                  white_balance_gains(request.white_balance_k));
}

// The filter when asked for (render/README.md, Denoising), with the primary layer's rays
// through the same scene, camera and air the image was traced with.
Image finished(Image image, const RenderScene& scene, const Sky& sky, const Camera& camera, const Haze& haze,
               const RenderRequest& request) {
  return request.denoise ? denoise_render(std::move(image), scene, sky, camera, haze) : image;
}

// The still's writing time (its EXR and PNG), foretold from a band of an eighth of the rows
// (32 at least) written beside it and removed: the writers' work is about the same for every
// row, and the band is written under the machine's load of the moment.
double write_seconds(const Image& image, const RenderRequest& request, float stops) {
  const int rows = std::min(image.height, std::max(32, image.height / 8));
  if (rows == 0 || request.still.empty()) return 0;
  Image band;
  band.width = image.width, band.height = rows;
  const auto n = static_cast<std::ptrdiff_t>(image.width) * rows;
  band.beauty.assign(image.beauty.begin(), image.beauty.begin() + n);
  band.depth.assign(image.depth.begin(), image.depth.begin() + n);
  band.normal.assign(image.normal.begin(), image.normal.begin() + n);
  band.albedo.assign(image.albedo.begin(), image.albedo.begin() + n);
  band.id.assign(image.id.begin(), image.id.begin() + n);
  const fs::path probe = fs::path(request.still).replace_filename("." + request.still.stem().string() + ".write-probe.png");
  const auto start = std::chrono::steady_clock::now();
  try {
    write_exr(band, fs::path(probe).replace_extension(".exr"));
    write_png(tone_mapped(band, request, stops), probe);
  } catch (const std::exception&) {
    // Writing the still itself will say what is wrong with its folder.
  }
  const double seconds = seconds_since(start) * image.height / rows;
  std::error_code ignored;
  fs::remove(probe, ignored), fs::remove(fs::path(probe).replace_extension(".exr"), ignored);
  return seconds;
}

struct Still {
  Image image;
  Rgb8 png;  // tone-mapped; the minimap is set into it before it is written
  RayCounts rays;
  int passes = 0, samples = 0;  // samples a pixel, over the passes
  double seconds = 0, denoise_seconds = 0;  // tracing, denoising
  double cpu_s = 0, denoise_cpu_s = 0;      // the same in CPU seconds
  double write_foretold_s = 0;              // with a budget: the writing it kept time for
  double denoise_foretold_s = 0;            // with a budget: the denoiser's time as last foretold
  double filter_foretold_s = 0;             // of which the filter's
  double primary_layer_s = 0;               // of denoise_seconds, the primary layer's
  bool denoised = false;
  int primary_rays = 0;  // the denoiser's primary layer's, a pixel
  float metered_ev = 0;
};

// The denoiser's time for `samples` path samples a pixel, from the filter's time on bands
// (filter_seconds) and a path sample's. Measured on the town's orbit at 960x540 (release,
// the machine shared), the whole image's filter took 0.8 to 2.3 times the bands' forecast,
// 1.3 in the median: the coarse levels' taps that fall outside a band of 34 rows are not
// computed there (about a fifth of the taps), and a band's layers fit in the cache where
// the image's do not. The primary layer's rays took 0.3 to 0.6 of a path sample each
// there (a third on the Cycles comparison's view): half is kept.
constexpr double kFilterOverBands = 1.3, kPrimaryRayOverSample = 0.5;
double denoise_seconds(const RenderRequest& request, const Haze& haze, int samples, double filter_s, double sample_s) {
  if (!request.denoise) return 0;
  const bool layer = haze.density <= 0 && samples >= 2;  // denoise_render adds none to one sample
  return filter_s * kFilterOverBands + (layer ? sample_s * primary_rays(samples) * kPrimaryRayOverSample : 0);
}

// Passes of request.spp samples: one, or as many as the time budget holds (run_passes,
// render/pass_budget.h). The budget is the whole command's, from request.started. The
// image depends only on the passes' sizes (Film), and the report records its samples and
// passes.
Still render_still(const RenderScene& scene, const Sky& sky, const Camera& camera, const RenderRequest& request,
                   const Daylight& day, const Haze& haze, const RenderProgress& progress, const StreetLights* lights) {
  Still still;
  const bool budget = request.time_budget_s > 0;
  TraceSettings settings{request.width, request.height, request.spp};
  settings.haze = haze;
  settings.lights = lights;
  Film film(request.width, request.height);
  auto trace_pass = [&](int samples) {
    settings.spp = samples;
    const double pass_cpu = cpu_seconds();
    add_samples(film, scene, sky, camera, settings, &still.rays, [&](int done, int all) {
      if (!progress) return;
      if (!budget) return progress("still", static_cast<double>(done) / all);
      progress("still", std::clamp(seconds_since(request.started) / request.time_budget_s, 0.0, 1.0));
    });
    still.cpu_s += cpu_seconds() - pass_cpu;
  };
  // The filter's time and the writing's, measured on bands once the first pass has given
  // an image. The filter's is measured again once the film has two halves: on one sample's
  // two equal halves the filter finds no variance and took a third of its time on two
  // (town orbit, 960x540: 0.7 s foretold against 1.8 s).
  std::optional<double> filter_s, write_s;
  bool filter_timed_on_halves = false;
  auto denoiser_s = [&](int samples, double per_sample_s) {
    if (request.denoise && (!filter_s || (!filter_timed_on_halves && film.samples >= 2))) {
      filter_s = filter_seconds(film.image(), haze.density <= 0);
      filter_timed_on_halves = film.samples >= 2;
    }
    return denoise_seconds(request, haze, samples, filter_s.value_or(0), per_sample_s);
  };
  auto writing_s = [&] {
    if (!write_s) write_s = write_seconds(film.image(), request, day.stops);
    return *write_s;
  };
  // The filter alone, for when the primary layer does not fit (PassBudget::least_finish_s).
  auto filter_only_s = [&](int, double per_sample_s) { return denoiser_s(1, per_sample_s); };
  if (budget) {
    PassBudget plan{request.time_budget_s, request.spp, denoiser_s, writing_s, filter_only_s};
    const Passes passes = run_passes(plan, trace_pass, [&] { return seconds_since(request.started); });
    still.passes = passes.passes, still.seconds = passes.traced_s;
    still.write_foretold_s = writing_s();
    if (passes.least_s > request.time_budget_s * 1.1)
      std::fprintf(stderr,
                   "exacity: note: --time %g is less than this command needs on this machine now: the city, its scene "
                   "and one sample a pixel took %.1f s, writing takes about %.1f s more; it writes that sample, not denoised\n",
                   request.time_budget_s, passes.least_s - still.write_foretold_s, still.write_foretold_s);
  } else {
    const auto start = std::chrono::steady_clock::now();
    trace_pass(request.spp);
    still.passes = 1, still.seconds = seconds_since(start);
  }
  still.samples = film.samples;
  const auto filtering = std::chrono::steady_clock::now();
  const double filtering_cpu = cpu_seconds();
  Image image = film.image();
  if (request.denoise) {
    // Over the budget already: the filter without its primary layer, or none.
    DenoiseSettings denoising;
    const double remaining = request.time_budget_s - seconds_since(request.started) - still.write_foretold_s;
    if (budget) {
      still.denoise_foretold_s = denoiser_s(film.samples, still.seconds / film.samples);
      still.filter_foretold_s = denoiser_s(1, 0);
      // One sample is filtered as one estimate, not the two halves the passes were planned for.
      if (film.samples == 1 && remaining > 0)
        still.filter_foretold_s = still.denoise_foretold_s =
            denoise_seconds(request, haze, 1, filter_seconds(image, false, true), 0);
    }
    if (budget && still.denoise_foretold_s > remaining) denoising.primary_rays = 0;
    still.denoised = !budget || still.filter_foretold_s <= remaining;
    if (still.denoised)
      image = denoise_render(std::move(image), scene, sky, camera, haze, denoising, &still.primary_layer_s);
    still.primary_rays = image.extra.samples;
  }
  still.image = std::move(image);
  still.denoise_seconds = seconds_since(filtering);
  still.denoise_cpu_s = cpu_seconds() - filtering_cpu;
  still.metered_ev = metered_stops(still.image);
  still.png = tone_mapped(still.image, request, still.metered_ev + day.stops);
  return still;
}

// How each city tile was drawn: counted by level, then tile by tile.
nlohmann::ordered_json tiles_report(const RenderScene& scene) {
  nlohmann::ordered_json levels = nlohmann::ordered_json::object();
  int culled = 0;
  for (const auto& tl : scene.tiles) {
    levels[tl.level] = levels.value(tl.level, 0) + 1;
    culled += tl.level == "culled";
  }
  nlohmann::ordered_json tiles{{"count", scene.tiles.size()}, {"culled", culled}, {"by_level", levels}};
  nlohmann::ordered_json tile_levels = nlohmann::ordered_json::array();
  for (const auto& tl : scene.tiles) tile_levels.push_back({tl.tile, tl.level});
  tiles["levels"] = tile_levels;
  return tiles;
}

nlohmann::ordered_json still_report(const RenderRequest& request, const SolarPlace& place, const Daylight& day,
                                    const RenderScene& scene, double scene_s, double scene_cpu_s,
                                    const Still& still) {
  const RayCounts& rays = still.rays;
  nlohmann::ordered_json report{
      {"size", {request.width, request.height}},
      {"samples_per_pixel", still.samples},
      {"passes", still.passes},
      {"samples_per_pass", request.spp},  // the most; with a budget, the first pass's is one
      {"time_budget_s", request.time_budget_s},
      {"denoised", still.denoised},
      {"primary_rays", still.primary_rays},
      {"exposure_ev", request.exposure_ev},
      {"metered_ev", still.metered_ev},
      {"white_balance_k", request.white_balance_k},
      {"time_of_day", request.time_of_day},
      {"day_of_year", request.day_of_year},
      {"latitude", place.latitude},
      {"grid_north", place.grid_north},
      {"sun", {{"azimuth", day.sun_azimuth}, {"elevation", day.sun_elevation}}},
      {"night", day.night},
      {"night_stops", day.stops},  // the camera opened up for the night, with metered_ev
      {"lamps", scene.lamps.size()},
      {"haze_visibility_m", request.haze_visibility},
      {"clear_visibility_m", request.haze_visibility > 0 ? 0.0f : request.clear_visibility},
      {"mark_mapped", request.mark_mapped},
      {"landscape_trees", request.landscape_trees},
      {"camera",
       {{"from", {request.camera.from.x, request.camera.from.y, request.camera.from.z}},
        {"to", {request.camera.to.x, request.camera.to.y, request.camera.to.z}},
        {"fov_y", request.camera.fov_y},
        {"aperture", request.camera.depth_of_field.aperture},
        {"focus_distance", request.camera.depth_of_field.focus_distance},
        {"focus_tilt", request.camera.depth_of_field.focus_tilt}}},
      {"tiles", tiles_report(scene)},
      {"scene",
       {{"triangles", scene.triangles},
        {"instances", scene.instances},
        {"landscape_instances", scene.landscape_instances},
        {"build_s", scene_s},
        {"build_cpu_s", scene_cpu_s},
        {"embree_peak_mib", static_cast<double>(scene.embree_peak_bytes()) / (1 << 20)}}},
      {"still",
       {{"seconds", still.seconds},
        {"camera_rays", rays.camera},
        {"bounce_rays", rays.bounce},
        {"shadow_rays", rays.shadow},
        {"rays_per_s", static_cast<double>(rays.camera + rays.bounce + rays.shadow) / still.seconds},
        {"denoise_s", still.denoise_seconds},
        {"write_foretold_s", still.write_foretold_s},
        {"denoise_foretold_s", still.denoise_foretold_s},
        {"filter_foretold_s", still.filter_foretold_s},
        {"primary_layer_s", still.primary_layer_s},
        {"cpu_s", still.cpu_s},
        {"denoise_cpu_s", still.denoise_cpu_s}}},
  };
  return report;
}

// The whole city from straight above, into its own file; returns what the report records.
nlohmann::ordered_json render_overview(const RenderScene& whole, const Sky& sky, const RenderRequest& request,
                                       const Haze& haze, const RenderProgress& progress) {
  const int size = std::max(request.width, request.height);
  const float top = whole.top;
  Camera over = overview_camera(whole.bounds, top, request.camera.fov_y, 1, request.orthographic_overview);
  // A map: the air's fade is the still's, not the overview's.
  Haze map_haze = haze;
  map_haze.air_density = 0;
  TraceSettings s{size, size, request.spp, 8, map_haze};
  Image img = finished(trace(whole, sky, over, s, nullptr, [&](int done, int n) {
    if (progress) progress("overview", static_cast<double>(done) / n);
  }), whole, sky, over, map_haze, request);
  write_png(tone_mapped(img, request), request.overview_file);
  return {{"height_m", over.from.z - top}, {"orthographic", request.orthographic_overview}};
}

constexpr int kMinimapSize = 256;  // pixels, square

// Scene coordinates to minimap pixels (the orthographic top-down view, north up).
std::pair<float, float> minimap_pixel(const Camera& top_down, geom::Vec2 p) {
  const int m = kMinimapSize;
  const float span = top_down.ortho_height;
  return std::pair<float, float>{(static_cast<float>(p.x) - top_down.from.x) / span * m + m / 2.0f,
                                 m / 2.0f - (static_cast<float>(p.y) - top_down.from.y) / span * m};
}

// The still's camera on the minimap: the ground it sees, where it stands and where it looks.
void draw_still_camera(Rgb8& map, const Camera& top_down, const Camera& camera, const std::vector<geom::Vec2>& seen) {
  for (int i = 0; i < 4; ++i) {
    auto [x0, y0] = minimap_pixel(top_down, seen[i]);
    auto [x1, y1] = minimap_pixel(top_down, seen[(i + 1) % 4]);
    line(map, {1.0f, 0.85f, 0.1f}, x0, y0, x1, y1, 2);
  }
  auto [cx, cy] = minimap_pixel(top_down, {camera.from.x, camera.from.y});
  const V3 heading = camera.forward();
  const float hl = std::hypot(heading.x, heading.y);
  if (hl > 1e-4f) line(map, {0.9f, 0.1f, 0.1f}, cx, cy, cx + heading.x / hl * 18, cy - heading.y / hl * 18, 2);
  disc(map, {0.9f, 0.1f, 0.1f}, cx, cy, 4);
}

// Set into the still's top-right corner, a third of its height, with a frame.
void inset_minimap(Rgb8& still_png, const Rgb8& map, const RenderRequest& request) {
  const int m = kMinimapSize;
  const int size = std::max(32, request.height / 3), x0 = request.width - size - 8, y0 = 8;
  for (int y = -2; y < size + 2; ++y)
    for (int x = -2; x < size + 2; ++x) {
      const bool frame = x < 0 || y < 0 || x >= size || y >= size;
      const std::uint8_t* p = &map.pixels[(static_cast<std::size_t>(std::clamp(y * m / size, 0, m - 1)) * m +
                                           std::clamp(x * m / size, 0, m - 1)) *
                                          3];
      std::uint8_t* q = nullptr;
      if (x0 + x >= 0 && y0 + y >= 0 && x0 + x < request.width && y0 + y < request.height)
        q = &still_png.pixels[(static_cast<std::size_t>(y0 + y) * request.width + (x0 + x)) * 3];
      if (!q) continue;
      for (int c = 0; c < 3; ++c) q[c] = frame ? 255 : p[c];
    }
}

// The minimap, into its own file and into the still's corner; returns the ground the
// still sees, in city coordinates, for the report.
nlohmann::ordered_json render_minimap(const RenderScene& whole, const RenderScene& scene, const Sky& sky,
                                      const Camera& camera, const RenderRequest& request, Rgb8& still_png) {
  const int m = kMinimapSize;
  Camera top_down = overview_camera(whole.bounds, whole.top, 45, 1, true);
  Image img = finished(trace(whole, sky, top_down, TraceSettings{m, m, std::max(1, request.spp / 4)}), whole, sky,
                       top_down, Haze{}, request);
  Rgb8 map = tone_mapped(img, request);
  // The still's view, from its own scene (the same origin: both centre on the city).
  std::vector<geom::Vec2> seen = ground_footprint(camera, request.width, request.height, whole.ground, whole.bounds);
  draw_still_camera(map, top_down, camera, seen);
  write_png(map, request.minimap_file);
  inset_minimap(still_png, map, request);
  return {{"visible_ground",
           {{seen[0].x + scene.origin_x, seen[0].y + scene.origin_y},
            {seen[1].x + scene.origin_x, seen[1].y + scene.origin_y},
            {seen[2].x + scene.origin_x, seen[2].y + scene.origin_y},
            {seen[3].x + scene.origin_x, seen[3].y + scene.origin_y}}}};
}

// The EXR beside the PNG, under the same name.
void write_still(const Still& still, const fs::path& png) {
  fs::path exr = png;
  exr.replace_extension(".exr");
  write_exr(still.image, exr);
  write_png(still.png, png);
}

}  // namespace

SolarPlace solar_place(const exacity::City& city, int day_of_year) {
  SolarPlace place;
  if (day_of_year > 0) place.declination = solar_declination(day_of_year);
  const std::optional<int> epsg = exacity::epsg_of(city.settings.crs);
  const geom::Box box = city.ground.bounds();
  if (!epsg || box.holds_nothing()) return place;
  // The city's centre and a point a kilometre north of it on the map, in lon/lat: the
  // latitude, and the bearing of the map's north from true north there.
  const exacity::ToLonLat to_lon_lat(*epsg);
  const geom::Vec2 centre{(box.min_x + box.max_x) / 2, (box.min_y + box.max_y) / 2};
  const geom::Vec2 here = to_lon_lat(centre), north = to_lon_lat({centre.x, centre.y + 1000});
  if (!std::isfinite(here.y) || std::abs(here.y) > 90) return place;
  place.latitude = static_cast<float>(here.y);
  const double east = std::remainder(north.x - here.x, 360.0) * std::cos(here.y * 3.14159265358979 / 180);
  place.grid_north = static_cast<float>(std::atan2(east, north.y - here.y) * 180 / 3.14159265358979);
  return place;
}

Camera default_camera(const exacity::City& city, float aspect) {
  geom::Box box = city.ground.bounds();
  if (box.holds_nothing()) box = {0, 0, 100, 100};
  const exacity::Terrain* terrain = city.heightmap();
  auto ground_at = [&](double x, double y) { return terrain ? terrain->height_at({x, y}) : 0.0; };
  // The city's outline: its zones' and water's corners on the ground, its buildings' at
  // their tops (the box's corners where it has none).
  std::vector<V3> outline;
  auto add = [&](geom::Vec2 p, double z) {
    outline.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(z)});
  };
  for (const auto& z : city.ground.zones)
    for (geom::Vec2 p : z.polygon.outer) add(p, ground_at(p.x, p.y));
  for (const auto& w : city.ground.water)
    for (geom::Vec2 p : w.outer) add(p, ground_at(p.x, p.y));
  for (const auto& b : city.buildings)
    for (geom::Vec2 p : b.polygon.outer) add(p, b.floor + b.height);
  for (const auto& m : city.models)
    for (geom::Vec2 p : m.polygon.outer) add(p, m.floor + m.height);
  if (outline.empty())
    for (double x : {box.min_x, box.max_x})
      for (double y : {box.min_y, box.max_y}) add({x, y}, ground_at(x, y));
  geom::Box around = geom::Box::none();
  for (const V3& p : outline) around.add(geom::Vec2{p.x, p.y});
  const double cx = (around.min_x + around.max_x) / 2, cy = (around.min_y + around.max_y) / 2;
  const float az = 235 * kPi / 180, pitch = kDefaultPitch * kPi / 180, fov = 45;
  const V3 target{static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(ground_at(cx, cy))};
  const V3 back{std::cos(pitch) * std::cos(az), std::cos(pitch) * std::sin(az), std::sin(pitch)};
  // The nearest eye, backing off along the view, whose frame holds every corner with a
  // margin of a twentieth.
  const float tan_y = 0.95f * std::tan(fov * kPi / 360), tan_x = tan_y * aspect;
  auto holds = [&](float distance) {
    const Camera c = Camera::look(target + back * distance, target, fov);
    const V3 f = c.forward(), r = c.right(), u = cross(r, f);
    for (const V3& corner : outline) {
      const V3 p = corner - c.from;
      const float depth = dot(p, f);
      if (!(depth > 0 && std::abs(dot(p, r)) <= depth * tan_x && std::abs(dot(p, u)) <= depth * tan_y)) return false;
    }
    return true;
  };
  float top = 0;
  for (const V3& p : outline) top = std::max(top, p.z - target.z);
  float near = 1, far = static_cast<float>(10 * std::hypot(box.width(), box.height()) + 10 * top + 100);
  for (int i = 0; i < 40; ++i) {
    const float mid = (near + far) / 2;
    (holds(mid) ? far : near) = mid;
  }
  return Camera::look(target + back * far, target, fov);
}

nlohmann::ordered_json render_city(const exacity::City& city, const RenderRequest& request,
                                   const RenderProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const double start_cpu = cpu_seconds();
  const SolarPlace place = solar_place(city, request.day_of_year);
  const Daylight day = daylight(request, place);
  const Sky sky = Sky::at(day.sun_azimuth, day.sun_elevation, request.turbidity, day.night);
  const SceneOptions options = culled_to_view(request, day);
  if (progress) progress("scene", 0);
  // Tiles are grown towards the sun to keep what casts shadows into view; a set sun casts none.
  RenderScene scene(city, sky.sun_up() ? sky.sun_direction() : V3{0, 0, 1}, options);
  const StreetLights lights(scene.lamps);
  const double scene_s = seconds_since(start), scene_cpu_s = cpu_seconds() - start_cpu;
  const Camera camera = scene.to_scene(request.camera);
  const Haze haze = haze_layer(request, scene);

  Still still = render_still(scene, sky, camera, request, day, haze, progress, lights.empty() ? nullptr : &lights);
  nlohmann::ordered_json report = still_report(request, place, day, scene, scene_s, scene_cpu_s, still);
  // Between the steps too: writing a large image takes a while (generate/cancel.h).
  const exacity::CancelCheck cancel;
  cancel.check();
  if (request.overview || request.minimap) {
    // By day whatever the still's hour: maps, not views.
    const Sky map_sky(request.sun_azimuth, request.sun_elevation, request.turbidity);
    const RenderScene whole(city, map_sky.sun_direction(), whole_city(request));
    if (request.overview) report["overview"] = render_overview(whole, map_sky, request, haze, progress);
    if (request.minimap) report["minimap"] = render_minimap(whole, scene, map_sky, camera, request, still.png);
  }
  cancel.check();
  const auto writing = std::chrono::steady_clock::now();
  write_still(still, request.still);
  report["still"]["write_s"] = seconds_since(writing);
  // What is left of the command after this (freeing the scene and the city, exiting) is
  // outside what the budget foretells: the whole command's wall time less this says how long.
  report["still"]["written_at_s"] = seconds_since(request.started);
  return report;
}

}  // namespace render
