// Road-area strokes by docs/design.md, Exactness rule 3: every offset line runs through two grid points
// computed in doubles, and a mitre point is the exact meeting of two such lines.
#include <cmath>
#include <optional>

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
  const Vec2 n = left_normal(p, q);
  return {to_exact(offset(p, n, d)), to_exact(offset(q, n, d))};
}

// One street leaving a junction at q.
struct Arm {
  double angle, half_width, length;
  Vec2 toward, d;
  Line left, right;  // the stroke's sides, as add_stroke draws them
  Point left_at_q, right_at_q;
};

// The corner between arm i's left side and arm i + 1's right side, and how far along
// each arm it lies (0 when behind q).
struct Corner {
  std::vector<Point> points;
  double along_left = 0, along_right = 0;  // along arm i, along arm i + 1
};

// Streets of no length or no width leave no side to meet.
std::vector<Arm> arms_of(Vec2 q, const std::vector<JunctionArm>& input) {
  std::vector<Arm> arms;
  for (const JunctionArm& a : input) {
    const double dx = a.toward.x - q.x, dy = a.toward.y - q.y, to_next = std::hypot(dx, dy);
    if (to_next == 0 || a.half_width <= 0) continue;
    const double length = std::max(to_next, a.length);
    auto [l0, l1] = side(q, a.toward, a.half_width);
    auto [r0, r1] = side(q, a.toward, -a.half_width);
    arms.push_back({std::atan2(dy, dx), a.half_width, length, a.toward, {dx / to_next, dy / to_next}, Line(l0, l1),
                    Line(r0, r1), l0, r0});
  }
  return arms;
}

// By angle; streets leaving in one direction (a line drawn twice) are one arm, the widest.
void sort_and_merge(std::vector<Arm>& arms) {
  std::sort(arms.begin(), arms.end(), [](const Arm& a, const Arm& b) { return a.angle < b.angle; });
  for (std::size_t i = 1; i < arms.size();)
    if (arms[i].angle == arms[i - 1].angle) {
      if (arms[i].half_width > arms[i - 1].half_width) arms[i - 1] = arms[i];
      arms.erase(arms.begin() + i);
    } else {
      ++i;
    }
}

// Two streets running straight on meet flush, needing no junction.
bool straight_on(const std::vector<Arm>& arms) {
  return arms.size() == 2 && std::abs(arms[1].angle - arms[0].angle - M_PI) < 1e-9 &&
         arms[0].half_width == arms[1].half_width;
}

double along(const Arm& a, Vec2 q, Vec2 p) { return (p.x - q.x) * a.d.x + (p.y - q.y) * a.d.y; }

// The corner between arm a and the next arm b, `gap` radians on; none where their sides
// part only past their length.
std::optional<Corner> corner_between(Vec2 q, const Arm& a, const Arm& b, double gap) {
  Corner c;
  std::optional<Point> meet_point;
  if (auto meet = CGAL::intersection(a.left, b.right))
    if (const Point* p = boost::get<Point>(&*meet)) meet_point = constructed(*p);
  const Point* m = meet_point ? &*meet_point : nullptr;
  if (gap < M_PI) {
    // Inside a bend the streets part where their sides cross: on both streets, or within
    // the mitre limit of the node (a street shorter than the junction is wide, as
    // OpenStreetMap splits ways at every node, is paved a little past its end).
    if (!m) return std::nullopt;
    const Vec2 mp = to_plain(*m);
    c.along_left = along(a, q, mp), c.along_right = along(b, q, mp);
    const double limit = kMitreLimit * std::max(a.half_width, b.half_width);
    if (c.along_left > std::max(a.length, limit) || c.along_right > std::max(b.length, limit)) return std::nullopt;
    c.points = {*m};
  } else if (m && std::hypot(to_plain(*m).x - q.x, to_plain(*m).y - q.y) <=
                      kMitreLimit * std::max(a.half_width, b.half_width)) {
    const Vec2 mp = to_plain(*m);
    c.along_left = std::max(along(a, q, mp), 0.0), c.along_right = std::max(along(b, q, mp), 0.0);
    c.points = {*m};
  } else {
    c.points = {a.left_at_q, b.right_at_q};  // bevel
  }
  return c;
}

// corners[i] lies between arms i and i + 1 (the last between the last arm and the first).
std::optional<std::vector<Corner>> corners_of(Vec2 q, const std::vector<Arm>& arms) {
  const std::size_t k = arms.size();
  std::vector<Corner> corners(k);
  for (std::size_t i = 0; i < k; ++i) {
    const Arm &a = arms[i], &b = arms[(i + 1) % k];
    const double gap = b.angle - a.angle + (i + 1 == k ? 2 * M_PI : 0);
    std::optional<Corner> c = corner_between(q, a, b, gap);
    if (!c) return std::nullopt;
    corners[i] = std::move(*c);
  }
  return corners;
}

// Around q: each arm cut straight across through its farther corner, then the corner
// after it. None where a cut misses the arm's other side.
std::optional<ExactRing> star_ring(const std::vector<Arm>& arms, const std::vector<Corner>& corners) {
  const std::size_t k = arms.size();
  ExactRing ring;
  auto push = [&](const Point& p) {
    if (ring.empty() || ring.back() != p) ring.push_back(p);
  };
  for (std::size_t i = 0; i < k; ++i) {
    const Arm& a = arms[i];
    const Corner &before = corners[(i + k - 1) % k], &after = corners[i];
    const double t = std::max(before.along_right, after.along_left);
    if (t <= 0) {
      push(a.right_at_q), push(a.left_at_q);
    } else {
      const bool by_right = before.along_right >= after.along_left;
      const Point& through = by_right ? before.points.front() : after.points.front();
      const Line cut(through, Kernel::Vector_2(-a.d.y, a.d.x));
      auto other = CGAL::intersection(cut, by_right ? a.left : a.right);
      const Point* o = other ? boost::get<Point>(&*other) : nullptr;
      if (!o) return std::nullopt;
      if (by_right) push(through), push(constructed(*o));
      else push(constructed(*o)), push(through);
    }
    for (const Point& p : after.points) push(p);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  return ring;
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
    if (const Point* found = boost::get<Point>(&*meet)) {
      const Point m = constructed(*found);
      Vec2 mp = to_plain(m);
      if (std::hypot(mp.x - q.x, mp.y - q.y) <= kMitreLimit * hw) {
        ExactRing mitre = counter_clockwise({pq, r0, m, r1});
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

ExactRing junction_piece(Vec2 q, const std::vector<JunctionArm>& input) {
  std::vector<Arm> arms = arms_of(q, input);
  sort_and_merge(arms);
  if (arms.size() < 2 || straight_on(arms)) return {};
  const std::optional<std::vector<Corner>> corners = corners_of(q, arms);
  if (!corners) return {};
  std::optional<ExactRing> ring = star_ring(arms, *corners);
  if (!ring) return {};
  return counter_clockwise(std::move(*ring));
}

}  // namespace geom::exact
