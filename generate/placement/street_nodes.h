// Where the centre lines meet (for street clutter): the roads layer is a noded network, every
// junction a vertex of each line through it (docs/design.md, Outputs), so its nodes are found
// by exact equality of written vertices, with no tolerance. A node where three or more arms
// leave is a junction; traffic lights stand at the corners of junctions of major roads, stop
// signs on the local roads' approaches to major ones.
#pragma once

#include <vector>

#include "generate/city/ground.h"
#include "geom/plain.h"

namespace exacity {

// Highways and main roads; local roads are minor.
inline bool is_major(RoadClass c) { return c != RoadClass::Local; }

// A centre line leaving a node: the road (its id in the roads layer), the unit direction
// towards its next vertex, its class and half width. (Not the sketch reader's StreetArm,
// generate/city/street_graph.h: one name, one type, in the whole program.)
struct RoadArm {
  int road = -1;
  geom::Vec2 toward;
  RoadClass road_class = RoadClass::Local;
  double half_width = 0;
};

// A node of the network where three or more arms leave, its arms counter-clockwise by angle.
struct StreetJunction {
  geom::Vec2 at;
  std::vector<RoadArm> arms;
  int major_arms() const;
  // Major roads meet here (three or more major arms: not a major road passing a local one).
  bool of_major_roads() const { return major_arms() >= 3; }
  // Local roads meet a major road here without major roads meeting each other.
  bool local_meets_major() const {
    return major_arms() > 0 && !of_major_roads() && major_arms() < static_cast<int>(arms.size());
  }
  // How far from `at` the junction's surface reaches along any arm, about: its widest arm.
  double reach() const;
};

// The junctions of the centre lines, in the order their node first appears along the roads;
// lines on bridges count like any other.
std::vector<StreetJunction> street_junctions(const std::vector<RoadLine>& roads);

}  // namespace exacity
