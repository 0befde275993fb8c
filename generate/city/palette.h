// The city's colours, one place for every output: base colours of the 3D exports (linear
// RGB in [0, 1]), the renderer's albedos, and the SVG map's colours.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "generate/city/surface.h"
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

// The colour variation of placed models (docs/design.md, Algorithms: rows): tint t multiplies a model's colours.
inline Colour tinted(const Colour& c, int tint) {
  static constexpr std::array<Colour, 4> kTint{{{1, 1, 1}, {1.08, 1.0, 0.90}, {0.90, 0.96, 1.06}, {0.82, 0.82, 0.82}}};
  const Colour& t = kTint[static_cast<std::size_t>(tint) % kTint.size()];
  return {std::min(1.0, c[0] * t[0]), std::min(1.0, c[1] * t[1]), std::min(1.0, c[2] * t[2])};
}

// The renderer's albedos (linear RGB, as floats: what its materials hold).
using Albedo = std::array<float, 3>;
inline constexpr Albedo kGrassAlbedo{0.30f, 0.45f, 0.20f};  // grass, before its pattern
inline constexpr Albedo kLushGrassAlbedo{0.20f, 0.40f, 0.12f}, kDryGrassAlbedo{0.42f, 0.45f, 0.22f};  // the pattern
// Pavements as measured in the field (docs/design.md, Rendering: facades and roofs): asphalt
// in service, its binder worn off the aggregate, 0.10-0.18 (new, 0.05); concrete slabs
// weathered, 0.25-0.35 (new, about 0.4).
inline constexpr Albedo kSidewalkAlbedo{0.31f, 0.30f, 0.285f}, kAsphaltAlbedo{0.125f, 0.12f, 0.115f};
inline constexpr Albedo kPaintAlbedo{0.85f, 0.85f, 0.80f}, kYellowPaintAlbedo{0.80f, 0.62f, 0.12f};
inline constexpr Albedo kWaterAlbedo{0.02f, 0.06f, 0.08f}, kWindowAlbedo{0.04f, 0.05f, 0.06f};
inline constexpr Albedo kCommercialLotAlbedo{0.50f, 0.49f, 0.46f}, kIndustrialLotAlbedo{0.42f, 0.40f, 0.37f};

// The ground in the 3D exports (city.glb, city.obj, city.ply): open land by zone, roads,
// water and the terrain beyond the zones, in the renderer's albedos, so the 3D view looks
// like the still: zones and terrain grass, commercial and industrial land their lots'
// paving, roads asphalt, bridges' piers and sides the sidewalks' concrete, water its (the
// still's water is that under the sky's reflection).
inline constexpr Colour albedo_colour(const Albedo& a) { return {a[0], a[1], a[2]}; }
inline Colour ground_colour(ZoneType zone) {
  switch (zone) {
    case ZoneType::Commercial: return albedo_colour(kCommercialLotAlbedo);
    case ZoneType::Industrial: return albedo_colour(kIndustrialLotAlbedo);
    case ZoneType::Water: return albedo_colour(kWaterAlbedo);
    case ZoneType::Residential:
    case ZoneType::Park: break;
  }
  return albedo_colour(kGrassAlbedo);
}
inline constexpr Colour kRoadColour = albedo_colour(kAsphaltAlbedo);
inline constexpr Colour kTerrainColour = albedo_colour(kGrassAlbedo);
inline constexpr Colour kBridgeColour = albedo_colour(kSidewalkAlbedo);

// Facade and roof albedos per zone type; each building picks one of each.
inline const std::vector<Albedo>& facade_albedos(ZoneType z) {
  static const std::vector<Albedo> residential{
      {0.80f, 0.72f, 0.60f}, {0.72f, 0.48f, 0.36f}, {0.86f, 0.82f, 0.66f}, {0.70f, 0.70f, 0.68f}};
  static const std::vector<Albedo> commercial{
      {0.62f, 0.64f, 0.66f}, {0.50f, 0.56f, 0.62f}, {0.76f, 0.72f, 0.64f}, {0.84f, 0.84f, 0.82f}};
  static const std::vector<Albedo> industrial{{0.55f, 0.56f, 0.56f}, {0.56f, 0.40f, 0.30f}, {0.58f, 0.62f, 0.56f}};
  return z == ZoneType::Commercial ? commercial : z == ZoneType::Industrial ? industrial : residential;
}
inline const std::vector<Albedo>& roof_albedos(ZoneType z) {
  static const std::vector<Albedo> residential{{0.45f, 0.18f, 0.12f}, {0.22f, 0.22f, 0.25f}, {0.38f, 0.28f, 0.20f}};
  static const std::vector<Albedo> flat{{0.30f, 0.30f, 0.30f}, {0.42f, 0.41f, 0.39f}};
  return z == ZoneType::Residential ? residential : flat;
}

// The SVG map's colours (sRGB hex): a map's, lighter than the ground's own.
inline const std::map<std::string, const char*>& map_zone_colours() {  // by zone name, the legend's order
  static const std::map<std::string, const char*> colours{
      {"residential", "#f2c9a0"}, {"commercial", "#a9c8ec"}, {"industrial", "#cdb89a"}, {"park", "#a8d38d"}};
  return colours;
}
inline constexpr const char* kMapBackground = "#f4f4f0";
inline constexpr const char* kMapWater = "#5b9bd5";
inline constexpr const char* kMapLot = "#f7ecdc";  // in the legend; lots are drawn in kMapLotFill, half opaque
inline constexpr const char* kMapLotFill = "#fbf3e6";
inline constexpr const char* kMapLotEdge = "#8a6d4b";
inline constexpr const char* kMapBuilding = "#9a8672";
inline constexpr const char* kMapBuildingEdge = "#5e4f40";
inline constexpr const char* kMapRoad = "#6b6b6b";
inline constexpr const char* kMapBridge = "#3a3a3a";
inline constexpr const char* kMapSidewalk = "#c9c3b8";
inline constexpr const char* kMapCentreLine = "#ffffff";
inline constexpr const char* kMapClutter = "#7b3294";  // street clutter's dots

// The sketch as exacity serve's page draws it (sRGB hex): the classic red residential, green
// commercial and brown industrial, park and water as on the SVG map; roads darker
// the higher their class.
inline const char* sketch_zone_colour(ZoneType zone) {
  switch (zone) {
    case ZoneType::Residential: return "#d6604d";
    case ZoneType::Commercial: return "#3f9a6e";
    case ZoneType::Industrial: return "#96693c";
    case ZoneType::Park: return "#a6d96a";
    case ZoneType::Water: return kMapWater;
  }
  return "#808080";
}
inline const char* sketch_road_colour(RoadClass road) {
  switch (road) {
    case RoadClass::Highway: return "#111111";
    case RoadClass::Main: return "#333333";
    case RoadClass::Local: return "#555555";
  }
  return "#000000";
}

}  // namespace exacity
