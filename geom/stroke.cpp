// Road-area strokes by DESIGN.md rule 3: every offset line runs through two grid points
// computed in doubles, and a mitre point is the exact meeting of two such lines.
#include <cmath>

#include <CGAL/Polygon_2_algorithms.h>

#include "geom/exact.h"
#include "geom/grid.h"

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

struct Side {
  Vec2 start, end;  // the offset segment's grid points
};

}  // namespace

std::vector<ExactRing> stroke_pieces(const Polyline& input, double hw) {
  Polyline line;
  for (Vec2 p : input)
    if (line.empty() || !(line.back() == p)) line.push_back(p);
  std::vector<ExactRing> pieces;
  if (line.size() < 2) return pieces;

  std::vector<Side> left, right;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    Vec2 p = line[i], q = line[i + 1];
    double dx = q.x - p.x, dy = q.y - p.y, len = std::hypot(dx, dy);
    Vec2 n{-dy / len, dx / len};
    left.push_back({offset(p, n, hw), offset(q, n, hw)});
    right.push_back({offset(p, n, -hw), offset(q, n, -hw)});
    ExactRing quad = counter_clockwise({to_exact(right.back().start), to_exact(right.back().end),
                                        to_exact(left.back().end), to_exact(left.back().start)});
    if (!quad.empty()) pieces.push_back(std::move(quad));
  }

  // Joints: fill the gap on the outer side of each bend.
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    Point a = to_exact(line[i - 1]), q = to_exact(line[i]), b = to_exact(line[i + 1]);
    CGAL::Orientation turn = CGAL::orientation(a, q, b);
    if (turn == CGAL::COLLINEAR) continue;
    const Side& s0 = turn == CGAL::LEFT_TURN ? right[i - 1] : left[i - 1];
    const Side& s1 = turn == CGAL::LEFT_TURN ? right[i] : left[i];
    Point r0 = to_exact(s0.end), r1 = to_exact(s1.start);
    ExactRing wedge;
    Line l0(to_exact(s0.start), r0), l1(r1, to_exact(s1.end));
    auto meet = CGAL::intersection(l0, l1);
    if (meet) {
      if (const Point* m = boost::get<Point>(&*meet)) {
        Vec2 mp = to_plain(*m);
        double reach = std::hypot(mp.x - line[i].x, mp.y - line[i].y);
        if (reach <= kMitreLimit * hw) wedge = counter_clockwise({q, r0, *m, r1});
      }
    }
    if (wedge.empty()) wedge = counter_clockwise({q, r0, r1});  // bevel
    if (!wedge.empty()) pieces.push_back(std::move(wedge));
  }
  return pieces;
}

}  // namespace geom::exact
