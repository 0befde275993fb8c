// Buildings: a footprint inside each lot, inset by the zone's setback (DESIGN.md rule 3),
// exact; its height drawn between the zone's range, which falls with distance from the
// city centre, with a small chance near the centre of doubling (seed 003).
#pragma once

#include <vector>

#include "generate/lots.h"
#include "generate/random.h"
#include "generate/sketch.h"
#include "generate/zone_map.h"
#include "geom/roof.h"

namespace exacity {

struct Building {
  int lot = -1;  // index into the lots
  ZoneType zone = ZoneType::Residential;
  geom::Cell footprint;    // exact
  geom::Polygon polygon;   // rounded
  double height = 0;       // m, to the top of the roof
  std::string roof = "flat";
  double eaves = 0;        // m: where walls meet a pitched roof (the height, for flat roofs)
  std::vector<geom::Face3> roof_faces;  // pitched roofs only, in place
};

// The roof a footprint gets: its kind, its faces (none for flat) and the eaves height.
// A pitched roof rising over half the building's height, or whose skeleton leaves the
// footprint, falls back to flat.
void choose_roof(Building& b, const ZoneParams& p);

// One building per lot piece big enough, lot by lot in parallel.
std::vector<Building> place_buildings(const ZoneMap& zone_map, const std::vector<Lot>& lots, const Sketch& sketch);

// Seed 003's height: uniform in the zone's range scaled by 1 - distance / radius (down to
// half at the city's edge); the top doubles with a chance of 0.1 × that scale².
double building_height(const ZoneParams& p, double distance, double radius, Random& rng);

}  // namespace exacity
