// Buildings: rectangular footprints in a row along each lot's street, checked exactly
// inside the lot; each one's height drawn between the zone's range, which falls with distance from the
// city centre, with a small chance near the centre of doubling (seed 003).
#pragma once

#include <vector>

#include "generate/parcels/lots.h"
#include "generate/placement/model_library.h"
#include "generate/city/random.h"
#include "generate/city/sketch.h"
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

struct Building {
  int lot = -1;  // index into the lots
  ZoneType zone = ZoneType::Residential;
  geom::Polygon polygon;   // on the grid
  Placement placed;        // placed.model < 0: an extruded footprint
  double height = 0;       // m, to the top of the roof
  std::string roof = "flat";
  double eaves = 0;        // m: where walls meet a pitched roof (the height, for flat roofs)
  std::vector<geom::Face3> roof_faces;  // pitched roofs only, in place
  // Terrain under the footprint: the building stands on `floor` (the highest point), its
  // walls or foundation reach down to `base` (the lowest). Heights above count from floor.
  double base = 0, floor = 0;
};

// The roof a footprint gets: its kind, its faces (none for flat) and the eaves height.
// A pitched roof rising over half the building's height, or whose skeleton leaves the
// footprint, falls back to flat.
void choose_roof(Building& b, const ZoneParams& p);

// Lot by lot in parallel: rows of models facing the road where the library has buildings
// for the zone, else a row of extruded rectangles along the street; then the
// library's street furniture and trees where they fit. Each stands on the terrain.
std::vector<Building> place_buildings(const std::vector<Lot>& lots, const Sketch& sketch, const ModelLibrary* library,
                                      const Terrain* terrain);

// The 3D exports write every placed model's triangles (OBJ, PLY and CityJSON have no
// instances for buildings), about 0.75 kB of memory each while they are written: past
// kMaxExportTriangles a run stops with one line naming the model that weighs most.
inline constexpr double kMaxExportTriangles = 20e6;
void check_export_size(const std::vector<Building>& buildings, const ModelLibrary* library);

// Seed 003's height: uniform in the zone's range scaled by 1 - distance / radius (down to
// half at the city's edge); the top doubles with a chance of 0.1 × that scale².
double building_height(const ZoneParams& p, double distance, double radius, Random& rng);

}  // namespace exacity
