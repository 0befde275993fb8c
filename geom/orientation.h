// Orientation of points given in doubles, decided exactly (the filtered predicate of CGAL's
// inexact-constructions kernel), for the checks that ask it of many plain segments.
#pragma once

#include <algorithm>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "geom/plain.h"

namespace geom {

// +1 when c lies left of the line a -> b, -1 right, 0 on it.
inline int orient(Vec2 a, Vec2 b, Vec2 c) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  // Shared vertices are most of what the checks meet: no predicate for those (a filtered one
  // fails on an exact zero and computes again).
  if (c == a || c == b || a == b) return 0;
  return static_cast<int>(CGAL::orientation(K::Point_2(a.x, a.y), K::Point_2(b.x, b.y), K::Point_2(c.x, c.y)));
}

// p in the closed box of the segment u-v: on it, when the three are collinear.
inline bool in_segment_box(Vec2 u, Vec2 v, Vec2 p) {
  return std::min(u.x, v.x) <= p.x && p.x <= std::max(u.x, v.x) && std::min(u.y, v.y) <= p.y && p.y <= std::max(u.y, v.y);
}

}  // namespace geom
