// PlanarMap::snap_round: every edge split at the grid points (pixels) of the vertices near
// it, so that the map rounded to doubles has no edge crossing another (docs/design.md,
// Exactness, rule 5).
#include "geom/planar_map_arrangement.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>

#include "geom/segment_buckets.h"

namespace geom {
using namespace arrangement;

namespace {

// The closed box of points that round to g (to nearest, ties to even): its sides lie
// halfway to the neighbouring doubles.
Kernel::Iso_rectangle_2 pixel(Vec2 g) {
  auto half = [](double a, double b) { return (exact::FT(a) + exact::FT(b)) / 2; };
  const double inf = std::numeric_limits<double>::infinity();
  return {Point(half(std::nextafter(g.x, -inf), g.x), half(std::nextafter(g.y, -inf), g.y)),
          Point(half(g.x, std::nextafter(g.x, inf)), half(g.y, std::nextafter(g.y, inf)))};
}

// A point of the segment that rounds to g, if it has one.
std::optional<Point> point_rounding_to(const exact::Segment& s, Vec2 g) {
  auto meet = CGAL::intersection(s, pixel(g));
  if (!meet) return std::nullopt;
  Point m;
  if (const Point* p = boost::get<Point>(&*meet)) m = *p;
  else m = CGAL::midpoint(boost::get<exact::Segment>(&*meet)->source(), boost::get<exact::Segment>(&*meet)->target());
  // The chord's midpoint lies inside the pixel unless the chord runs along a side whose
  // points round to the neighbour; then no point of the segment rounds to g.
  if (!(to_plain(m) == g)) return std::nullopt;
  return m;
}

// Pairs (vertex, edge) where the rounded vertex lies within `reach` of the rounded edge,
// found through a grid of buckets each edge is entered in along its length.
template <typename F>
void for_each_near_pair(const std::vector<Vec2>& vertices, const std::vector<std::pair<int, int>>& edges, double reach,
                        F f) {
  Box box = Box::none();
  for (Vec2 v : vertices) box.add(v);
  const double extent = std::max({box.width(), box.height(), reach});
  const double bucket = std::max(extent / std::sqrt(static_cast<double>(vertices.size()) + 1), 16 * reach);
  const SegmentBuckets grid(box, bucket);
  std::vector<std::pair<long, int>> entries;  // (bucket, edge)
  for (int e = 0; e < static_cast<int>(edges.size()); ++e)
    grid.along(vertices[edges[e].first], vertices[edges[e].second], reach, [&](long k) { entries.push_back({k, e}); });
  std::sort(entries.begin(), entries.end());
  for (int v = 0; v < static_cast<int>(vertices.size()); ++v) {
    const Vec2 p = vertices[v];
    const long key = grid.key(p);
    for (auto it = std::lower_bound(entries.begin(), entries.end(), std::pair<long, int>(key, INT_MIN));
         it != entries.end() && it->first == key; ++it) {
      const auto [ia, ib] = edges[it->second];
      if (ia == v || ib == v) continue;
      const Vec2 a = vertices[ia], b = vertices[ib];
      if (p.x < std::min(a.x, b.x) - reach || p.x > std::max(a.x, b.x) + reach || p.y < std::min(a.y, b.y) - reach ||
          p.y > std::max(a.y, b.y) + reach)
        continue;
      const double dx = b.x - a.x, dy = b.y - a.y;
      if (std::abs(dx * (p.y - a.y) - dy * (p.x - a.x)) <= reach * std::hypot(dx, dy)) f(v, it->second);
    }
  }
}

}  // namespace

std::size_t PlanarMap::snap_round() {
  if constexpr (exact::kSnapped) return 0;  // every vertex is a double already, noded on its grid
  impl_->edges_change();
  Arrangement& arr = impl_->arr;
  // Candidates come from the vertices' interval approximations (rounding every vertex
  // exactly costs seconds on a large map); only a candidate's vertices are rounded exactly.
  std::vector<Arrangement::Vertex_handle> vertex_of;
  std::vector<Vec2> near;
  std::unordered_map<const void*, int> index;
  double largest = 0, widest = 0;
  for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
    index.emplace(&*v, static_cast<int>(near.size()));
    vertex_of.push_back(v);
    const auto [x, y] = exact::approx(v->point());
    near.push_back({(x.inf() + x.sup()) / 2, (y.inf() + y.sup()) / 2});
    largest = std::max({largest, std::abs(x.inf()), std::abs(x.sup()), std::abs(y.inf()), std::abs(y.sup())});
    widest = std::max({widest, x.sup() - x.inf(), y.sup() - y.inf()});
  }
  std::vector<std::optional<Vec2>> rounded(near.size());
  auto rounded_of = [&](int v) -> Vec2 {
    if (!rounded[v]) rounded[v] = to_plain(vertex_of[v]->point());
    return *rounded[v];
  };
  std::vector<Arrangement::Halfedge_handle> edge_of;  // each directed left to right
  std::vector<std::pair<int, int>> ends;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    Arrangement::Halfedge_handle h = left_to_right(Arrangement::Halfedge_handle(e));
    edge_of.push_back(h);
    ends.push_back({index.at(&*h->source()), index.at(&*h->target())});
  }
  // An edge meets a vertex's pixel only within about two steps of a double at the largest
  // coordinate of the rounded vertex, plus what the approximations leave open; far more
  // than that, and than the error of the test.
  const double step = std::nextafter(largest, std::numeric_limits<double>::infinity()) - largest;
  std::vector<std::pair<int, Point>> splits;  // (edge, point)
  const exacity::CancelCheck cancel;
  for_each_near_pair(near, ends, 16 * step + 2 * widest, [&](int v, int e) {
    cancel.check();
    const Vec2 g = rounded_of(v);
    if (rounded_of(ends[e].first) == g || rounded_of(ends[e].second) == g) return;  // it has a vertex there
    if (auto m = point_rounding_to(exact::Segment(edge_of[e]->source()->point(), edge_of[e]->target()->point()), g))
      splits.push_back({e, *m});
  });
  std::sort(splits.begin(), splits.end(), [](const auto& p, const auto& q) {
    return p.first != q.first ? p.first < q.first : CGAL::compare_xy(p.second, q.second) == CGAL::SMALLER;
  });
  std::size_t added = 0;
  const auto split = arr.geometry_traits()->split_2_object();
  for (std::size_t k = 0; k < splits.size();) {
    cancel.check();
    Arrangement::Halfedge_handle h = edge_of[splits[k].first];
    Vec2 last = rounded_of(ends[splits[k].first].first);
    for (const int e = splits[k].first; k < splits.size() && splits[k].first == e; ++k) {
      const Point& m = splits[k].second;
      const Vec2 at = to_plain(m);
      if (at == last) continue;  // one vertex per pixel is enough
      last = at;
      Traits::X_monotone_curve_2 left, right;
      split(h->curve(), m, left, right);
      h = arr.split_edge(h, left, right)->next();
      ++added;
    }
  }
  return added;
}

}  // namespace geom
