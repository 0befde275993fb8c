// The buildings stage: each zone's placers (generate/placement/placer.h) fill every lot.
// Extruded buildings are rectangular footprints in a row along the lot's street, checked
// exactly inside the lot; each one's height drawn between the zone's range, which falls
// with distance from the city centre, with a small chance near the centre of doubling
// (docs/design.md, Algorithms: extruded buildings).
#pragma once

#include <vector>

#include "generate/parcels/lots.h"
#include "generate/placement/model_library.h"
#include "generate/city/channels.h"
#include "generate/city/random.h"
#include "generate/city/zone_settings.h"
#include "generate/city/terrain.h"
#include "generate/city/city_map.h"
#include "geom/roof.h"

namespace exacity {

// A placed model: its library index, where its origin stands, the turn (radians,
// counter-clockwise) that brings its x axis along the row, its size and colour variant.
struct Placement {
  int model = -1;
  geom::Vec2 position;
  double angle = 0, scale = 1;
  int tint = 0;
  // A point of the model's mesh in the city, standing on `floor`.
  Vec3 apply(Vec3 v, double floor) const;
};
inline constexpr int kTints = 4;

// Buildings and placed models share one numbering, `id`: lot by lot, a lot's extruded
// buildings before its models. The outputs write their stable_id (give_stable_ids). Terrain under a footprint: it
// stands on `floor` (the highest point), its walls or foundation reach down to `base` (the
// lowest); heights count from floor.

// A mapped building's building:part (OSM's Simple 3D Buildings): its own prism from
// `bottom` to its eaves under its own roof, heights from the building's floor.
struct BuildingPart {
  geom::Polygon polygon;  // outer ring counter-clockwise, inside the building's outline
  double bottom = 0, height = 0, eaves = 0;  // m
  std::string roof = "flat";
  std::vector<geom::Face3> roof_faces;  // pitched roofs only, in place
  std::string osm_id, tag;              // its OSM id and building:part tag
  int mapped = -1;                      // its index in the sketch's building_parts
};

// An extruded building: a footprint raised to its height under a roof.
struct Building {
  int id = -1;
  int stable_id = -1;  // its id in the outputs (give_stable_ids)
  int lot = -1;  // index into the lots
  ZoneType zone = ZoneType::Residential;
  geom::Polygon polygon;   // on the grid
  double height = 0;       // m, to the top of the roof
  std::string roof = "flat";
  double eaves = 0;        // m: where walls meet a pitched roof (the height, for flat roofs)
  std::vector<geom::Face3> roof_faces;  // pitched roofs only, in place
  double base = 0, floor = 0;
  // A mapped building's (generate/placement/mapped_buildings.h): its index in the sketch's
  // buildings, OSM id and building tag; -1 and empty for generated ones. Its lot, the one
  // it stands on, may be -1.
  int mapped = -1;
  std::string osm_id, building_tag;
  std::pair<std::string, std::string> source_id;  // MappedBuilding's
  // Where it maps building:parts, its 3D is theirs and its footprint only the outline (its
  // height their highest top).
  std::vector<BuildingPart> parts;
};

// A library model placed on a lot: a building, street furniture or a tree.
struct ModelInstance {
  int id = -1;
  int stable_id = -1;  // its id in the outputs (give_stable_ids; clutter's, place_clutter)
  int lot = -1;
  ZoneType zone = ZoneType::Residential;
  ModelKind kind = ModelKind::Building;
  geom::Polygon polygon;   // its outline, on the grid
  Placement placed;
  double height = 0;       // m, the model's top
  double base = 0, floor = 0;
  // Nesting (docs/design.md, Placement: nesting): the model's slabs in place,
  // heights from its floor, the lowest from its base; empty where the zone does not nest.
  std::vector<Slab> slabs;
};

// What the buildings stage raises on the lots.
struct Structures {
  std::vector<Building> buildings;
  std::vector<ModelInstance> models;
};

// Visits buildings and models in id order; each list must be sorted by id.
template <typename OnBuilding, typename OnModel>
void for_each_by_id(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                    OnBuilding&& on_building, OnModel&& on_model) {
  std::size_t i = 0, j = 0;
  while (i < buildings.size() || j < models.size()) {
    if (j == models.size() || (i < buildings.size() && buildings[i].id < models[j].id)) on_building(buildings[i++]);
    else on_model(models[j++]);
  }
}

// Each building's and model's stable_id (generate/city/stable_ids.h), from what the
// buildings layer writes of it but ids and its lot: one numbering for both.
void give_stable_ids(std::vector<Building>& buildings, std::vector<ModelInstance>& models);

// The roof a footprint gets: its kind, its faces (none for flat) and the eaves height.
// A pitched roof rising over half the building's height, or whose skeleton leaves the
// footprint, falls back to flat.
void choose_roof(Building& b, const BuildingSettings& p);

// The lots mapped buildings stand on (lots_holding, generate/placement/mapped_buildings.h).
struct HeldLots {
  std::vector<char> held;   // per lot: a mapped footprint stands on it
  std::vector<int> lot_of;  // per footprint: the first lot it stands on, or -1
  std::vector<std::vector<geom::Ring>> standing;  // per lot: the outer rings of those standing on it
  std::vector<double> standing_m2;               // per lot: their area on it
};

// Lot by lot in parallel: rows of models facing the road where the library has buildings
// for the zone, else a row of extruded rectangles along the street; then the
// library's street furniture and trees where they fit, each drawn by its weight and
// channels. Each stands on the terrain. Each lot draws from a stream of its exact cell
// (content_id). With a memo, a lot's structures are taken from it when the lot (its zone,
// density, model and cell) and the lots' box are as before (docs/design.md, Regions and
// regenerating). A lot `held` names (a mapped building stands on it) is built only where
// its zone sets lot_coverage, which says how much more it takes: its placers keep off the
// mapped footprints (Occupancy::stand), which count toward the coverage; else it gets nothing.
Structures place_buildings(const std::vector<Lot>& lots, const CitySettings& city, const ModelLibrary* library,
                           const Channels& channels, const Terrain* terrain, Memo<Structures>* memo = nullptr,
                           const HeldLots* held = nullptr);

// The 3D exports write every placed model's triangles (OBJ, PLY and CityJSON have no
// instances for buildings), about 100 bytes of memory and 145 of files each (the town with a
// 9,408-triangle model in its buildings: 14.7 million, 1.5 GB more at the peak, 2.1 GB
// written): past kMaxExportTriangles a run stops with one line naming the model that weighs most.
inline constexpr double kMaxExportTriangles = 60e6;
void check_export_size(const std::vector<ModelInstance>& models, const ModelLibrary* library);

// The height: uniform in the zone's range scaled by 0.5 + 0.5 near_centre (in [0, 1]:
// 1 - distance / radius from the city's centre, or the zone's height channel), so down to
// half at the city's edge; the top doubles with a chance of 0.1 × near_centre².
double building_height(const BuildingSettings& p, double near_centre, Random& rng);

}  // namespace exacity
