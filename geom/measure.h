// Measures in doubles, for choices and reports (never for topology).
#pragma once

#include <cmath>

#include "geom/plain.h"

namespace geom {

// Signed area: positive for counter-clockwise rings. Computed relative to the first vertex,
// so large coordinates do not swamp small areas.
inline double signed_area(const Ring& r) {
  double a = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 &o = r[0], &u = r[i], &v = r[(i + 1) % r.size()];
    a += (u.x - o.x) * (v.y - o.y) - (v.x - o.x) * (u.y - o.y);
  }
  return a / 2;
}

// Outer area less the holes' (holes are clockwise, so their signed areas are negative).
inline double area(const Polygon& p) {
  double a = signed_area(p.outer);
  for (const auto& h : p.holes) a += signed_area(h);
  return a;
}

inline double perimeter(const Polygon& p) {
  double sum = 0;
  auto ring = [&](const Ring& r) {
    for (std::size_t i = 0; i < r.size(); ++i) sum += std::hypot(r[(i + 1) % r.size()].x - r[i].x, r[(i + 1) % r.size()].y - r[i].y);
  };
  ring(p.outer);
  for (const auto& h : p.holes) ring(h);
  return sum;
}

}  // namespace geom
