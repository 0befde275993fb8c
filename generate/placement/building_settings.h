// A zone type's building settings ("exacity".zones.TYPE, docs/design.md, The sketch): the
// extruded footprints' sizes, heights and roofs, and how densely placed models stand; read
// and checked here.
#pragma once

#include <set>
#include <string>

#include "generate/city/settings.h"
#include "generate/city/zone_type.h"

namespace exacity {

struct BuildingSettings {
  double setback = 3;                 // m: footprints stand this far behind the street
  double building_gap = 4;            // m: between neighbouring footprints, and from the lot's other edges (half)
  Range footprint_width{8, 14};       // m: along the street
  Range footprint_depth{9, 14};       // m: back from the street
  double min_footprint_width = 6;     // m: no footprint narrower than this either way
  double max_footprint_area = 2000;   // m²: no footprint larger
  double min_footprint_area = 30;     // m²: smaller footprints get no building
  double min_height = 4, max_height = 12;  // m: near the city centre; half that at its edge
  // "auto": gabled on near-rectangular residential footprints, hipped on the others, flat
  // elsewhere; or "flat", "gabled" (falls back to hipped), "hipped" for every footprint.
  std::string roof = "auto";
  double roof_pitch = 30;             // degrees
  // How far apart placed models stand in their rows, centre to centre (a grammar's
  // _Dense/_Sparse): "dense" 1.25–1.5 model widths, "normal" 2–3, "sparse" 4–5.
  std::string density = "normal";
  // How placed models fill a lot: "rows" along the street or "grid", the occupancy grid's
  // grid filling, on cells of `grid_cell` metres, filled `grid_passes` times.
  std::string placement = "rows";
  double grid_cell = 1;
  int grid_passes = 1;
  // Nesting, a 3D occupancy grid: grid filling lets a model stand under another's overhang.
  bool nesting = false;
  // A channel whose value takes the place of nearness to the city's centre in the
  // extruded buildings' heights (building_height); empty for none.
  std::string height_channel;
};

BuildingSettings default_building_settings(ZoneType type);

// The keys read_building_settings reads.
const std::set<std::string>& building_setting_keys();

BuildingSettings read_building_settings(const SettingsReader& settings, BuildingSettings defaults);

}  // namespace exacity
