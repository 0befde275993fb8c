#include "generate/export/ring_sides.h"

#include <algorithm>
#include <vector>

#include "geom/orientation.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::in_segment_box;
using geom::orient;
using geom::Ring;
using geom::Vec2;

geom::Box box_of(Vec2 a, Vec2 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y)}; }

// The ring a and where points and pieces lie against its closed region.
class Region {
 public:
  explicit Region(const Ring& a) : a_(a) {}

  // +1 inside, 0 on the boundary, -1 outside.
  int side(Vec2 p) const { return geom::point_side(a_, p); }

  // The side of the piece x-y (no vertex of a inside it, no edge of a crossing it), where
  // x lies on the boundary and y is not x.
  int piece_side_from(Vec2 x, Vec2 y) const {
    const std::size_t n = a_.size();
    // Along an edge: the piece is part of it (it holds no vertex of a). Mostly the piece is
    // an edge of a, whose ends decide it.
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 v = a_[i], w = a_[(i + 1) % n];
      if ((x == v && y == w) || (x == w && y == v)) return 0;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 v = a_[i], w = a_[(i + 1) % n];
      if (in_segment_box(v, w, x) && in_segment_box(v, w, y) && orient(v, w, x) == 0 && orient(v, w, y) == 0) return 0;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 u = a_[(i + n - 1) % n], v = a_[i], w = a_[(i + 1) % n];
      if (!(x == v)) continue;
      // At a vertex: inside its corner (the side left of both edges when it turns left, of
      // either when it turns right). y lies on neither edge, as that piece would run along it.
      const int in = orient(u, v, y), out = orient(v, w, y), turn = orient(u, v, w);
      if (turn > 0) return in > 0 && out > 0 ? 1 : -1;
      if (turn < 0) return in > 0 || out > 0 ? 1 : -1;
      return in > 0 ? 1 : -1;
    }
    // Inside an edge: its left is the inside.
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 v = a_[i], w = a_[(i + 1) % n];
      if (in_segment_box(v, w, x) && orient(v, w, x) == 0) return orient(v, w, y) > 0 ? 1 : -1;
    }
    return side(y);  // not reached: x lies on the boundary
  }

  // The side of the piece x-y (no vertex of a inside it, no edge crossing it), given the sides of its ends.
  int piece_side(Vec2 x, int x_side, Vec2 y, int y_side) const {
    if (x_side != 0) return x_side;
    if (y_side != 0) return y_side;
    return piece_side_from(x, y);
  }

  const Ring& ring() const { return a_; }

 private:
  const Ring& a_;
};

}  // namespace

RingSides ring_sides(const Ring& b, const Ring& a) {
  RingSides sides;
  const Region region(a);
  // The edges of a whose boxes meet b's (a lot's in its block's ring of many edges): only
  // these can meet an edge of b, whose box lies in b's.
  geom::Box b_box = geom::Box::none();
  for (Vec2 p : b) b_box.add(p);
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (b_box.meets(box_of(a[i], a[(i + 1) % a.size()]))) near.push_back(i);
  std::vector<Vec2> cuts;
  int p_side = 0, first_side = 0;  // the sides of the edge's first end and of the ring's first vertex
  for (std::size_t k = 0; k < b.size(); ++k) {
    const Vec2 p = b[k], q = b[(k + 1) % b.size()];
    const geom::Box s = box_of(p, q);
    cuts.clear();
    for (std::size_t i : near) {
      const Vec2 u = a[i], v = a[(i + 1) % a.size()];
      if (!s.meets(box_of(u, v))) continue;
      const int ou = orient(p, q, u), ov = orient(p, q, v);
      if (ou * ov < 0 && orient(u, v, p) * orient(u, v, q) < 0) return sides.crosses = true, sides;
      if (ou == 0 && !(u == p) && !(u == q) && in_segment_box(p, q, u)) cuts.push_back(u);
    }
    // The cuts in order from p to q: along x, or along y on an upright edge (collinear, so exact).
    const bool by_x = p.x != q.x;
    const bool up = by_x ? p.x < q.x : p.y < q.y;
    std::sort(cuts.begin(), cuts.end(), [&](Vec2 c, Vec2 d) {
      const double cc = by_x ? c.x : c.y, dd = by_x ? d.x : d.y;
      return up ? cc < dd : cc > dd;
    });
    // The cuts lie on the boundary; each end's side is found once.
    if (k == 0) p_side = first_side = region.side(p);
    const int q_side = k + 1 == b.size() ? first_side : region.side(q);
    Vec2 from = p;
    int from_side = p_side;
    for (Vec2 to : cuts) {
      const int side = region.piece_side(from, from_side, to, 0);
      sides.inside |= side > 0;
      sides.outside |= side < 0;
      from = to, from_side = 0;
    }
    const int side = region.piece_side(from, from_side, q, q_side);
    sides.inside |= side > 0;
    sides.outside |= side < 0;
    p_side = q_side;
  }
  return sides;
}

