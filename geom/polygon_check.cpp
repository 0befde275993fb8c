#include "geom/polygon_check.h"
#include "geom/polygon_slabs.h"

#include <algorithm>
#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/convex_hull_2.h>

#include "geom/exact.h"
#include "geom/grid.h"
#include "geom/orientation.h"
#include "geom/planar_map.h"

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

std::set<std::pair<int, int>> overlapping_pairs(const std::vector<const Polygon*>& polygons) {
  PlanarMap map;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    map.add_ring(polygons[i]->outer, static_cast<int>(i));
    for (const Ring& h : polygons[i]->holes) map.add_ring(h, static_cast<int>(i));
  }
  map.insert_batch();
  std::set<std::pair<int, int>> pairs;
  map.label_faces([&](const Windings& w) {
    std::vector<int> inside;
    for (auto [counter, winding] : w)
      if (winding != 0) inside.push_back(counter);
    for (std::size_t a = 0; a < inside.size(); ++a)
      for (std::size_t b = a + 1; b < inside.size(); ++b) pairs.insert({std::min(inside[a], inside[b]), std::max(inside[a], inside[b])});
    return 0;
  });
  return pairs;
}

bool interiors_overlap(const Polygon& a, const Polygon& b) {
  // Most pairs a caller asks about lie apart: the closed regions' test decides those
  // without building a map.
  return rings_meet(a.outer, b.outer) && !overlapping_pairs({&a, &b}).empty();
}

int ring_orientation(const Ring& ring) {
  if (ring.size() < 3 || !ring_is_simple(ring)) return 0;
  auto pts = points(ring);
  return static_cast<int>(CGAL::orientation_2(pts.begin(), pts.end(), K()));
}

namespace {

// Whether the closed segments a-b and c-d meet.
bool segments_meet(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  // Boxes apart (comparisons of the doubles, exact): most pairs of a ring's edges, asked no predicate.
  if (std::max(a.x, b.x) < std::min(c.x, d.x) || std::max(c.x, d.x) < std::min(a.x, b.x) ||
      std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y))
    return false;
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && in_segment_box(a, b, c)) || (o2 == 0 && in_segment_box(a, b, d)) ||
         (o3 == 0 && in_segment_box(c, d, a)) || (o4 == 0 && in_segment_box(c, d, b));
}

// Whether u and w (collinear with s, neither s) lie on the same side of s on their line.
bool same_side_of(Vec2 s, Vec2 u, Vec2 w) {
  if (u.x != s.x) return (u.x < s.x) == (w.x < s.x);
  return (u.y < s.y) == (w.y < s.y);  // an upright line
}

// Rings of up to this many vertices are asked pair of edges by pair (small_ring_is_simple).
constexpr std::size_t kSmallRing = 64;

// ring_is_simple of a ring of finite coordinates and 3 to kSmallRing vertices, asking every
// pair of edges exactly: no vertex repeated, edges apart but neighbours, which meet only at
// their shared vertex (not folding back along each other). CGAL's sweep allocated its way
// through each footprint, lot and block of a city (a test compares the two).
bool small_ring_is_simple(const Ring& r) {
  const std::size_t n = r.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (r[i] == r[j]) return false;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec2 a = r[i], b = r[(i + 1) % n], c = r[j], d = r[(j + 1) % n];
      if (j == i + 1) {  // b = c
        if (orient(a, b, d) == 0 && same_side_of(b, a, d)) return false;
      } else if (i == 0 && j == n - 1) {  // d = a
        if (orient(c, a, b) == 0 && same_side_of(a, c, b)) return false;
      } else if (segments_meet(a, b, c, d)) {
        return false;
      }
    }
  return true;
}

}  // namespace

bool ring_is_simple(const Ring& ring) {
  if (ring.size() < 3) return false;
  if (ring.size() <= kSmallRing &&
      std::all_of(ring.begin(), ring.end(), [](Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }))
    return small_ring_is_simple(ring);
  return cgal_ring_is_simple(ring);
}

bool cgal_ring_is_simple(const Ring& ring) {
  if (ring.size() < 3) return false;
  auto pts = points(ring);
  return CGAL::is_simple_2(pts.begin(), pts.end(), K());
}

