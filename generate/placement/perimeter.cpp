#include "generate/placement/perimeter.h"

#include <array>
#include <cmath>

#include "geom/grid.h"
#include "geom/measure.h"
#include "geom/outline.h"
#include "geom/polygon_check.h"
#include "geom/triangulate.h"

namespace exacity {

namespace {

using geom::Vec2;

// The convex polygon's part where dot(n, p - a) >= offset (Sutherland-Hodgman on one line).
// An edge is cut from its lesser end, so two triangles sharing it cut it at one point and
// their pieces' union has no seam.
std::vector<Vec2> clip(const std::vector<Vec2>& polygon, Vec2 a, Vec2 n, double offset) {
  std::vector<Vec2> out;
  auto side = [&](Vec2 p) { return geom::dot(n, p - a) - offset; };
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    Vec2 p = polygon[i], q = polygon[(i + 1) % polygon.size()];
    if (side(p) >= 0) out.push_back(p);
    if ((side(p) >= 0) == (side(q) >= 0)) continue;
    if (std::pair{q.x, q.y} < std::pair{p.x, p.y}) std::swap(p, q);
    out.push_back(geom::lerp(p, q, side(p) / (side(p) - side(q))));
  }
  return out;
}

// The ring without the vertices that lie within `tolerance` of the line through their
// neighbours, or whose neighbours lie within it of each other (a needle out and back):
// rounding leaves lots with millimetre edges at random turns, which no corner can be
// moved along.
geom::Ring simplified(geom::Ring ring, double tolerance) {
  for (bool dropped = true; dropped;) {
    dropped = false;
    for (std::size_t i = 0; i < ring.size() && ring.size() > 3;) {
      const Vec2 before = ring[(i + ring.size() - 1) % ring.size()], corner = ring[i], after = ring[(i + 1) % ring.size()];
      const double base = geom::distance(before, after);
      if (base < tolerance || std::abs(geom::cross(after - before, corner - before)) < tolerance * base) {
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
        dropped = true;
      } else {
        ++i;
      }
    }
  }
  return ring;
}

// Every edge moved `by` to its left (into a polygon, for its counter-clockwise outer ring
// and clockwise holes), each corner where its two moved edges meet (a hairpin's held at
// fifty times `by`); the caller checks the ring is still simple.
geom::Ring inset(const geom::Ring& ring, double by) {
  geom::Ring out;
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 before = ring[(i + n - 1) % n], corner = ring[i], after = ring[(i + 1) % n];
    const Vec2 n1 = geom::left_normal(before, corner), n2 = geom::left_normal(corner, after);
    const double s = by / std::max(1 + geom::dot(n1, n2), 0.02);
    out.push_back(geom::snap(corner + (n1 + n2) * s));
  }
  return out;
}

}  // namespace

std::vector<geom::Polygon> perimeter_footprints(const geom::Cell& lot, int road_kind, double setback, double depth,
                                                double clearance) {
  const auto fronts = lot.edges_of_kind(road_kind);
  if (fronts.empty()) return {};
  // The land moved inside the lot's edges first: the lot's rings are long edges meeting at
  // gentle turns, where moving edges is safe; the union below is not.
  geom::Polygon land = lot.to_plain();
  if (land.outer.size() < 3) return {};
  // Within a tenth of the clearance: the land stays inside the lot.
  land.outer = inset(simplified(land.outer, clearance / 10), clearance);
  for (geom::Ring& hole : land.holes) hole = inset(simplified(hole, clearance / 10), clearance);
  if (!geom::ring_is_simple(land.outer) || geom::ring_orientation(land.outer) != 1) return {};
  for (const geom::Ring& hole : land.holes)
    if (!geom::ring_is_simple(hole)) return {};
  std::vector<Vec2> corners = land.outer;
  for (const geom::Ring& hole : land.holes) corners.insert(corners.end(), hole.begin(), hole.end());
  // Each of the land's triangles cut to each frontage's band, as triangles again; their
  // union is the building.
  std::vector<std::array<Vec2, 3>> band;
  for (const auto& [i, j, k] : geom::triangulate(land))
    for (const auto& [a, b] : fronts) {
      const double length = geom::distance(a, b);
      if (length == 0) continue;
      const Vec2 u = geom::unit_along(a, b), n{-u.y, u.x};
      std::vector<Vec2> piece{corners[i], corners[j], corners[k]};
      piece = clip(piece, a, n, setback);
      piece = clip(piece, a, n * -1, -(setback + depth));
      piece = clip(piece, a, u, -depth);
      piece = clip(piece, a, u * -1, -(length + depth));
      for (std::size_t m = 1; m + 1 < piece.size(); ++m) band.push_back({piece[0], piece[m], piece[m + 1]});
    }
  std::vector<geom::Polygon> footprints = geom::union_of_triangles(band);
  // Courtyards are the land more than `depth` from every frontage; a smaller hole is where
  // two bands' rounded edges left a gap.
  for (geom::Polygon& p : footprints)
    std::erase_if(p.holes, [](const geom::Ring& hole) { return -geom::signed_area(hole) < 1; });
  return footprints;
}

}  // namespace exacity
