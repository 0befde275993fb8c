// The roads stage: every region's roads planned by its zone's RoadLayout
// (generate/layout/road_layout.h; recursive road growth in growth.h), links that join islands
// of streets to the rest, then every generated road into the city map in one batch.
#pragma once

#include "generate/city/city_map.h"
#include "generate/city/features.h"
#include "generate/city/memo.h"
#include "generate/city/zone_settings.h"
#include "generate/layout/road_layout.h"

namespace exacity {

struct RoadNetworkStats {
  int regions = 0;
  int levels = 0;
  int cells_without_access = 0;  // cells left whole: none of their roads could reach a road
  int links = 0;                 // roads added to join a region's streets to the rest (link_islands)
  int dropped_roads = 0;         // a layout's drawn roads that reached nothing (RoadPlan::dropped_roads)
};

struct RoadNetwork {
  CityMap map;  // the city map with the generated roads' centre lines and areas, relabelled
  RoadNetworkStats stats;
  std::vector<PlannedUse> uses;  // land a layout gave a use (a grammar's terminals)
};

// With a memo, each region's plan is taken from it when its region, stream and the drawn
// zones over it are as before (docs/design.md, Regions and regenerating).
RoadNetwork grow_road_network(CityMap zones, const CitySettings& settings, const std::vector<ZoneFeature>& drawn_zones,
                              Memo<RoadPlan>* memo = nullptr);

}  // namespace exacity
