// A layout's roads drawn in doubles, made an exact network (no map needed): ends that nearly
// meet are joined (within the plan's join distance); an end left open runs on ahead to
// another of the roads, or to the centre line of a sketch road whose surface it reaches, or
// to the region's edge; a road with an end that reaches none of them is dropped, until none
// is. Roads that would repeat others (a segment another already has, a road inside
// another's surface) are left out. Roads that meet, directly or through others, are one
// piece; where roads share a point, a junction.
#pragma once

#include <vector>

#include "generate/layout/road_layout.h"

namespace exacity {

struct PlannedRoad {
  geom::Polyline line;  // centre line, in doubles on the grid
  double width = 0;
  RoadClass road_class = RoadClass::Local;
};

struct LinePlan {
  std::vector<PlannedRoad> roads;
  std::vector<PlannedUse> uses;
  double join = 0;  // m: road ends this near another road are joined to it (generate/city/street_graph.h)
};

RoadPlan settle(LinePlan plan, const geom::Cell& region, const SketchLines& sketch);

}  // namespace exacity
