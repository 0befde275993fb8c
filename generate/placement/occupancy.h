// What stands on one lot piece so far, and the exact test every placer shares: a footprint
// may stand where it is a simple counter-clockwise ring strictly inside the piece (so off
// roads, water and parks) and apart from every footprint already there. Placers propose
// places in doubles, on the grid; this test, made exactly, has the last word.
#pragma once

#include <optional>
#include <vector>

#include "geom/cell.h"
#include "geom/plain.h"

namespace exacity {

// The edge rows run along: the piece's longest road frontage (or its longest edge, for a
// piece with none: `on_road` false), its direction u from a, the inward normal n, and the
// piece's extent along u (t0 to t1) and along n (depth).
struct Frontage {
  geom::Vec2 a, u, n;
  double t0 = 0, t1 = 0, depth = 0;
  bool on_road = false;
  geom::Vec2 at(double t, double d) const { return {a.x + u.x * t + n.x * d, a.y + u.y * t + n.y * d}; }
};
Frontage principal_frontage(const geom::Cell& piece, int road_kind);

class Occupancy {
 public:
  // `road_kind`: the edge kind of the piece's road frontage.
  Occupancy(const geom::Cell& piece, int road_kind) : piece_(piece), road_kind_(road_kind) {}

  const geom::Cell& piece() const { return piece_; }
  const Frontage& frontage() const {
    if (!frontage_) frontage_ = principal_frontage(piece_, road_kind_);
    return *frontage_;
  }
  // Whether the ring lies inside the piece, whatever stands there (a clearance around a
  // footprint, say).
  bool inside(const geom::Ring& ring) const;
  // Whether the ring may stand here now.
  bool free(const geom::Ring& ring) const;
  // Takes the ring's place when it is free; whether it did.
  bool take(const geom::Ring& ring);

 private:
  const geom::Cell& piece_;
  int road_kind_;
  mutable std::optional<Frontage> frontage_;
  std::vector<geom::Ring> taken_;
};

}  // namespace exacity
