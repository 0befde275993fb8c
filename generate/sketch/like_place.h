// Looking like a place (docs/design.md, Looking like a place): the zone parameters of a
// sketch measured from a real place's mapped buildings (footprint areas and sides, heights,
// setbacks, gaps), per zone type of the land use they stand on.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city/zone_type.h"
#include "generate/sketch/sketch.h"

namespace exacity {

// Fewer mapped buildings than this in a zone type say too little of it: its defaults stay.
inline constexpr int kMinBuildingsToMeasure = 10;

// One real footprint: in metres, with the height it is tagged with or its storeys.
struct RealFootprint {
  geom::Polygon polygon;
  std::optional<double> height, levels;
};

// What a zone type's mapped buildings measure. Sides are each footprint's smallest
// enclosing rectangle's (long: along the street, short: back from it); setback is a
// footprint's distance from the nearest road's surface (for those within 25 m of one), gap
// its distance from the nearest other footprint (for those within 20 m of one).
struct PlaceFigures {
  int buildings = 0;
  // wing_depths: twice the area over the perimeter, a long wing's depth.
  std::vector<double> areas, long_sides, short_sides, wing_depths, heights, setbacks, gaps;
  double land_m2 = 0;  // the zone type's land use, where the buildings stand
  double frontage_m = 0;  // the length of street its land use fronts, each side of a street once
  // The streets' surface within its land use (each side of a street whose half is in it: its
  // length times the half width): the land use less it is the land its blocks hold.
  double street_m2 = 0;
};

// Measures `footprints` by the zone type of `zones` each one's centre lies in (the last
// drawn wins, as zones cover earlier ones); all of them under every built-up type when
// `zones` is empty. `roads` (centre lines with widths) give the setbacks.
std::map<ZoneType, PlaceFigures> measure_place(const std::vector<RealFootprint>& footprints,
                                               const std::vector<ZoneFeature>& zones,
                                               const std::vector<RoadFeature>& roads,
                                               const std::map<ZoneType, ZoneSettings>& settings);

// The built-up zone type of the drawn zone the ring's centre of area lies in (the last
// drawn winning, as zones cover earlier ones); none outside them, or in park or water.
std::optional<ZoneType> built_up_zone_at(const std::vector<ZoneFeature>& zones, const geom::Ring& ring);

// Each zone type's land as the map gives it: where zones overlap the later wins
// (docs/sketch.md), so a park or a pond drawn over the land use takes that land from it.
// GEOS, through OGR, each polygon made valid; in doubles: a measure.
std::map<ZoneType, double> land_by_zone(const std::vector<ZoneFeature>& zones);

// The zone settings the figures give, as a sketch writes them ("footprint_width": [a, b], ...);
// none when there are fewer than kMinBuildingsToMeasure.
nlohmann::ordered_json settings_from_figures(const PlaceFigures& figures, const ZoneSettings& defaults);

// Reads `like` (an OSM extract, or footprints in any format the sketch reader takes),
// measures it and writes the settings it gives into the sketch's zone types that do not set
// them themselves; the sketch is read again from the document so made, which
// OUT/sketch.geojson keeps (so validate and render rebuild the same city). Returns what was
// measured and set, for report.json's "like". A file with fewer than
// kMinBuildingsToMeasure footprints is a UserError.
nlohmann::ordered_json like_place(Sketch& sketch, const std::filesystem::path& like);

// The lines generate prints of like_place's report.
std::vector<std::string> like_notes(const nlohmann::ordered_json& report);

}  // namespace exacity