namespace {

// point_side's step for the edge u-v: true when p lies on it; else `inside` flips when the
// edge crosses the horizontal line through p right of p.
bool on_edge_or_cross(Vec2 u, Vec2 v, Vec2 p, bool& inside) {
  // An edge whose box leaves p's height holds no p and crosses no line through it; one
  // wholly left or right of p holds no p either, and its crossing, if any, lies on that
  // side: the orientation below would say as much, so it is asked only of the edges whose
  // box holds p (comparisons of written doubles: exact).
  if (p.y < std::min(u.y, v.y) || p.y > std::max(u.y, v.y) || p.x > std::max(u.x, v.x)) return false;
  if (p.x < std::min(u.x, v.x)) {
    if ((u.y <= p.y) != (v.y <= p.y)) inside = !inside;
    return false;
  }
  if (p == u) return true;  // a vertex, as validation's proofs ask of shared ones: no predicate
  const CGAL::Orientation o = CGAL::orientation(K::Point_2(u.x, u.y), K::Point_2(v.x, v.y), K::Point_2(p.x, p.y));
  if (o == CGAL::COLLINEAR) return true;  // on the line and in the edge's box: on the edge
  // An edge across the horizontal line through p (its lower end on or below it) crosses
  // it right of p when p lies left of the edge going up, right of it going down.
  if ((u.y <= p.y) != (v.y <= p.y) && (v.y > u.y) == (o == CGAL::LEFT_TURN)) inside = !inside;
  return false;
}

// A polygon's side from its rings' (ring 0 the outer one, then the holes): inside its outer
// ring and outside every hole, on the boundary where on any of them.
template <class RingSide>
int polygon_side(std::size_t rings, RingSide side_of) {
  int side = side_of(0);
  for (std::size_t r = 1; r < rings && side > 0; ++r) side = std::min(side, -side_of(r));
  return side;
}

}  // namespace

int point_side(const Ring& ring, Vec2 p) {
  if (ring.size() < 3) return -1;
  // The crossing rule on exact orientations, as CGAL::bounded_side_2 decides it, without
  // copying the ring into CGAL's points: validation asks this of every clutter point
  // against every area near it, and of every vertex its proofs look at.
  bool inside = false;
  for (std::size_t i = 0; i < ring.size(); ++i)
    if (on_edge_or_cross(ring[i], ring[(i + 1) % ring.size()], p, inside)) return 0;
  return inside ? 1 : -1;
}

PolygonSlabs::RingSlabs PolygonSlabs::slabs_of(const Ring& ring) {
  RingSlabs r;
  r.ring = &ring;
  if (ring.size() < 3) return r;
  double y1 = ring[0].y;
  r.y0 = ring[0].y;
  for (Vec2 v : ring) r.y0 = std::min(r.y0, v.y), y1 = std::max(y1, v.y);
  const int count = static_cast<int>(std::clamp<std::size_t>(ring.size() / 4, 1, 1024));
  r.height = (y1 - r.y0) / count;
  if (!(r.height > 0)) r.height = 1;  // a level ring, or one too thin to divide: one slab holds all
  r.start.assign(count + 1, 0);
  // Each edge in every slab from its lower end's to its upper end's: slab() grows with y,
  // so a point at a height the edge spans lies in one of them.
  auto each = [&](auto&& f) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 u = ring[i], v = ring[(i + 1) % ring.size()];
      for (int k = r.slab(std::min(u.y, v.y)); k <= r.slab(std::max(u.y, v.y)); ++k) f(k, i);
    }
  };
  each([&](int k, std::size_t) { ++r.start[k + 1]; });
  for (int k = 0; k < count; ++k) r.start[k + 1] += r.start[k];
  r.edges.resize(r.start[count]);
  std::vector<std::uint32_t> next(r.start.begin(), r.start.end() - 1);
  each([&](int k, std::size_t i) { r.edges[next[k]++] = static_cast<std::uint32_t>(i); });
  return r;
}

int PolygonSlabs::RingSlabs::slab(double y) const {
  const double k = std::floor((y - y0) / height);
  return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(start.size() - 2)));
}

int PolygonSlabs::RingSlabs::side(Vec2 p) const {
  if (ring->size() < 3) return -1;
  // An edge outside p's slab does not span p's height: point_side passes it by.
  bool inside = false;
  const int k = slab(p.y);
  for (std::uint32_t e = start[k]; e < start[k + 1]; ++e) {
    const std::size_t i = edges[e];
    if (on_edge_or_cross((*ring)[i], (*ring)[(i + 1) % ring->size()], p, inside)) return 0;
  }
  return inside ? 1 : -1;
}

