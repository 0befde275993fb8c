#include "generate/placement/slabs.h"

#include <algorithm>
#include <array>
#include <optional>

#include "generate/placement/model_library.h"
#include "geom/filled_outline.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::Vec2;

// Where the edge from p (at or below z) to q (above) crosses the height z. Always from the
// lower end, so the two triangles sharing an edge find the same point.
Vec2 crossing(const Vec3& p, const Vec3& q, double z) {
  const double t = (z - p[2]) / (q[2] - p[2]);
  return {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])};
}

// The polygon clipped to z >= lo (keep_above) or z <= hi (Sutherland-Hodgman).
std::vector<Vec3> clip(const std::vector<Vec3>& poly, double z, bool keep_above) {
  std::vector<Vec3> out;
  auto in = [&](const Vec3& v) { return keep_above ? v[2] >= z : v[2] <= z; };
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3 &p = poly[i], &q = poly[(i + 1) % poly.size()];
    if (in(p)) out.push_back(p);
    if (in(p) != in(q)) {
      const Vec3& lo = p[2] <= q[2] ? p : q;
      const Vec3& hi = p[2] <= q[2] ? q : p;
      const Vec2 c = crossing(lo, hi, z);
      out.push_back({c.x, c.y, z});
    }
  }
  return out;
}

// The heights the mesh is cut at: its undersides', at most kMaxSlabs - 1 of them, the
// lowest always (the most room under it).
std::vector<double> cut_heights(const TriangleMesh& mesh, double height) {
  std::vector<double> zs;
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    if (geom::triangle_normal(a, b, c)[2] >= 0) continue;
    for (const Vec3* v : {&a, &b, &c})
      if ((*v)[2] > 0 && (*v)[2] < height) zs.push_back((*v)[2]);
  }
  std::sort(zs.begin(), zs.end());
  zs.erase(std::unique(zs.begin(), zs.end()), zs.end());
  if (zs.size() < kMaxSlabs) return zs;
  std::vector<double> picked;
  for (std::size_t k = 0; k + 1 < kMaxSlabs; ++k) picked.push_back(zs[k * zs.size() / (kMaxSlabs - 1)]);
  picked.erase(std::unique(picked.begin(), picked.end()), picked.end());
  return picked;
}

// What of the mesh lies at heights [z0, z1) ([z0, z1] for the top slab) seen from above;
// nothing when it cannot be made sure (see geom::filled_outline).
std::optional<std::vector<geom::Ring>> slab_outline(const TriangleMesh& mesh, double z0, double z1, bool top) {
  std::vector<std::array<Vec2, 3>> shadows;
  std::vector<std::pair<Vec2, Vec2>> section;
  std::vector<Vec2> must_cover;
  const double mid = (z0 + z1) / 2;
  auto within = [&](double z) { return z >= z0 && (z < z1 || (top && z == z1)); };
  for (const Vec3& v : mesh.vertices)
    if (within(v[2])) must_cover.push_back({v[0], v[1]});
  for (const auto& t : mesh.triangles) {
    const std::vector<Vec3> tri{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    const bool flat = tri[0][2] == tri[1][2] && tri[1][2] == tri[2][2];
    // A flat triangle belongs to the slab its height is in (an underside at a cut to the
    // slab above it); the others are clipped to the slab.
    const std::vector<Vec3> part =
        flat ? (within(tri[0][2]) ? tri : std::vector<Vec3>{}) : clip(clip(tri, z0, true), z1, false);
    for (std::size_t k = 1; k + 1 < part.size(); ++k)
      shadows.push_back(
          {Vec2{part[0][0], part[0][1]}, Vec2{part[k][0], part[k][1]}, Vec2{part[k + 1][0], part[k + 1][1]}});
    if (flat) continue;
    // The cross-section at mid-height, the solid on each segment's left: walls have no
    // shadow, but their section bounds what they enclose.
    std::vector<Vec2> ends;
    for (int e = 0; e < 3; ++e) {
      const Vec3 &p = tri[e], &q = tri[(e + 1) % 3];
      if ((p[2] > mid) == (q[2] > mid)) continue;
      ends.push_back(p[2] <= mid ? crossing(p, q, mid) : crossing(q, p, mid));
    }
    if (ends.size() != 2) continue;
    const Vec3 n = geom::triangle_normal(tri[0], tri[1], tri[2]);
    const Vec2 d = ends[1] - ends[0];
    // Inside on the left: the left normal points against the outward normal.
    const double side = -d.y * n[0] + d.x * n[1];
    if (side < 0)
      section.push_back({ends[0], ends[1]});
    else if (side > 0)
      section.push_back({ends[1], ends[0]});
  }
  return geom::filled_outline(shadows, section, must_cover);
}

// Few corners and few pieces, as Occupancy tests each against the others exactly: a ring of
// more than kOutlineCorners corners becomes the polygon around it, more than kMaxSlabPieces
// pieces their hull.
constexpr std::size_t kMaxSlabPieces = 16;
std::vector<geom::Ring> bounded(std::vector<geom::Ring> rings) {
  if (rings.size() > kMaxSlabPieces) {
    std::vector<Vec2> all;
    for (const geom::Ring& r : rings) all.insert(all.end(), r.begin(), r.end());
    return {geom::convex_hull(all)};
  }
  for (geom::Ring& r : rings)
    if (r.size() > kOutlineCorners) r = geom::polygon_around(r, kOutlineCorners);
  return rings;
}

}  // namespace

std::vector<Slab> model_slabs(const TriangleMesh& mesh, const geom::Ring& outline, double height) {
  std::vector<double> levels{0};
  if (mesh.triangles.size() <= kExactOutlineTriangles)
    for (double z : cut_heights(mesh, height)) levels.push_back(z);
  levels.push_back(height);
  std::vector<Slab> slabs;
  for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
    std::optional<std::vector<geom::Ring>> rings;
    if (levels.size() > 2) rings = slab_outline(mesh, levels[k], levels[k + 1], k + 2 == levels.size());
    Slab s{levels[k], levels[k + 1],
           rings && !rings->empty() ? bounded(std::move(*rings)) : std::vector<geom::Ring>{outline}};
    // Two slabs alike are one (a fallback on both sides of a cut).
    if (!slabs.empty() && slabs.back().outline == s.outline)
      slabs.back().top = s.top;
    else
      slabs.push_back(std::move(s));
  }
  return slabs;
}

bool slabs_meet(const std::vector<Slab>& a, double floor_a, const std::vector<Slab>& b, double floor_b) {
  for (const Slab& s : a)
    for (const Slab& t : b) {
      if (geom::compare_sums(floor_a, s.top, floor_b, t.bottom) < 0 ||
          geom::compare_sums(floor_b, t.top, floor_a, s.bottom) < 0)
        continue;
      for (const geom::Ring& r : s.outline)
        for (const geom::Ring& q : t.outline)
          if (geom::rings_meet(r, q)) return true;
    }
  return false;
}

}  // namespace exacity
