#include "geom/roof.h"

#include <algorithm>
#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/create_straight_skeleton_from_polygon_with_holes_2.h>

namespace geom {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polygon2 = CGAL::Polygon_2<K>;

Polygon2 polygon2(const Ring& r) {
  Polygon2 p;
  for (Vec2 v : r) p.push_back(K::Point_2(v.x, v.y));
  return p;
}

// Inside or on the boundary of the footprint, decided exactly on the doubles.
bool within(const CGAL::Polygon_with_holes_2<K>& p, const K::Point_2& q) {
  if (p.outer_boundary().bounded_side(q) == CGAL::ON_UNBOUNDED_SIDE) return false;
  for (auto h = p.holes_begin(); h != p.holes_end(); ++h)
    if (h->bounded_side(q) == CGAL::ON_BOUNDED_SIDE) return false;
  return true;
}

}  // namespace

std::vector<Face3> hipped_roof(const Polygon& footprint, double eaves, double slope) {
  CGAL::Polygon_with_holes_2<K> p(polygon2(footprint.outer));
  for (const Ring& h : footprint.holes) p.add_hole(polygon2(h));
  auto skeleton = CGAL::create_interior_straight_skeleton_2(p, K());
  if (!skeleton) return {};
  std::vector<Face3> faces;
  for (auto f = skeleton->faces_begin(); f != skeleton->faces_end(); ++f) {
    Face3 face;
    auto h = f->halfedge(), first = h;
    do {
      const auto& v = h->vertex();
      if (!within(p, v->point())) return {};  // a skeleton that leaves the footprint: no roof
      face.push_back({v->point().x(), v->point().y(), eaves + v->time() * slope});
      h = h->next();
    } while (h != first);
    faces.push_back(std::move(face));
  }
  return faces;
}

std::vector<Face3> gabled_roof(const Polygon& footprint, double eaves, double slope) {
  const Ring& r = footprint.outer;
  if (r.size() != 4 || !footprint.holes.empty()) return {};
  auto length = [&](int i) { return std::hypot(r[(i + 1) % 4].x - r[i].x, r[(i + 1) % 4].y - r[i].y); };
  // Eaves along edges k and k+2, gables on edges k+1 and k+3.
  int k = length(0) + length(2) >= length(1) + length(3) ? 0 : 1;
  Vec2 a = r[k], b = r[(k + 1) % 4], c = r[(k + 2) % 4], d = r[(k + 3) % 4];
  auto ridge_end = [&](Vec2 p, Vec2 q) {  // over the middle of a gable edge
    return Vec3{(p.x + q.x) / 2, (p.y + q.y) / 2, eaves + slope * std::hypot(q.x - p.x, q.y - p.y) / 2};
  };
  Vec3 rb = ridge_end(b, c), rd = ridge_end(d, a);
  auto at = [&](Vec2 p) { return Vec3{p.x, p.y, eaves}; };
  // The slopes are planar only for rectangles: split each into two triangles.
  return {{at(a), at(b), rb}, {at(a), rb, rd}, {at(c), at(d), rd}, {at(c), rd, rb}, {at(b), at(c), rb}, {at(d), at(a), rd}};
}

double roof_top(const std::vector<Face3>& faces) {
  double top = 0;
  for (const Face3& f : faces)
    for (const Vec3& v : f) top = std::max(top, v[2]);
  return top;
}

}  // namespace geom
