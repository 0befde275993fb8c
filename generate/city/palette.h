// Base colours of the city's surfaces (linear RGB in [0, 1]), one place for every export.
#pragma once

#include <array>

#include "generate/export/building_mesh.h"
#include "generate/city/zone_type.h"

namespace exacity {

using Colour = std::array<double, 3>;

// Facades by zone, roofs darker and browner, ground faces grey.
inline Colour surface_colour(ZoneType zone, Surface s) {
  Colour c = zone == ZoneType::Residential  ? Colour{0.85, 0.72, 0.58}
             : zone == ZoneType::Commercial ? Colour{0.62, 0.70, 0.80}
             : zone == ZoneType::Industrial ? Colour{0.66, 0.62, 0.55}
                                            : Colour{0.8, 0.8, 0.8};
  if (s == Surface::Roof) return {c[0] * 0.6, c[1] * 0.55, c[2] * 0.5};
  if (s == Surface::Ground) return {0.45, 0.45, 0.45};
  return c;
}

// The ground: open land by zone, roads, water and the terrain beyond the zones.
inline Colour ground_colour(ZoneType zone) {
  switch (zone) {
    case ZoneType::Residential: return {0.55, 0.60, 0.42};
    case ZoneType::Commercial: return {0.58, 0.58, 0.55};
    case ZoneType::Industrial: return {0.52, 0.50, 0.46};
    case ZoneType::Park: return {0.36, 0.55, 0.26};
    case ZoneType::Water: return {0.16, 0.33, 0.50};
  }
  return {0.5, 0.5, 0.5};
}
inline constexpr Colour kRoadColour{0.22, 0.22, 0.23};
inline constexpr Colour kTerrainColour{0.45, 0.52, 0.33};

// Seed 001's colour alteration of placed models: tint t multiplies a model's colours.
inline Colour tinted(const Colour& c, int tint) {
  static constexpr std::array<Colour, 4> kTint{{{1, 1, 1}, {1.08, 1.0, 0.90}, {0.90, 0.96, 1.06}, {0.82, 0.82, 0.82}}};
  const Colour& t = kTint[static_cast<std::size_t>(tint) % kTint.size()];
  return {std::min(1.0, c[0] * t[0]), std::min(1.0, c[1] * t[1]), std::min(1.0, c[2] * t[2])};
}

}  // namespace exacity
