// Road growth (seed 000, 3.2.1) in exact vector form: from a seed point in each region,
// roads grow step by step until they meet a road or the region's edge; they split the
// region, and each part above its zone's block area is grown again, one level deeper.
#pragma once

#include "generate/layout/road_layout.h"
#include "generate/city/sketch.h"
#include "generate/city/city_map.h"

namespace exacity {

struct RoadNetworkStats {
  int regions = 0;
  int levels = 0;
  int cells_without_access = 0;  // cells left whole: none of their roads could reach a road
  int links = 0;                 // roads added to join a region's streets to the rest (link_islands)
};

struct RoadNetwork {
  CityMap map;  // the zone map with the grown roads' centre lines and areas, relabelled
  RoadNetworkStats stats;
  std::vector<PlannedUse> uses;  // land a layout gave a use (a grammar's terminals)
};

RoadNetwork grow_road_network(CityMap zones, const Sketch& sketch);

}  // namespace exacity
