// Models on one lot piece (seeds 001 and 002): buildings in rows parallel to the lot's
// principal road frontage, their fronts to the road, spaced by the zone's density and
// placed largest first; street furniture along the frontage inside the setback; trees
// where room is left. Every footprint is checked exactly: strictly inside the lot piece
// (so off roads, water and parks) and apart from every footprint already there.
#pragma once

#include <vector>

#include "generate/placement/buildings.h"

namespace exacity {

// The edge rows run along: the lot's longest road frontage (or its longest edge, for a lot
// with none: `on_road` false), its direction u from a, the inward normal n, and the lot's
// extent along u (t0 to t1) and along n (depth).
struct Frontage {
  geom::Vec2 a, u, n;
  double t0 = 0, t1 = 0, depth = 0;
  bool on_road = false;
  geom::Vec2 at(double t, double d) const { return {a.x + u.x * t + n.x * d, a.y + u.y * t + n.y * d}; }
};
Frontage principal_frontage(const geom::Cell& piece, int road_kind);

// Whether the ring is simple, counter-clockwise, strictly inside the piece and apart from
// every ring taken.
bool fits(const geom::Cell& piece, const geom::Ring& ring, const std::vector<geom::Ring>& taken);

// `taken`: footprints already on the piece. `road_kind`: the edge kind of road frontage.
std::vector<Building> place_models(const geom::Cell& piece, int road_kind, std::vector<geom::Ring>& taken,
                                   const std::vector<int>& choices, ModelKind kind, const ModelLibrary& library,
                                   const ZoneParams& params, Random& rng);

// The model's outline turned by `angle`, scaled and moved to `position`, on the grid.
geom::Ring placed_outline(const Model& model, const Placement& p);

}  // namespace exacity
