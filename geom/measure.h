// Measures in doubles, for choices and reports (never for topology).
#pragma once

#include <algorithm>
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

// The ring with every edge split into equal pieces no longer than `step` (samples along
// it, not geometry).
inline Ring densified(const Ring& r, double step) {
  Ring out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 a = r[i], b = r[(i + 1) % r.size()];
    const int n = std::max(1, static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / step)));
    for (int k = 0; k < n; ++k) out.push_back({a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n});
  }
  return out;
}

// Whether the ring crosses a ray from p an odd number of times (even-odd rule, in
// doubles: for sampling, not for topology).
inline bool odd_crossings(const Ring& r, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    if ((r[i].y > p.y) != (r[j].y > p.y) && p.x < r[j].x + (r[i].x - r[j].x) * (p.y - r[j].y) / (r[i].y - r[j].y))
      in = !in;
  return in;
}

// Whether p lies inside the polygon by the even-odd rule over all its rings.
inline bool odd_crossings(const Polygon& polygon, Vec2 p) {
  bool in = odd_crossings(polygon.outer, p);
  for (const Ring& h : polygon.holes) in ^= odd_crossings(h, p);
  return in;
}

// The point of the segment ab nearest p (a, when the segment has no length).
inline Vec2 nearest_on_segment(Vec2 p, Vec2 a, Vec2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0;
  return {a.x + t * dx, a.y + t * dy};
}

// The distance from p to the segment ab (to a, when the segment has no length).
inline double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 n = nearest_on_segment(p, a, b);
  return std::hypot(n.x - p.x, n.y - p.y);
}

// The distance from p to the nearest edge of any of the polygon's rings.
inline double distance_to_outline(const Polygon& polygon, Vec2 p) {
  double d = INFINITY;
  auto visit = [&](const Ring& r) {
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) d = std::min(d, distance_to_segment(p, r[j], r[i]));
  };
  visit(polygon.outer);
  for (const Ring& h : polygon.holes) visit(h);
  return d;
}

// A lot's depth over its width: its extent across `frontage` (a, b: the edge it fronts the
// street by) over its extent along it; 0 for a zero-length frontage.
inline double depth_over_width(const Ring& r, Vec2 a, Vec2 b) {
  if (a == b) return 0;
  const Vec2 u = unit_along(a, b);
  Box box = Box::none();
  for (Vec2 v : r) box.add(Vec2{v.x * u.x + v.y * u.y, -v.x * u.y + v.y * u.x});
  return box.width() > 0 ? box.height() / box.width() : 0;
}

// How many times the ring winds around p, counter-clockwise positive (in doubles; a point on
// the ring may count either way).
inline int winding_number(const Ring& r, Vec2 p) {
  int w = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 a = r[i], b = r[(i + 1) % r.size()];
    const double side = (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y);
    if (a.y <= p.y && b.y > p.y && side > 0) ++w;
    if (a.y > p.y && b.y <= p.y && side < 0) --w;
  }
  return w;
}

}  // namespace geom
