// Buildings: a footprint inside each lot, inset by the zone's setback (DESIGN.md rule 3),
// exact; its height drawn between the zone's range, which falls with distance from the
// city centre, with a small chance near the centre of doubling (seed 003).
#pragma once

#include <vector>

#include "generate/lots.h"
#include "generate/random.h"
#include "generate/sketch.h"
#include "generate/zone_map.h"

namespace exacity {

struct Building {
  int lot = -1;  // index into the lots
  ZoneType zone = ZoneType::Residential;
  geom::Cell footprint;    // exact
  geom::Polygon polygon;   // rounded
  double height = 0;       // m
};

// One building per lot piece big enough, lot by lot in parallel.
std::vector<Building> place_buildings(const ZoneMap& zone_map, const std::vector<Lot>& lots, const Sketch& sketch);

// Seed 003's height: uniform in the zone's range scaled by 1 - distance / radius (down to
// half at the city's edge); the top doubles with a chance of 0.1 × that scale².
double building_height(const ZoneParams& p, double distance, double radius, Random& rng);

}  // namespace exacity
