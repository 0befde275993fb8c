// Renders a city held in memory: the still from a camera, the overview from straight
// above, and the minimap with the still's visible ground region (docs/design.md, Algorithms).
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "generate/city.h"
#include "render/camera.h"
#include "render/night.h"

namespace render {

struct RenderRequest {
  Camera camera;  // city coordinates
  int width = 960, height = 540, spp = 16;
  bool overview = false, orthographic_overview = false, minimap = false;
  float sun_azimuth = 200, sun_elevation = 40, turbidity = 3, exposure = 0.25f;
  // Hours of local solar time (render/night.h): the still's sun by the hour, and after
  // sunset its sky's twilight, the street lamps and a share of the windows lit; below 0,
  // the sun above as given. The overview and the minimap keep that sun, by day.
  float time_of_day = -1;
  // The day of the year (1 to 366) the hour's sun is reckoned on; 0: an equinox. Where on
  // Earth is the city's own (solar_place).
  int day_of_year = 0;
  float haze_visibility = 0;    // m; 0: clear air. Haze fills the 500 m over the lowest ground.
  // m: clear air's visibility, for the still's aerial perspective (Haze::air_density; 0: none)
  float clear_visibility = 20000;
  float exposure_ev = 0;        // stops over `exposure`
  float white_balance_k = 6500; // the light's colour temperature made neutral (6500: none)
  bool mark_mapped = false;     // buildings coloured by origin (SceneOptions::mark_mapped)
  bool denoise = true;          // the edge-aware filter (render/denoise.h) before tone mapping
  // The still's woods and hedgerows beyond the city (SceneOptions::landscape_trees); off, the
  // fields stay bare, as city.glb's land is (the Cycles comparison, benchmarks/cycles).
  bool landscape_trees = true;
  // Progressive: passes of `spp` samples while the whole still, counted from `started`
  // (the command's start: the city's and the scene's builds included) and the denoiser
  // after them, fits in this many seconds (at least one pass; the denoiser's primary layer,
  // then the denoiser, left out when it would not fit); 0: one pass. The report records the
  // passes, which fix the image.
  double time_budget_s = 0;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  std::filesystem::path still;  // PNG; the EXR goes beside it
  std::filesystem::path overview_file, minimap_file;
};

// From the south-west, looking kDefaultPitch degrees down at the city's centre, as near as
// the frame (of this aspect) holds the city's whole box, ground to tallest roof; the
// horizon and a band of sky show above it, as in an oblique air photo.
constexpr float kDefaultPitch = 18;
Camera default_camera(const exacity::City& city, float aspect = 16.0f / 9);

// Where on Earth the city's hour is reckoned (render/night.h): the latitude of its centre
// and its map's grid north from the sketch's CRS (through PROJ), or 50 degrees north and
// true north where it has none; the sun's declination on `day_of_year` (0: an equinox).
SolarPlace solar_place(const exacity::City& city, int day_of_year = 0);

// The stage name, then the fraction of it done.
using RenderProgress = std::function<void(const std::string&, double)>;

// Writes the still (PNG and EXR), and the overview and minimap when asked; the minimap is
// also set into the still's top-right corner. Returns what report.json records: sizes,
// samples, scene and render times, rays, and how each city tile was drawn.
nlohmann::ordered_json render_city(const exacity::City& city, const RenderRequest& request,
                                   const RenderProgress& progress = nullptr);

}  // namespace render
