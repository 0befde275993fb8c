// GET /api/settings: the zone types' settings as the CLI reads them, for the page's forms;
// GET /api/palette: the colours and road widths the page draws with (docs/design.md,
// Serving: settings and palette).
#include "serve/settings_table.h"

#include <map>

#include "generate/city/palette.h"
#include "generate/sketch/sketch.h"
#include "render/render.h"
#include "serve/server_state.h"

namespace exacity::serve {
using nlohmann::json;

namespace {

struct Note {
  const char* unit;
  const char* description;
};

// What each key means, in the README's words (The sketch: zone parameters). Names, kinds,
// bounds and defaults come from the steps' readers themselves.
const std::map<std::string, Note>& notes() {
  static const std::map<std::string, Note> n{
      {"layout", {"", "how the zone's roads are laid out: growth (recursive road growth), grammar (a split grammar), voronoi (streets along Voronoi cells) or streets (the sketch's roads only)"}},
      {"grammar", {"", "for grammar: the grammar file, relative to the sketch"}},
      {"grammar_depth", {"rules", "for grammar: how many rules deep a root grows at most"}},
      {"grow_large_pieces", {"", "for grammar: land between the grammar's roads over 4 × block_area is laid out by growth inside"}},
      {"cell_size", {"m", "for voronoi: one point per square of this size"}},
      {"junction_spacing", {"m", "for voronoi: the step between junctions along the cells' roads"}},
      {"block_area", {"m²", "cells above this are grown again, one level deeper"}},
      {"segment_length", {"m", "one growth step"}},
      {"branches", {"roads", "roads grown from each seed point"}},
      {"jitter", {"°", "a level-n cell turns its parent's orientation by up to ±jitter/n"}},
      {"segment_deviation", {"°", "Δsegm at level 0, falling by 2 a level (0: straight roads)"}},
      {"origin_deviation", {"°", "Δorig: how far a road may turn from its first direction"}},
      {"road_widths", {"m", "per level, the last for all deeper: level 0 roads are main, deeper ones local"}},
      {"min_block_area", {"m²", "smaller blocks become green space"}},
      {"min_block_width", {"m", "thinner blocks (width 2·area/perimeter) become green space"}},
      {"bridges", {"", "grown roads cross heightmap water as bridges instead of stopping at the shore"}},
      {"lots", {"", "allocation (lots along the street), split (recursive splitting) or library (the lots the model library's entries ask for)"}},
      {"lot_width", {"m", "[min, max] frontage of an allocated lot, drawn per street side"}},
      {"lot_frontages", {"m", "street widths of allocated lots at equal steps of their distribution, smallest to largest (a real place's, as --like's frontage rule gives it): each lot's width is drawn from it instead of lot_width; empty: lot_width"}},
      {"lot_depth", {"m", "how far allocated lots reach back from the street"}},
      {"lot_area", {"m²", "split halves lots until they are below this"}},
      {"min_lot_edge", {"m", "allocated lots with a shorter frontage or depth are dropped"}},
      {"min_lot_area", {"m²", "smaller lots are dropped"}},
      {"setback", {"m", "footprints stand this far behind the street"}},
      {"building_gap", {"m", "between neighbouring footprints (half of it inside the lot's other edges)"}},
      {"footprint_width", {"m", "[min, max] size of a footprint along the street"}},
      {"footprint_depth", {"m", "[min, max] size of a footprint back from the street"}},
      {"min_footprint_width", {"m", "no footprint narrower than this either way"}},
      {"max_footprint_area", {"m²", "no footprint larger; a larger lot gets several buildings"}},
      {"min_footprint_area", {"m²", "no smaller footprint"}},
      {"footprint_areas", {"m²", "footprint areas at equal steps of their distribution, smallest to largest (a real place's, as --like measures it): each footprint's area is drawn from it, its shape from footprint_width and footprint_depth"}},
      {"perimeter_depth", {"m", "above 0: perimeter blocks, each lot's land this deep behind its streets one building (0: rectangles in rows)"}},
      {"lot_coverage", {"share", "above 0: rows behind the first fill each lot until its footprints cover this share of it (0: one row)"}},
      {"heights", {"m", "[lowest, highest] building near the city centre (half at its edge)"}},
      {"roof", {"", "auto (gabled on near-rectangles, hipped otherwise, for residential; flat for the others), flat, gabled or hipped"}},
      {"roof_pitch", {"°", "the roofs' pitch"}},
      {"storey_height", {"m", "a mapped building with building:levels and no height is this tall a storey"}},
      {"density", {"", "placed models' spacing along a row: dense 1.25–1.5 model widths, normal 2–3, sparse 4–5"}},
      {"placement", {"", "how library buildings fill a lot: rows along the street or grid (grid filling)"}},
      {"grid_cell", {"m", "for grid: the grid's cell"}},
      {"grid_passes", {"passes", "for grid: how many times the lot is filled"}},
      {"nesting", {"", "for grid: a 3D bounding grid, so a model may stand under another's overhang"}},
      {"height_channel", {"", "a channel whose value takes the place of nearness to the city's centre in extruded heights"}},
  };
  return n;
}

// The defaults of the keys a step reads itself (kind "json"), from the settings read.
json own_default(const std::string& key, const ZoneSettings& z) {
  if (key == "road_widths") return z.roads.road_widths;
  if (key == "heights") return json::array({z.buildings.min_height, z.buildings.max_height});
  if (key == "footprint_areas") return z.buildings.footprint_areas;
  if (key == "lot_frontages") return json::array();  // none: lot_width decides
  return nullptr;
}

}  // namespace

json zone_settings_table(ZoneType type) {
  // The steps read an empty object over the zone type's defaults as the sketch reader reads
  // a zone's settings, each describing what it reads.
  std::vector<SettingShape> shapes;
  const json empty = json::object();
  const ZoneSettings read = read_zone_settings(SettingsReader(empty, shapes), type, false);
  json table = json::array();
  for (const SettingShape& s : shapes) {
    json row{{"key", s.key}, {"kind", s.kind}, {"default", s.kind == "json" ? own_default(s.key, read) : s.value}};
    if (s.kind == "number" || s.kind == "whole" || s.kind == "range") row["min"] = s.min, row["max"] = s.max;
    if (s.kind == "choice") row["choices"] = s.choices;
    const auto note = notes().find(s.key);
    row["unit"] = note == notes().end() ? "" : note->second.unit;
    row["description"] = note == notes().end() ? s.what : note->second.description;
    table.push_back(std::move(row));
  }
  return table;
}

json palette_table() {
  json sketch_zones = json::object(), roads = json::object(), widths = json::object();
  for (std::size_t i = 0; i < kZoneTypeNames.size(); ++i) {
    const auto type = static_cast<ZoneType>(i);
    const std::string name(kZoneTypeNames[i]);
    sketch_zones[name] = sketch_zone_colour(type);
  }
  for (std::size_t i = 0; i < kRoadClassNames.size(); ++i) {
    const auto road = static_cast<RoadClass>(i);
    roads[std::string(kRoadClassNames[i])] = sketch_road_colour(road);
    widths[std::string(kRoadClassNames[i])] = default_width(road);
  }
  json map = json::object();
  for (const auto& [zone, colour] : map_zone_colours()) map["zones"][zone] = colour;
  map["background"] = kMapBackground, map["water"] = kMapWater, map["lot"] = kMapLot, map["lot_fill"] = kMapLotFill;
  map["lot_edge"] = kMapLotEdge, map["building"] = kMapBuilding, map["building_edge"] = kMapBuildingEdge;
  map["road"] = kMapRoad, map["bridge"] = kMapBridge, map["sidewalk"] = kMapSidewalk, map["centre_line"] = kMapCentreLine;
  map["clutter"] = kMapClutter;
  const render::RenderRequest still;
  return {{"sketch_zones", sketch_zones}, {"sketch_roads", roads}, {"road_widths", widths}, {"map", map},
          {"sun", {{"azimuth", still.sun_azimuth}, {"elevation", still.sun_elevation}}}};
}

void add_settings_routes(ServerState& s) {
  s.http.Get("/api/settings", [](const httplib::Request&, httplib::Response& res) {
    json zones = json::object();
    for (ZoneType type : {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial})
      zones[std::string(name(type))] = zone_settings_table(type);
    res.set_content(json{{"zones", zones}}.dump(), "application/json");
  });
  s.http.Get("/api/palette", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(palette_table().dump(), "application/json");
  });
}

}  // namespace exacity::serve
