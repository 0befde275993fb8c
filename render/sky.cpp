#include "render/sky.h"

#include <cmath>

namespace render {
namespace {

constexpr float kDegree = kPi / 180;
constexpr float kSunHalfAngle = 0.5f * kDegree;  // twice the real sun's, for softer shadows
// Sky luminance comes in kcd/m²; this brings a clear zenith near 1.
constexpr float kLuminanceToRadiance = 0.1f;
// The sun's irradiance at normal incidence above the atmosphere, in the same units: a few
// times the clear sky's, as on a sunny day.
constexpr float kSunIrradiance = 8.0f;

// atan2 to within 2e-6 rad (an odd polynomial fitted to atan over [0, 1], folded to the
// octant), a 25,000th of the table's columns: libm's took 3.5% of a render.
float azimuth(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y), hi = std::max(ax, ay);
  if (hi == 0) return 0;
  const float t = std::min(ax, ay) / hi, t2 = t * t;
  float a = t * (0.99997723f + t2 * (-0.33262314f + t2 * (0.19354242f + t2 * (-0.11643181f + t2 * (0.05265333f - 0.01172154f * t2)))));
  if (ay > ax) a = kPi / 2 - a;
  if (x < 0) a = kPi - a;
  return y < 0 ? -a : a;
}

}  // namespace

Sky::Sky(float sun_azimuth, float sun_elevation, float turbidity, float sky_scale, float sun_scale)
    : scale_(sky_scale) {
  const float az = sun_azimuth * kDegree, el = std::clamp(sun_elevation, -10.0f, 90.0f) * kDegree;
  sun_ = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  sun_frame_ = Frame(sun_);
  sun_cos_max_ = std::cos(kSunHalfAngle);
  const float theta_s = kPi / 2 - std::max(el, 0.0f);  // the sun's angle from the zenith
  const float T = turbidity;
  // The paper's Perez coefficients (its appendix), for luminance Y and chromaticities x, y.
  const float Y[5] = {0.1787f * T - 1.4630f, -0.3554f * T + 0.4275f, -0.0227f * T + 5.3251f, 0.1206f * T - 2.5771f,
                      -0.0670f * T + 0.3703f};
  const float x[5] = {-0.0193f * T - 0.2592f, -0.0665f * T + 0.0008f, -0.0004f * T + 0.2125f, -0.0641f * T - 0.8989f,
                      -0.0033f * T + 0.0452f};
  const float y[5] = {-0.0167f * T - 0.2608f, -0.0950f * T + 0.0092f, -0.0079f * T + 0.2102f, -0.0441f * T - 1.6537f,
                      -0.0109f * T + 0.0529f};
  std::copy(Y, Y + 5, cY_), std::copy(x, x + 5, cx_), std::copy(y, y + 5, cy_);
  // Zenith luminance and chromaticity.
  const float chi = (4.0f / 9 - T / 120) * (kPi - 2 * theta_s);
  zenith_Y_ = (4.0453f * T - 4.9710f) * std::tan(chi) - 0.2155f * T + 2.4192f;
  const float t3 = theta_s * theta_s * theta_s, t2 = theta_s * theta_s, t1 = theta_s;
  zenith_x_ = (0.00166f * t3 - 0.00375f * t2 + 0.00209f * t1) * T * T +
              (-0.02903f * t3 + 0.06377f * t2 - 0.03202f * t1 + 0.00394f) * T +
              (0.11693f * t3 - 0.21196f * t2 + 0.06052f * t1 + 0.25886f);
  zenith_y_ = (0.00275f * t3 - 0.00610f * t2 + 0.00317f * t1) * T * T +
              (-0.04214f * t3 + 0.08970f * t2 - 0.04153f * t1 + 0.00516f) * T +
              (0.15346f * t3 - 0.26756f * t2 + 0.06670f * t1 + 0.26688f);
  norm_Y_ = perez(cY_, 1, theta_s), norm_x_ = perez(cx_, 1, theta_s), norm_y_ = perez(cy_, 1, theta_s);

  // The sun's colour: light through `airmass` atmospheres, blue scattered most.
  const float airmass = 1 / std::max(std::sin(std::max(el, 0.0f)), 0.05f);
  const V3 depth{0.02f, 0.05f, 0.12f};
  const float k = 0.25f * T;
  V3 transmit{std::exp(-depth.x * k * airmass), std::exp(-depth.y * k * airmass), std::exp(-depth.z * k * airmass)};
  const float solid_angle = 2 * kPi * (1 - sun_cos_max_);
  sun_radiance_ = transmit * (kSunIrradiance * sun_scale / solid_angle);
  if (sun_.z <= 0) sun_radiance_ = {0, 0, 0};

  table_.resize(static_cast<std::size_t>(kRows) * kColumns);
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      const float t = static_cast<float>(r) / (kRows - 1), z = 1 - t * t;
      const float phi = (static_cast<float>(c) / kColumns - 0.5f) * 2 * kPi;
      const float h = std::sqrt(1 - z * z);
      table_[static_cast<std::size_t>(r) * kColumns + c] = model_radiance({h * std::cos(phi), h * std::sin(phi), z});
    }
}

