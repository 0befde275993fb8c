// Daylight: Preetham, Shirley and Smits' analytic sky (SIGGRAPH 1999), written here from
// the paper, with a sun disk. The sky is the dome over the city; what it returns below the
// horizon is never seen, the ground plane being in the way.
#pragma once

#include <vector>

#include "render/vec.h"

namespace render {

class Sky {
 public:
  // The sun at `elevation` above the horizon and `azimuth` counter-clockwise from east,
  // both in degrees; turbidity 2 (clear) to 10 (hazy). The scales multiply the sky's and
  // the sun's radiance (0 turns either off, for tests).
  Sky(float sun_azimuth, float sun_elevation, float turbidity = 3, float sky_scale = 1, float sun_scale = 1);
  // The sky at a sun this high, night included: Preetham's model holds the sun at the
  // horizon once it has set, so the sky dims with the sun's depth under it (e-folding every
  // 2.5 degrees: a tenth at -6, civil twilight's end) and keeps the night's glow, a dark
  // blue (a city's sky glow and the moon's) `night` of it (0 to 1, render/night.h).
  static Sky at(float sun_azimuth, float sun_elevation, float turbidity, float night);

  // Sky radiance (linear sRGB) towards `dir`, the sun disk excluded: looked up in a table
  // of the model, bilinearly, so a bounce costs no exponentials.
  V3 radiance(V3 dir) const;
  // The model itself, which the table samples.
  V3 model_radiance(V3 dir) const;
  V3 sun_direction() const { return sun_; }
  const Frame& sun_frame() const { return sun_frame_; }
  // The sun: a disk of this half-angle (cosine) and radiance.
  float sun_cos_max() const { return sun_cos_max_; }
  V3 sun_radiance() const { return sun_radiance_; }
  bool sun_up() const { return sun_.z > 0; }
  // Irradiance the sun gives a surface facing it.
  V3 sun_irradiance() const;

 private:
  float perez(const float coeffs[5], float cos_theta, float gamma) const;
  V3 sun_;
  Frame sun_frame_;
  float sun_cos_max_;
  V3 sun_radiance_;
  float scale_;
  V3 glow_{0, 0, 0};  // added everywhere: the night's
  float cY_[5], cx_[5], cy_[5];
  float zenith_Y_, zenith_x_, zenith_y_;
  float norm_Y_, norm_x_, norm_y_;                  // the Perez functions at the zenith
  static constexpr int kRows = 64, kColumns = 128;  // sqrt(1 - z) from the zenith, azimuth
  std::vector<V3> table_;
};

}  // namespace render
