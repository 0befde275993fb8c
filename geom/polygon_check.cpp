#include "geom/polygon_check.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

namespace geom {
namespace {

// Doubles in, predicates only: the filtered inexact kernel decides these exactly.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

std::vector<K::Point_2> points(const Ring& ring) {
  std::vector<K::Point_2> pts;
  pts.reserve(ring.size());
  for (Vec2 p : ring) pts.emplace_back(p.x, p.y);
  return pts;
}

}  // namespace

int ring_orientation(const Ring& ring) {
  if (ring.size() < 3 || !ring_is_simple(ring)) return 0;
  auto pts = points(ring);
  return static_cast<int>(CGAL::orientation_2(pts.begin(), pts.end(), K()));
}

bool ring_is_simple(const Ring& ring) {
  if (ring.size() < 3) return false;
  auto pts = points(ring);
  return CGAL::is_simple_2(pts.begin(), pts.end(), K());
}

}  // namespace geom
