// What stands on one lot piece so far, and the exact test every placer shares: a footprint
// may stand where it is a simple counter-clockwise ring strictly inside the piece (so off
// roads, water and parks) and apart from every footprint already there. Placers propose
// places in doubles, on the grid; this test, made exactly, has the last word. With seed
// 001's nesting a model given with its slabs may overlap another in plan where their slabs
// prove one lies wholly below the other there (docs/design.md, Placement: nesting).
#pragma once

#include <optional>
#include <vector>

#include "generate/city/terrain.h"
#include "generate/placement/slabs.h"
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
  // `road_kind`: the edge kind of the piece's road frontage. `terrain` (may be null) gives
  // the ground under what stands, which nested models' heights count from.
  Occupancy(const geom::Cell& piece, int road_kind, const Terrain* terrain = nullptr)
      : piece_(piece), road_kind_(road_kind), terrain_(terrain) {}

  const geom::Cell& piece() const { return piece_; }
  const Frontage& frontage() const {
    if (!frontage_) frontage_ = principal_frontage(piece_, road_kind_);
    return *frontage_;
  }
  // Whether the ring lies inside the piece, whatever stands there (a clearance around a
  // footprint, say).
  bool inside(const geom::Ring& ring) const;
  // Whether the ring may stand here now: apart from every footprint taken, or, given its
  // slabs (heights from its floor, the lowest from its base), meeting only footprints taken
  // with slabs that its slabs do not meet (slabs_meet).
  bool free(const geom::Ring& ring, const std::vector<Slab>* slabs = nullptr) const;
  // Takes the ring's place when it is free; whether it did.
  bool take(const geom::Ring& ring, const std::vector<Slab>* slabs = nullptr);
  // Mapped footprints' outer rings (simple, counter-clockwise) standing on the piece
  // already, which may reach past it (docs/design.md, Mapped buildings): no ring taken
  // meets them, and `area_m2`, their area on the piece, counts as covered.
  void stand(std::vector<geom::Ring> rings, double area_m2);
  // Whether mapped footprints stand here, their area on the piece, and whether the ring
  // meets none of them.
  bool has_standing() const { return !standing_.empty(); }
  double standing_m2() const { return standing_m2_; }
  bool apart_from_standing(const geom::Ring& ring) const;
  // The lowest and highest ground under the ring (the base and floor a structure there
  // gets); 0 and 0 without terrain.
  std::pair<double, double> ground_under(const geom::Ring& ring) const;

 private:
  struct Taken {
    geom::Ring ring;
    std::vector<Slab> slabs;  // empty: the footprint's whole column
    double floor = 0;
  };
  const geom::Cell& piece_;
  int road_kind_;
  const Terrain* terrain_;
  mutable std::optional<Frontage> frontage_;
  std::vector<Taken> taken_;
  std::vector<geom::Ring> standing_;
  double standing_m2_ = 0;
};

}  // namespace exacity
