// The sketch's roads as a street graph (docs/design.md, Road layouts): lines drawn by hand
// nearly meet, so ends are joined first; then every point where lines meet is a node with
// the streets leaving it, and a line end that meets nothing is a dead end.
#pragma once

#include <vector>

#include "generate/city/features.h"

namespace exacity {

// Joins line ends that nearly meet: an end within `snap` metres of another line's end
// moves onto the first such end; one within `snap` of another line's side moves onto its
// nearest point there (rounded to the grid), which becomes a vertex of that line too.
// Returns how many ends moved. In sketch order, so the result is deterministic.
int join_near_ends(std::vector<RoadFeature>& roads, double snap);

// A street leaving a node.
struct StreetArm {
  int road = 0;       // index into the roads
  geom::Vec2 toward;  // the next vertex along the line
  double length = 0;  // m along the line to its end that way
};

// A point where two or more streets meet: line ends meeting end to end, or lines meeting
// at a vertex they share. A line's own bends are no nodes.
struct StreetNode {
  geom::Vec2 at;
  std::vector<StreetArm> arms;
};

std::vector<StreetNode> street_nodes(const std::vector<RoadFeature>& roads);

// Line ends that are no vertex of any other line (nor of their own line elsewhere).
std::vector<DeadEnd> dead_ends(const std::vector<RoadFeature>& roads);

}  // namespace exacity