float Sky::perez(const float c[5], float cos_theta, float gamma) const {
  const float cg = std::cos(gamma);
  return (1 + c[0] * std::exp(c[1] / std::max(cos_theta, 0.01f))) *
         (1 + c[2] * std::exp(c[3] * gamma) + c[4] * cg * cg);
}

Sky Sky::at(float sun_azimuth, float sun_elevation, float turbidity, float night) {
  Sky sky(sun_azimuth, sun_elevation, turbidity, sun_elevation >= 0 ? 1 : std::exp(sun_elevation / 2.5f));
  sky.glow_ = V3{0.00025f, 0.0004f, 0.0008f} * night;
  for (V3& t : sky.table_) t += sky.glow_;
  return sky;
}

V3 Sky::radiance(V3 dir) const {
  if (scale_ == 0) return glow_;
  // Rows by sqrt(1 - z), about even in the angle from the zenith down.
  const float u = std::sqrt(1 - std::clamp(dir.z, 0.0f, 1.0f)) * (kRows - 1);
  const float v = (azimuth(dir.y, dir.x) / (2 * kPi) + 0.5f) * kColumns;
  const int r0 = std::min(static_cast<int>(u), kRows - 2), c0 = static_cast<int>(v) % kColumns,
            c1 = (c0 + 1) % kColumns;
  const float fu = u - static_cast<float>(r0), fv = v - std::floor(v);
  auto at = [&](int r, int c) { return table_[static_cast<std::size_t>(r) * kColumns + c]; };
  return (at(r0, c0) * (1 - fv) + at(r0, c1) * fv) * (1 - fu) + (at(r0 + 1, c0) * (1 - fv) + at(r0 + 1, c1) * fv) * fu;
}

V3 Sky::model_radiance(V3 dir) const {
  if (scale_ == 0) return glow_;
  dir.z = std::max(dir.z, 0.001f);
  dir = normalize(dir);
  const float gamma = std::acos(std::clamp(dot(dir, sun_), -1.0f, 1.0f));
  const float Y = zenith_Y_ * perez(cY_, dir.z, gamma) / norm_Y_;
  const float x = zenith_x_ * perez(cx_, dir.z, gamma) / norm_x_;
  const float y = zenith_y_ * perez(cy_, dir.z, gamma) / norm_y_;
  // xyY to XYZ to linear sRGB (D65).
  const float X = x / y * Y, Z = (1 - x - y) / y * Y;
  V3 rgb{3.2406f * X - 1.5372f * Y - 0.4986f * Z, -0.9689f * X + 1.8758f * Y + 0.0415f * Z,
         0.0557f * X - 0.2040f * Y + 1.0570f * Z};
  rgb = {std::max(rgb.x, 0.0f), std::max(rgb.y, 0.0f), std::max(rgb.z, 0.0f)};
  return rgb * (kLuminanceToRadiance * scale_) + glow_;
}

V3 Sky::sun_irradiance() const { return sun_radiance_ * (2 * kPi * (1 - sun_cos_max_)); }

}  // namespace render