PolygonSlabs::PolygonSlabs(const Polygon& polygon) {
  rings_.push_back(slabs_of(polygon.outer));
  for (const Ring& hole : polygon.holes) rings_.push_back(slabs_of(hole));
}

int PolygonSlabs::side(Vec2 p) const {
  return polygon_side(rings_.size(), [&](std::size_t r) { return rings_[r].side(p); });
}

int point_side(const Polygon& polygon, Vec2 p) {
  return polygon_side(polygon.holes.size() + 1,
                      [&](std::size_t r) { return point_side(r == 0 ? polygon.outer : polygon.holes[r - 1], p); });
}

bool rings_meet(const Ring& a, const Ring& b) {
  if (a.empty() || b.empty()) return false;
  Box ba = Box::none(), bb = Box::none();
  for (Vec2 v : a) ba.add(v);
  for (Vec2 v : b) bb.add(v);
  if (ba.max_x < bb.min_x || bb.max_x < ba.min_x || ba.max_y < bb.min_y || bb.max_y < ba.min_y) return false;
  auto pa = points(a), pb = points(b);
  for (std::size_t i = 0; i < pa.size(); ++i) {
    K::Segment_2 s(pa[i], pa[(i + 1) % pa.size()]);
    for (std::size_t j = 0; j < pb.size(); ++j)
      if (CGAL::do_intersect(s, K::Segment_2(pb[j], pb[(j + 1) % pb.size()]))) return true;
  }
  // No edges meet: either one lies inside the other or they are apart.
  return CGAL::bounded_side_2(pb.begin(), pb.end(), pa[0], K()) != CGAL::ON_UNBOUNDED_SIDE ||
         CGAL::bounded_side_2(pa.begin(), pa.end(), pb[0], K()) != CGAL::ON_UNBOUNDED_SIDE;
}

bool ring_within(const Ring& ring, const Ring& outer) {
  const auto o = points(outer);
  for (Vec2 v : ring) {
    auto side = CGAL::bounded_side_2(o.begin(), o.end(), K::Point_2(v.x, v.y), K());
    if (side != CGAL::ON_BOUNDARY) return side == CGAL::ON_BOUNDED_SIDE;
  }
  // Every vertex on the outer ring: an edge's midpoint, constructed exactly, decides.
  using E = exact::Kernel;
  std::vector<E::Point_2> oe;
  for (Vec2 v : outer) oe.emplace_back(v.x, v.y);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
    auto side = CGAL::bounded_side_2(oe.begin(), oe.end(), CGAL::midpoint(E::Point_2(a.x, a.y), E::Point_2(b.x, b.y)), E());
    if (side != CGAL::ON_BOUNDARY) return side == CGAL::ON_BOUNDED_SIDE;
  }
  return true;  // the same ring
}

int compare_sums(double a, double b, double c, double d) {
  using Q = CGAL::Exact_rational;
  const Q x = Q(a) + Q(b), y = Q(c) + Q(d);
  return x < y ? -1 : y < x ? 1 : 0;
}

Ring convex_hull(const std::vector<Vec2>& points) {
  std::vector<K::Point_2> pts, hull;
  for (Vec2 p : points) pts.emplace_back(p.x, p.y);
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull), K());
  Ring ring;
  for (const auto& p : hull) ring.push_back({p.x(), p.y()});
  return ring;
}

Ring polygon_around(const std::vector<Vec2>& points, int sides) {
  // Side k lies on {p : p . u_k = h_k}, u_k pointing out at angle 2 pi k / sides.
  std::vector<Vec2> normal(sides);
  std::vector<double> reach(sides, -INFINITY);
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * M_PI * k / sides;
    normal[k] = {std::cos(a), std::sin(a)};
    for (Vec2 p : points) reach[k] = std::max(reach[k], p.x * normal[k].x + p.y * normal[k].y);
    reach[k] += 2 * kGridStep;
  }
  Ring ring;
  for (int k = 0; k < sides; ++k) {
    const Vec2 u = normal[k], w = normal[(k + 1) % sides];
    const double det = u.x * w.y - u.y * w.x, h = reach[k], g = reach[(k + 1) % sides];
    const Vec2 corner = snap(Vec2{(h * w.y - g * u.y) / det, (u.x * g - w.x * h) / det});
    if (ring.empty() || !(corner == ring.back())) ring.push_back(corner);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  return ring;
}

}  // namespace geom
