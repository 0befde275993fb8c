// point_side for many points against one polygon of many vertices (implemented beside
// point_side, in geom/polygon_check.cpp, on the same edge step).
#pragma once

#include <cstdint>
#include <vector>

#include "geom/plain.h"

namespace geom {

// A polygon's edges sorted into horizontal slabs of its box, for many point_side questions
// of one polygon of many vertices (validation's clutter against a long carriageway): each
// question looks at the edges of the slab its point lies in, and gets point_side's answer.
class PolygonSlabs {
 public:
  explicit PolygonSlabs(const Polygon& polygon);
  int side(Vec2 p) const;

 private:
  struct RingSlabs {
    const Ring* ring;
    double y0 = 0, height = 1;            // the slabs' bottom and each one's height
    std::vector<std::uint32_t> start;     // slab k's edges are edges[start[k], start[k + 1])
    std::vector<std::uint32_t> edges;     // an edge i runs from ring[i] to the next vertex
    int slab(double y) const;
    int side(Vec2 p) const;
  };
  static RingSlabs slabs_of(const Ring& ring);
  std::vector<RingSlabs> rings_;  // the outer ring, then the holes
};

}  // namespace geom
