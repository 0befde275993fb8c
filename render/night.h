// Night (render/README.md, Night): the sun by the hour, and the street lamps as lights
// chosen among many: one lamp a shadow ray, drawn among the lamps within kReach of the
// point (found in a grid) by the light each would give there, its power over the squared
// distance, so that a city of ten thousand lamps costs and converges as one street of
// them does.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "render/vec.h"

namespace render {

// Where and when on Earth the hour's sun is reckoned: the latitude (degrees north), the
// sun's declination that day (degrees; 0 on an equinox), and how far grid north, the
// map's y axis, is turned east of true north there (degrees; a projection's meridian
// convergence). A sketch without a CRS has no place on Earth: 50 degrees north, an
// equinox, y true north.
struct SolarPlace {
  float latitude = 50, declination = 0, grid_north = 0;
};

// The sun at a local solar time (hours, 0 to 24) at `place`: on an equinox at 50 degrees
// north, up from 6:00 to 18:00, in the south at noon 40 degrees high; degrees as Sky takes
// them (azimuth counter-clockwise from the map's east).
struct SunPosition {
  float azimuth = 0, elevation = 0;
};
SunPosition sun_at_hour(float hours, const SolarPlace& place = {});

// The sun's declination in degrees on a day of the year (1 to 366), by Spencer's Fourier
// series ("Fourier series representation of the position of the sun", 1971: within 0.05
// degrees of the almanac's), and the day of the year of a month and day (a leap year's
// when `leap`).
float solar_declination(int day_of_year);
int day_of_year(int month, int day, bool leap = false);

// How far into the night a sun this high is, 0 (day: 3 degrees up or more) to 1 (night:
// 8 degrees down or more), linearly between.
float night_share(float sun_elevation);

// A lamp: a point light under its head, sending `intensity` straight down and
// kUplight of it sideways and up, a cosine lobe between; its light fades to nothing at
// kReach (a window on the inverse square, as real-time renderers bound their lights':
// beyond 80 m a lamp gives under a 1,600th of the light at its foot).
struct Lamp {
  V3 position;
  float intensity = 0;
};
constexpr float kUplight = 0.15f;
// A street lamp's intensity straight down (the sun's irradiance is 8 in these units: a lamp
// lights the road under it 6 m down at a 2^6-th of that, a lit street at night, for which
// the camera opens up 6 stops).
constexpr float kLampIntensity = 4;
constexpr float kReach = 80;  // m
// Its radiant intensity towards direction d (unit, leaving the lamp), at distance r.
inline float lamp_intensity(const Lamp& l, V3 d, float r) {
  const float x = r / kReach, x4 = x * x * x * x, window = x4 < 1 ? (1 - x4) * (1 - x4) : 0;
  return l.intensity * window * (kUplight + (1 - kUplight) * std::max(0.0f, -d.z));
}

class StreetLights {
 public:
  explicit StreetLights(std::vector<Lamp> lamps);
  bool empty() const { return lamps_.empty(); }
  std::size_t size() const { return lamps_.size(); }
  // A lamp for a shadow ray from p, from a uniform number, and the chance it was drawn;
  // null where no lamp reaches p.
  const Lamp* choose(V3 p, float u, float& chance) const;

 private:
  struct Near {
    std::vector<std::uint32_t> lamps;  // within kReach of p
    std::vector<float> weights;        // the light each gives at p, unshadowed
    float total = 0;
  };
  Near near(V3 p) const;
  std::vector<Lamp> lamps_;
  // A grid of kReach / 2 cells: the lamps in each cell, by index.
  float min_x_ = 0, min_y_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<std::uint32_t>> cells_;
};

}  // namespace render
