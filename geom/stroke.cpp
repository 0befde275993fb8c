// Road-area strokes by DESIGN.md rule 3: every offset line runs through two grid points
// computed in doubles, and a mitre point is the exact meeting of two such lines.
#include <cmath>

#include <CGAL/Polygon_2_algorithms.h>

#include "geom/exact.h"
#include "geom/grid.h"
#include "geom/ring_cleanup.h"

namespace geom::exact {
namespace {

constexpr double kMitreLimit = 4.0;  // mitre length / half width, as SVG's default

Vec2 offset(Vec2 p, Vec2 n, double d) { return snap(Vec2{p.x + n.x * d, p.y + n.y * d}); }

// The same ring, counter-clockwise; empty when it has no area or is not simple.
ExactRing counter_clockwise(ExactRing r) {
  if (r.size() < 3 || !CGAL::is_simple_2(r.begin(), r.end(), Kernel())) return {};
  auto o = CGAL::orientation_2(r.begin(), r.end(), Kernel());
  if (o == CGAL::COLLINEAR) return {};
  if (o == CGAL::CLOCKWISE) std::reverse(r.begin(), r.end());
  return r;
}

// The offset of segment p -> q by d to its left, through two grid points.
std::pair<Point, Point> side(Vec2 p, Vec2 q, double d) {
  double dx = q.x - p.x, dy = q.y - p.y, len = std::hypot(dx, dy);
  Vec2 n{-dy / len, dx / len};
  return {to_exact(offset(p, n, d)), to_exact(offset(q, n, d))};
}

}  // namespace

ExactRing joint_piece(Vec2 a, Vec2 q, Vec2 b, double hw) {
  Point pa = to_exact(a), pq = to_exact(q), pb = to_exact(b);
  CGAL::Orientation turn = CGAL::orientation(pa, pq, pb);
  if (turn == CGAL::COLLINEAR) return {};
  // The outer side of the bend: right of a left turn, left of a right turn.
  double d = turn == CGAL::LEFT_TURN ? -hw : hw;
  auto [s0, r0] = side(a, q, d);
  auto [r1, s1] = side(q, b, d);
  auto meet = CGAL::intersection(Line(s0, r0), Line(r1, s1));
  if (meet) {
    if (const Point* m = boost::get<Point>(&*meet)) {
      Vec2 mp = to_plain(*m);
      if (std::hypot(mp.x - q.x, mp.y - q.y) <= kMitreLimit * hw) {
        ExactRing mitre = counter_clockwise({pq, r0, *m, r1});
        if (!mitre.empty()) return mitre;
      }
    }
  }
  return counter_clockwise({pq, r0, r1});  // bevel
}

Ring round_ring(const std::vector<Point>& points) {
  Ring r;
  r.reserve(points.size());
  for (const Point& p : points) r.push_back(to_plain(p));
  drop_repeats_and_spikes(r);
  return r;
}

ExactRing disc_piece(Vec2 c, double r) {
  // Circumscribed, so the disc of radius r lies inside it.
  constexpr int kSides = 16;
  const double R = r / std::cos(M_PI / kSides);
  ExactRing ring;
  for (int i = 0; i < kSides; ++i) {
    double t = 2 * M_PI * i / kSides;
    ring.push_back(to_exact(offset(c, Vec2{std::cos(t), std::sin(t)}, R)));
  }
  return counter_clockwise(std::move(ring));
}

std::vector<ExactRing> stroke_pieces(const Polyline& input, double hw) {
  Polyline line;
  for (Vec2 p : input)
    if (line.empty() || !(line.back() == p)) line.push_back(p);
  std::vector<ExactRing> pieces;
  if (line.size() < 2) return pieces;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    auto [left_start, left_end] = side(line[i], line[i + 1], hw);
    auto [right_start, right_end] = side(line[i], line[i + 1], -hw);
    ExactRing quad = counter_clockwise({right_start, right_end, left_end, left_start});
    if (!quad.empty()) pieces.push_back(std::move(quad));
  }
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    ExactRing joint = joint_piece(line[i - 1], line[i], line[i + 1], hw);
    if (!joint.empty()) pieces.push_back(std::move(joint));
  }
  return pieces;
}

}  // namespace geom::exact