bool interiors_apart(const Ring& a, const Ring& b) {
  // No edge crossing and neither ring inside the other's region: the interiors meet only if
  // each boundary lies on the other (the same region); a piece outside rules that out.
  const RingSides b_in_a = ring_sides(b, a);
  if (b_in_a.crosses || b_in_a.inside) return false;
  const RingSides a_in_b = ring_sides(a, b);
  if (a_in_b.crosses || a_in_b.inside) return false;
  return b_in_a.outside || a_in_b.outside;
}

bool ring_in_polygon(const Ring& ring, const geom::Polygon& polygon) {
  const RingSides in_outer = ring_sides(ring, polygon.outer);
  if (in_outer.crosses || in_outer.outside) return false;
  geom::Box box = geom::Box::none();
  for (Vec2 p : ring) box.add(p);
  for (const Ring& hole : polygon.holes) {
    geom::Box hole_box = geom::Box::none();
    for (Vec2 p : hole) hole_box.add(p);
    if (!box.meets(hole_box)) continue;
    const Ring region(hole.rbegin(), hole.rend());  // the hole's region, counter-clockwise
    if (!interiors_apart(ring, region)) return false;
  }
  return true;
}

bool segment_meets_box(Vec2 a, Vec2 b, const geom::Box& box) {
  if (!box_of(a, b).meets(box)) return false;
  // Separated by the segment's line when all four corners lie strictly on one side of it.
  int left = 0, right = 0;
  for (Vec2 corner : {Vec2{box.min_x, box.min_y}, Vec2{box.max_x, box.min_y}, Vec2{box.max_x, box.max_y}, Vec2{box.min_x, box.max_y}}) {
    const int o = orient(a, b, corner);
    left += o > 0, right += o < 0;
  }
  return left < 4 && right < 4;
}

int exact_winding_number(const Ring& ring, Vec2 p) {
  int winding = 0;
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 u = ring[i], v = ring[(i + 1) % n];
    // An upward edge with p left of it, or a downward one with p right of it, crosses the
    // ray from p to the right (each end counted on the side above the ray).
    if (u.y <= p.y) {
      if (v.y > p.y && orient(u, v, p) > 0) ++winding;
    } else if (v.y <= p.y && orient(u, v, p) < 0) {
      --winding;
    }
  }
  return winding;
}

SegmentMeeting segment_meeting(Vec2 a0, Vec2 a1, Vec2 b0, Vec2 b1) {
  if (!box_of(a0, a1).meets(box_of(b0, b1))) return SegmentMeeting::Apart;
  if ((a0 == b0 && a1 == b1) || (a0 == b1 && a1 == b0)) return SegmentMeeting::Same;
  const int o0 = orient(a0, a1, b0), o1 = orient(a0, a1, b1);
  // On one line, not running along each other: they touch at most where an end of each meets.
  if (o0 == 0 && o1 == 0) return segments_run_along(a0, a1, b0, b1) ? SegmentMeeting::Otherwise : SegmentMeeting::Apart;
  if (o0 * o1 > 0) return SegmentMeeting::Apart;
  const int o2 = orient(b0, b1, a0), o3 = orient(b0, b1, a1);
  if (o2 * o3 > 0) return SegmentMeeting::Apart;
  // Not on one line, they meet at one point: a shared end, if they have one.
  return a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1 ? SegmentMeeting::Apart : SegmentMeeting::Otherwise;
}

bool segments_run_along(Vec2 a0, Vec2 a1, Vec2 b0, Vec2 b1) {
  if (orient(a0, a1, b0) != 0 || orient(a0, a1, b1) != 0) return false;
  // On one line: compare along x, or along y when it is upright.
  const bool by_x = a0.x != a1.x;
  const double a_lo = by_x ? std::min(a0.x, a1.x) : std::min(a0.y, a1.y), a_hi = by_x ? std::max(a0.x, a1.x) : std::max(a0.y, a1.y);
  const double b_lo = by_x ? std::min(b0.x, b1.x) : std::min(b0.y, b1.y), b_hi = by_x ? std::max(b0.x, b1.x) : std::max(b0.y, b1.y);
  return std::max(a_lo, b_lo) < std::min(a_hi, b_hi);
}

}  // namespace exacity
