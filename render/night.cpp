#include "render/night.h"

#include <algorithm>
#include <cmath>

namespace render {
namespace {

constexpr float kDegree = kPi / 180;
constexpr float kCell = kReach / 2;  // m: the grid's cells

}  // namespace

SunPosition sun_at_hour(float hours, const SolarPlace& place) {
  // At hour angle H, the sun's direction (east, north, up) is (-cos d sin H,
  // cos(lat) sin d - sin(lat) cos d cos H, sin(lat) sin d + cos(lat) cos d cos H), for its
  // declination d (on an equinox, d = 0: (-sin H, -sin(lat) cos H, cos(lat) cos H)).
  const float h = (hours - 12) * 15 * kDegree, lat = place.latitude * kDegree, d = place.declination * kDegree;
  const float east = -std::cos(d) * std::sin(h);
  const float north = std::cos(lat) * std::sin(d) - std::sin(lat) * std::cos(d) * std::cos(h);
  const float up = std::sin(lat) * std::sin(d) + std::cos(lat) * std::cos(d) * std::cos(h);
  // Counter-clockwise from true east, then from the map's east, which is turned with grid north.
  return {std::atan2(north, east) / kDegree + place.grid_north, std::asin(std::clamp(up, -1.0f, 1.0f)) / kDegree};
}

float solar_declination(int day_of_year) {
  const double g = 2 * 3.14159265358979 * (day_of_year - 1) / 365;
  const double d = 0.006918 - 0.399912 * std::cos(g) + 0.070257 * std::sin(g) - 0.006758 * std::cos(2 * g) +
                   0.000907 * std::sin(2 * g) - 0.002697 * std::cos(3 * g) + 0.00148 * std::sin(3 * g);
  return static_cast<float>(d * 180 / 3.14159265358979);
}

int day_of_year(int month, int day, bool leap) {
  static constexpr int kBefore[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  return kBefore[month - 1] + day + (leap && month > 2 ? 1 : 0);
}

float night_share(float sun_elevation) { return std::clamp((3 - sun_elevation) / 11, 0.0f, 1.0f); }

StreetLights::StreetLights(std::vector<Lamp> lamps) : lamps_(std::move(lamps)) {
  if (lamps_.empty()) return;
  float max_x = lamps_[0].position.x, max_y = lamps_[0].position.y;
  min_x_ = max_x, min_y_ = max_y;
  for (const Lamp& l : lamps_) {
    min_x_ = std::min(min_x_, l.position.x), min_y_ = std::min(min_y_, l.position.y);
    max_x = std::max(max_x, l.position.x), max_y = std::max(max_y, l.position.y);
  }
  nx_ = static_cast<int>((max_x - min_x_) / kCell) + 1, ny_ = static_cast<int>((max_y - min_y_) / kCell) + 1;
  cells_.resize(static_cast<std::size_t>(nx_) * ny_);
  for (std::size_t i = 0; i < lamps_.size(); ++i) {
    const int cx = static_cast<int>((lamps_[i].position.x - min_x_) / kCell);
    const int cy = static_cast<int>((lamps_[i].position.y - min_y_) / kCell);
    cells_[static_cast<std::size_t>(cy) * nx_ + cx].push_back(static_cast<std::uint32_t>(i));
  }
}

StreetLights::Near StreetLights::near(V3 p) const {
  Near out;
  // The cells within kReach: two each way of kReach / 2.
  const int cx = static_cast<int>(std::floor((p.x - min_x_) / kCell)), cy = static_cast<int>(std::floor((p.y - min_y_) / kCell));
  for (int y = std::max(cy - 2, 0); y <= std::min(cy + 2, ny_ - 1); ++y)
    for (int x = std::max(cx - 2, 0); x <= std::min(cx + 2, nx_ - 1); ++x)
      for (std::uint32_t i : cells_[static_cast<std::size_t>(y) * nx_ + x]) {
        const V3 d = lamps_[i].position - p;
        const float r2 = dot(d, d);
        if (r2 >= kReach * kReach) continue;
        const float w = lamp_intensity(lamps_[i], {0, 0, -1}, std::sqrt(r2)) / std::max(r2, 1.0f);
        out.lamps.push_back(i), out.weights.push_back(w), out.total += w;
      }
  return out;
}

const Lamp* StreetLights::choose(V3 p, float u, float& chance) const {
  if (lamps_.empty()) return nullptr;
  const Near around = near(p);
  if (!(around.total > 0)) return nullptr;
  float target = u * around.total;
  std::size_t k = 0;
  while (k + 1 < around.lamps.size() && target >= around.weights[k]) target -= around.weights[k++];
  chance = around.weights[k] / around.total;
  return &lamps_[around.lamps[k]];
}

}  // namespace render
