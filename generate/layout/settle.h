// A layout's planned roads made into a network (no map needed): ends that nearly meet are
// joined (within the plan's join distance); an end left open runs on ahead to another of
// the roads, or to the centre line of a sketch road whose surface it reaches, or to the
// region's edge; a road with an end that reaches none of them is dropped, until none is.
// Roads that would repeat others (a segment another already has, a road inside another's
// surface) are left out. Roads that meet, directly or through others, are one piece.
#pragma once

#include <vector>

#include "generate/layout/road_layout.h"
#include "geom/cell.h"

namespace exacity {

struct SettledRoad {
  geom::Path path;
  double width = 0;
  RoadClass road_class = RoadClass::Local;
  int piece = 0;                // roads of one piece meet, directly or through others
  bool reaches_sketch = false;  // its piece runs on to a sketch road
};

// `sketch_roads`: the sketch's centre lines; `sketch_width` the widest of them.
std::vector<SettledRoad> settle(const RoadPlan& plan, const geom::Cell& region, const std::vector<geom::Path>& sketch_roads,
                                double sketch_width);

}  // namespace exacity
