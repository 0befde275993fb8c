#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>
#include <string>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <CGAL/Polygon_2_algorithms.h>

#include "geom/cell_impl.h"
#include "geom/grid.h"
#include "geom/hex_text.h"
#include "geom/measure.h"
#include "geom/untangle.h"

namespace geom {

using exact::Kernel;
using exact::Point;
using exact::Segment;
using exact::to_exact;

Path Path::from(const Polyline& line) {
  auto impl = std::make_shared<Impl>();
  for (Vec2 p : line) impl->points.push_back(to_exact(p));
  return Path(std::move(impl));
}

Path Path::reversed() const {
  auto impl = std::make_shared<Impl>();
  if (impl_) impl->points.assign(impl_->points.rbegin(), impl_->points.rend());
  return Path(std::move(impl));
}

std::size_t Path::size() const { return impl_ ? impl_->points.size() : 0; }
Vec2 Path::point(std::size_t i) const { return exact::to_plain(impl_->points[i]); }

Polyline Path::to_plain() const {
  Polyline line;
  for (std::size_t i = 0; i < size(); ++i) line.push_back(point(i));
  return line;
}

bool Path::is_straight() const {
  const auto& p = impl_->points;
  for (std::size_t i = 2; i < p.size(); ++i)
    if (!CGAL::collinear(p[0], p[1], p[i])) return false;
  return true;
}

Cell make_cell(KindRing outer, std::vector<KindRing> holes) {
  auto impl = std::make_shared<Cell::Impl>();
  // Area and bounds of the rounded rings: choices, not topology.
  double twice_area = 0;
  Box b = Box::none();
  auto add = [&](KindRing& r) {
    if (r.rounded.size() != r.points.size()) {
      r.rounded.clear();
      for (const Point& v : r.points) r.rounded.push_back(exact::to_plain(v));
    }
    for (Vec2 v : r.rounded) b.add(v);
  };
  add(outer);
  for (auto& h : holes) add(h);
  const Vec2 o = outer.rounded.at(0);  // relative to a vertex, so large coordinates keep their precision
  auto add_area = [&](const std::vector<Vec2>& p) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      Vec2 u = p[i], w = p[(i + 1) % p.size()];
      twice_area += (u.x - o.x) * (w.y - o.y) - (u.y - o.y) * (w.x - o.x);
    }
  };
  add_area(outer.rounded);
  for (const auto& h : holes) add_area(h.rounded);
  impl->area = twice_area / 2;
  impl->bounds = b;
  impl->outer = std::move(outer);
  impl->holes = std::move(holes);
  return Cell(std::move(impl));
}

double Cell::area() const { return impl_->area; }
Box Cell::bounds() const { return impl_->bounds; }

Vec2 Cell::centroid() const {
  // Of the outer ring's area, in doubles relative to its first vertex: a choice, not topology.
  const auto& pts = impl_->outer.rounded;
  Vec2 o = pts[0];
  double a = 0, cx = 0, cy = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    Vec2 p = pts[i], q = pts[(i + 1) % pts.size()];
    p = {p.x - o.x, p.y - o.y}, q = {q.x - o.x, q.y - o.y};
    double c = p.x * q.y - q.x * p.y;
    a += c, cx += (p.x + q.x) * c, cy += (p.y + q.y) * c;
  }
  if (a == 0) return o;
  return {o.x + cx / (3 * a), o.y + cy / (3 * a)};
}

bool Cell::contains(Vec2 v) const {
  Point p = to_exact(v);
  const auto& outer = impl_->outer.points;
  if (CGAL::bounded_side_2(outer.begin(), outer.end(), p, Kernel()) != CGAL::ON_BOUNDED_SIDE) return false;
  for (const auto& h : impl_->holes)
    if (CGAL::bounded_side_2(h.points.begin(), h.points.end(), p, Kernel()) != CGAL::ON_UNBOUNDED_SIDE) return false;
  return true;
}

bool Cell::holds(const Ring& ring) const {
  if (ring.size() < 3) return false;
  Box box = Box::none();
  for (Vec2 v : ring) box.add(v);
  // Each exact vertex lies within a step of its rounded double either way, so what lies past
  // the rounded bounds by more cannot be inside, and an edge whose rounded ends' box, a step
  // wider, misses the ring's cannot meet it: both decided before anything exact is made
  // (placers ask this of every place they try).
  const auto down = [](double v) { return std::nextafter(v, -INFINITY); };
  const auto up = [](double v) { return std::nextafter(v, INFINITY); };
  const Box& b = impl_->bounds;
  if (box.min_x < down(b.min_x) || box.max_x > up(b.max_x) || box.min_y < down(b.min_y) || box.max_y > up(b.max_y))
    return false;
  if (!contains(ring[0])) return false;
  std::vector<Segment> sides;
  for (std::size_t i = 0; i < ring.size(); ++i) sides.emplace_back(to_exact(ring[i]), to_exact(ring[(i + 1) % ring.size()]));
  auto crosses = [&](const KindRing& r) {
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      const Vec2 a = r.rounded[i], c = r.rounded[(i + 1) % r.points.size()];
      if (up(std::max(a.x, c.x)) < box.min_x || down(std::min(a.x, c.x)) > box.max_x ||
          up(std::max(a.y, c.y)) < box.min_y || down(std::min(a.y, c.y)) > box.max_y)
        continue;
      Segment e(r.points[i], r.points[(i + 1) % r.points.size()]);
      for (const Segment& s : sides)
        if (CGAL::do_intersect(s, e)) return true;
    }
    return false;
  };
  // With no boundary edge meeting the ring and one vertex inside, the ring lies inside
  // the outer ring; a hole could still sit wholly within it.
  if (crosses(impl_->outer)) return false;
  std::vector<Point> pts;
  for (Vec2 v : ring) pts.push_back(to_exact(v));
  for (const auto& h : impl_->holes)
    if (crosses(h) || CGAL::bounded_side_2(pts.begin(), pts.end(), h.points[0], Kernel()) != CGAL::ON_UNBOUNDED_SIDE)
      return false;
  return true;
}

std::optional<Vec2> Cell::point_inside_near(Vec2 wanted) const {
  Vec2 s = snap(wanted);
  if (contains(s)) return s;
  // Boundary edges nearest to `wanted` first; step inwards (interior is on each edge's left).
  struct Candidate {
    double distance;
    Vec2 foot, inward;
  };
  std::vector<Candidate> candidates;
  auto visit = [&](const KindRing& r) {
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      Vec2 a = r.rounded[i], b = r.rounded[(i + 1) % r.points.size()];
      double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
      if (len2 == 0) continue;
      Vec2 foot = nearest_on_segment(wanted, a, b);
      candidates.push_back({std::hypot(foot.x - wanted.x, foot.y - wanted.y), foot, left_normal(a, b)});
    }
  };
  visit(impl_->outer);
  for (const auto& h : impl_->holes) visit(h);
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  double size = std::max(impl_->bounds.width(), impl_->bounds.height());
  for (std::size_t k = 0; k < std::min<std::size_t>(candidates.size(), 16); ++k) {
    for (double d = 1.0 / 64; d < size; d *= 2) {
      Vec2 p = snap(Vec2{candidates[k].foot.x + candidates[k].inward.x * d, candidates[k].foot.y + candidates[k].inward.y * d});
      if (contains(p)) return p;
    }
  }
  return std::nullopt;
}

std::vector<std::pair<Vec2, Vec2>> Cell::edges_of_kind(int kind) const {
  std::vector<std::pair<Vec2, Vec2>> edges;
  auto visit = [&](const KindRing& r) {
    for (std::size_t i = 0; i < r.points.size(); ++i)
      if (r.kinds[i] == kind) edges.push_back({r.rounded[i], r.rounded[(i + 1) % r.points.size()]});
  };
  visit(impl_->outer);
  for (const auto& h : impl_->holes) visit(h);
  return edges;
}

std::vector<KindedRing> Cell::kinded_rings() const {
  std::vector<KindedRing> rings;
  auto visit = [&](const KindRing& r) {
    KindedRing out;
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      Vec2 p = r.rounded[i];
      if (!out.points.empty() && out.points.back() == p) {
        out.kinds.back() = r.kinds[i];  // the edge that rounded to nothing gives way to the next
        continue;
      }
      out.points.push_back(p);
      out.kinds.push_back(r.kinds[i]);
    }
    while (out.points.size() > 1 && out.points.front() == out.points.back()) out.points.pop_back(), out.kinds.pop_back();
    if (out.points.size() >= 3) rings.push_back(std::move(out));
  };
  visit(impl_->outer);
  for (const auto& h : impl_->holes) visit(h);
  return rings;
}

namespace {

std::vector<Ring> rounded_rings(const Cell::Impl& c) {
  std::vector<Ring> rings{c.outer.rounded};
  for (const auto& h : c.holes) rings.push_back(h.rounded);
  return rings;
}

}  // namespace

std::vector<Polygon> Cell::rounded() const { return untangle(rounded_rings(*impl_)); }

Polygon Cell::to_plain() const {
  std::vector<Polygon> parts = rounded();
  if (parts.empty()) return {};
  return *std::max_element(parts.begin(), parts.end(), [](const Polygon& a, const Polygon& b) { return geom::area(a) < geom::area(b); });
}

namespace {

// The ring rounded, less what rounding collapsed to nothing: an edge whose ends rounded to
// one point, and a spike, a sliver of the cell (or of its neighbour, reaching in) narrower
// than a double's step whose two sides rounded to one edge run there and back. Neither
// encloses anything; every edge kept keeps its kind. Fewer than 3 points when the whole
// ring collapsed.
KindedRing without_collapsed(const KindRing& r) {
  std::vector<Vec2> p = r.rounded;
  std::vector<int> k = r.kinds;
  for (bool changed = true; changed && p.size() >= 3;) {
    changed = false;
    for (std::size_t i = 0; i < p.size() && p.size() >= 3;) {
      const std::size_t n = p.size(), before = (i + n - 1) % n, after = (i + 1) % n;
      if (p[i] == p[after]) {
        // The edge from i rounded to nothing: the edge into i now ends at `after`, the same point.
        p.erase(p.begin() + static_cast<std::ptrdiff_t>(i)), k.erase(k.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
      } else if (p[before] == p[after]) {
        // Out to p[i] and straight back: `before` goes on along the edge that left `after`.
        k[before] = k[after];
        for (std::size_t e : {std::max(i, after), std::min(i, after)})
          p.erase(p.begin() + static_cast<std::ptrdiff_t>(e)), k.erase(k.begin() + static_cast<std::ptrdiff_t>(e));
        changed = true;
      } else {
        ++i;
      }
    }
  }
  return {std::move(p), std::move(k)};
}

}  // namespace

std::optional<Cell> Cell::as_written() const {
  const KindedRing outer = without_collapsed(impl_->outer);
  if (outer.points.size() < 3) return std::nullopt;
  std::vector<KindedRing> holes;
  for (const KindRing& h : impl_->holes)
    if (KindedRing hole = without_collapsed(h); hole.points.size() >= 3) holes.push_back(std::move(hole));
  std::vector<Ring> rings{outer.points};
  for (const KindedRing& h : holes) rings.push_back(h.points);
  if (vertex_repeats(rings)) return std::nullopt;
  auto written = [](const KindedRing& r) {
    KindRing w{{}, r.kinds, r.points};
    for (Vec2 v : r.points) w.points.push_back(to_exact(v));
    return w;
  };
  std::vector<KindRing> written_holes;
  for (const KindedRing& h : holes) written_holes.push_back(written(h));
  return make_cell(written(outer), std::move(written_holes));
}

std::optional<Cell> with_vertices_on_edges(const Cell& cell, const std::vector<VertexOnEdge>& added) {
  bool any = false;
  auto with = [&](const KindRing& r) {
    KindRing out;
    const std::size_t n = r.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      out.points.push_back(r.points[i]), out.kinds.push_back(r.kinds[i]), out.rounded.push_back(r.rounded[i]);
      const Vec2 from = r.rounded[i], to = r.rounded[(i + 1) % n];
      for (const VertexOnEdge& v : added)
        if (v.from == from && v.to == to) {
          out.points.push_back(to_exact(v.at)), out.kinds.push_back(r.kinds[i]), out.rounded.push_back(v.at);
          any = true;
        }
    }
    return out;
  };
  KindRing outer = with(cell.exact().outer);
  std::vector<KindRing> holes;
  for (const KindRing& h : cell.exact().holes) holes.push_back(with(h));
  if (!any) return std::nullopt;
  return make_cell(std::move(outer), std::move(holes));
}

std::vector<Vec2> Cell::corners() const {
  const auto& pts = impl_->outer.points;
  std::vector<Point> corners;
  for (std::size_t i = 0, n = pts.size(); i < n; ++i)
    if (!CGAL::collinear(pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n])) corners.push_back(pts[i]);
  return exact::round_ring(corners);  // corners closer than a double apart become one
}

std::vector<int> Cell::edge_kinds() const {
  std::vector<int> kinds = impl_->outer.kinds;
  for (const auto& h : impl_->holes) kinds.insert(kinds.end(), h.kinds.begin(), h.kinds.end());
  std::sort(kinds.begin(), kinds.end());
  kinds.erase(std::unique(kinds.begin(), kinds.end()), kinds.end());
  return kinds;
}

Path extend_to(const Path& road, const std::vector<Path>& targets, double reach, bool may_turn) {
  const auto& pts = road.exact().points;
  if (pts.size() < 2) return road;
  const Point &p = pts[pts.size() - 2], &q = pts.back();
  // The far end in doubles only bounds the search; the point found lies exactly on the line pq.
  Vec2 a = exact::to_plain(p), b = exact::to_plain(q);
  double len = std::hypot(b.x - a.x, b.y - a.y);
  if (len == 0) return road;
  const exact::Line line(p, q);
  const Box ray_box = [&] {
    Box box = Box::none();
    box.add(b);
    box.add(Vec2{b.x + (b.x - a.x) / len * reach, b.y + (b.y - a.y) / len * reach});
    return box;
  }();
  std::optional<Point> best;
  for (const Path& target : targets) {
    const auto& t = target.exact().points;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
      const Segment s(t[i], t[i + 1]);
      CGAL::Bbox_2 sb = s.bbox();
      if (sb.xmax() < ray_box.min_x - 1 || sb.xmin() > ray_box.max_x + 1 || sb.ymax() < ray_box.min_y - 1 ||
          sb.ymin() > ray_box.max_y + 1)
        continue;
      auto meet = CGAL::intersection(line, s);
      if (!meet) continue;
      const Point* found = boost::get<Point>(&*meet);
      if (!found) continue;
      const Point x = exact::constructed(*found);
      // only ahead of q (q on the grid as the snapped builds test equality: a drawn end is not on a decimal one)
      if (x == exact::constructed(q) || CGAL::angle(p, q, x) != CGAL::OBTUSE) continue;
      if (CGAL::squared_distance(q, x) > exact::FT(reach * reach)) continue;
      if (!best || CGAL::has_smaller_distance_to_point(q, x, *best)) best = x;
    }
  }
  if (!best && may_turn) {
    auto end = std::make_shared<Path::Impl>();
    end->points.push_back(q);
    const std::optional<Link> link = shortest_link({Path(std::move(end))}, targets);
    if (link && !link->path.empty() && link->length <= reach) best = link->path.exact().points[1];
  }
  if (!best) return road;
  auto impl = std::make_shared<Path::Impl>(road.exact());
  impl->points.push_back(*best);
  return Path(std::move(impl));
}

bool ends_on(const Path& road, const std::vector<Path>& targets) {
  const auto& pts = road.exact().points;
  if (pts.empty()) return false;
  const Point& q = pts.back();
  for (const Path& target : targets) {
    const auto& t = target.exact().points;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
      const Segment s(t[i], t[i + 1]);
      if constexpr (exact::kSnapped) {
        // The snapped build's ends lie within a grid step of what they met, not on it.
        if (CGAL::squared_distance(s, q) <= exact::FT(exact::kSnapStep * exact::kSnapStep)) return true;
      } else if (s.has_on(q)) {
        return true;
      }
    }
  }
  return false;
}

std::optional<Link> shortest_link(const std::vector<Path>& from, const std::vector<Path>& to) {
  struct Plain {
    Polyline line;
    Box box = Box::none();
  };
  auto plain = [](const std::vector<Path>& paths) {
    std::vector<Plain> out;
    for (const Path& p : paths) {
      Plain q{p.to_plain()};
      for (Vec2 v : q.line) q.box.add(v);
      out.push_back(std::move(q));
    }
    return out;
  };
  const std::vector<Plain> a = plain(from), b = plain(to);
  // The closest (vertex, segment) pair: which side the vertex is on, its path and index,
  // the segment's path and first index.
  struct Pair {
    bool vertex_from = true;
    std::size_t vertex_path = 0, vertex = 0, segment_path = 0, segment = 0;
  };
  std::optional<Pair> best;
  double best_d = INFINITY;
  auto search = [&](const std::vector<Plain>& vs, const std::vector<Plain>& ss, bool vertex_from) {
    for (std::size_t i = 0; i < vs.size(); ++i)
      for (std::size_t k = 0; k < vs[i].line.size(); ++k) {
        const Vec2 v = vs[i].line[k];
        for (std::size_t j = 0; j < ss.size(); ++j) {
          const Box& box = ss[j].box;
          const double dx = std::max({box.min_x - v.x, v.x - box.max_x, 0.0}),
                       dy = std::max({box.min_y - v.y, v.y - box.max_y, 0.0});
          if (std::hypot(dx, dy) >= best_d) continue;
          const Polyline& s = ss[j].line;
          for (std::size_t m = 0; m + 1 < s.size(); ++m) {
            const double d = distance_to_segment(v, s[m], s[m + 1]);
            if (d < best_d) best_d = d, best = Pair{vertex_from, i, k, j, m};
          }
        }
      }
  };
  search(a, b, true);
  search(b, a, false);
  if (!best) return std::nullopt;
  const std::vector<Path>& vertex_paths = best->vertex_from ? from : to;
  const std::vector<Path>& segment_paths = best->vertex_from ? to : from;
  const Point& v = vertex_paths[best->vertex_path].exact().points[best->vertex];
  const auto& s = segment_paths[best->segment_path].exact().points;
  const Point &p = s[best->segment], &q = s[best->segment + 1];
  Point nearest = CGAL::angle(v, p, q) != CGAL::ACUTE   ? p
                  : CGAL::angle(v, q, p) != CGAL::ACUTE ? q
                                                        : exact::constructed(exact::Line(p, q).projection(v));
  if (nearest == exact::constructed(v)) return Link{};
  auto impl = std::make_shared<Path::Impl>();
  impl->points = best->vertex_from ? std::vector<Point>{v, nearest} : std::vector<Point>{nearest, v};
  return Link{Path(std::move(impl)), best_d};
}

// --- Growth -------------------------------------------------------------------------

struct Growth::Impl {
  struct Obstacle {
    Segment segment;
    Box box;
    Met met;  // what a step that stops here met
  };
  Box bounds;
  double bucket = 1;
  int nx = 1, ny = 1;
  std::vector<std::vector<int>> buckets;  // obstacle indices per bucket
  std::vector<Obstacle> obstacles;
  std::vector<int> stamp;  // per obstacle: the query that last looked at it
  int query = 0;
  std::vector<Point> road;
  bool ended = false;

  static Box box_of(Vec2 a, Vec2 b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y)};
  }

  template <typename F>
  void for_each_bucket(const Box& b, F&& f) const {
    auto cx = [&](double x) { return std::clamp(static_cast<int>((x - bounds.min_x) / bucket), 0, nx - 1); };
    auto cy = [&](double y) { return std::clamp(static_cast<int>((y - bounds.min_y) / bucket), 0, ny - 1); };
    for (int j = cy(b.min_y); j <= cy(b.max_y); ++j)
      for (int i = cx(b.min_x); i <= cx(b.max_x); ++i) f(j * nx + i);
  }

  void add(const Point& a, const Point& b, Met met) {
    if (a == b) return;
    Box box = box_of(exact::to_plain(a), exact::to_plain(b));
    int id = static_cast<int>(obstacles.size());
    obstacles.push_back({Segment(a, b), box, met});
    stamp.push_back(-1);
    for_each_bucket(box, [&](int k) { buckets[k].push_back(id); });
  }
};

Growth::Growth(const Cell& cell, double step) : impl_(std::make_unique<Impl>()) {
  Impl& g = *impl_;
  g.bounds = cell.bounds();
  // Buckets about two steps wide, at most 256 a side.
  double extent = std::max({g.bounds.width(), g.bounds.height(), 1e-3});
  g.bucket = std::max(extent / 256, 2 * step);
  g.nx = std::max(1, static_cast<int>(std::ceil(g.bounds.width() / g.bucket)) + 1);
  g.ny = std::max(1, static_cast<int>(std::ceil(g.bounds.height() / g.bucket)) + 1);
  g.buckets.resize(static_cast<std::size_t>(g.nx) * g.ny);
  auto add_ring = [&](const KindRing& r) {
    for (std::size_t i = 0; i < r.points.size(); ++i) g.add(r.points[i], r.points[(i + 1) % r.points.size()], {Met::Edge, r.kinds[i]});
  };
  add_ring(cell.exact().outer);
  for (const auto& h : cell.exact().holes) add_ring(h);
}

Growth::~Growth() = default;

void Growth::begin(Vec2 start) {
  impl_->road = {to_exact(start)};
  impl_->ended = false;
}

Growth::Met Growth::extend(Vec2 next) {
  Impl& g = *impl_;
  if (g.ended) return {};
  const Point p = g.road.back(), q = to_exact(next);
  if (p == q) return {};
  const Segment step(p, q);
  ++g.query;
  std::optional<Point> best;
  Met best_met;
  auto beats = [](const Met& a, const Met& b) {
    return a.what == Met::Edge && (b.what != Met::Edge || a.kind > b.kind);
  };
  g.for_each_bucket(Impl::box_of(exact::to_plain(p), next), [&](int k) {
    for (int id : g.buckets[k]) {
      if (g.stamp[id] == g.query) continue;
      g.stamp[id] = g.query;
      const Impl::Obstacle& o = g.obstacles[id];
      if (!CGAL::do_intersect(step, o.segment)) continue;
      auto meet = CGAL::intersection(step, o.segment);
      Point at;
      if (const Point* x = boost::get<Point>(&*meet)) {
        at = exact::constructed(*x);
        // Where this step starts: the road's own previous vertex, on the grid as `at` is.
        if (at == exact::constructed(p)) continue;
      } else {
        const Segment& overlap = boost::get<Segment>(*meet);
        at = CGAL::compare_distance_to_point(p, overlap.source(), overlap.target()) == CGAL::SMALLER
                 ? overlap.source() : overlap.target();
      }
      if (!best || CGAL::compare_distance_to_point(p, at, *best) == CGAL::SMALLER ||
          (at == *best && beats(o.met, best_met))) {
        best = at;
        best_met = o.met;
      }
    }
  });
  const Point stop = best ? *best : q;
  if (stop != p) {
    g.add(p, stop, {Met::OwnRoad, 0});
    g.road.push_back(stop);
  }
  if (best) g.ended = true;
  return best ? best_met : Met{};
}

void Growth::add_obstacle(const Path& road) {
  const auto& p = road.exact().points;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) impl_->add(p[i], p[i + 1], {Met::OwnRoad, 0});
}

Path Growth::end() {
  Impl& g = *impl_;
  g.ended = true;
  if (g.road.size() < 2) return Path();
  auto impl = std::make_shared<Path::Impl>();
  impl->points = std::move(g.road);
  g.road.clear();
  return Path(std::move(impl));
}

}  // namespace geom

namespace geom {
namespace {

// A coordinate as its double in C's %a (std::hexfloat's text) where that is its exact value,
// else 'q' and its rational. Built with to_chars rather than a stream: a build keys every
// region, block and lot by this text (generate/regenerate.h), and the stream's printf was
// most of its cost. The text seeds streams and ids (content_id): it must not change.
void write_double(std::string& out, double v) { append_hex_text(out, v); }

template <typename Exact>
void write_coordinate(std::string& out, double rounded, const Exact& exact) {
  if (exact == rounded) return write_double(out, rounded);
  std::ostringstream q;
  q << 'q' << exact << ' ';
  out += q.str();
}

// `rounded` is to_plain(p), which a cell keeps for each of its vertices. A coordinate whose
// interval is one double is that double; the point is evaluated exactly otherwise (as
// to_plain did, so that costs nothing more), never through p.x(), which adds a lazy node.
void write_point(std::string& out, [[maybe_unused]] const exact::Point& p, Vec2 rounded) {
#if !defined(EXACITY_FLOAT_KERNEL)
  const auto& a = p.approx();
  if (a.x().inf() != a.x().sup() || a.y().inf() != a.y().sup()) {
    const auto& e = CGAL::exact(p);
    write_coordinate(out, rounded.x, e.x());
    write_coordinate(out, rounded.y, e.y());
    return;
  }
#endif
  write_double(out, rounded.x);
  write_double(out, rounded.y);
}

void write_ring(std::string& out, const KindRing& ring) {
  out += "ring " + std::to_string(ring.points.size()) + ' ';
  for (std::size_t i = 0; i < ring.points.size(); ++i) {
    write_point(out, ring.points[i], ring.rounded[i]);
    out += std::to_string(ring.kinds[i]) + ' ';
  }
}

}  // namespace

std::string exact_text(const Cell& cell) {
  std::string out;
  if (!cell.has_value()) return out;
  write_ring(out, cell.exact().outer);
  for (const KindRing& hole : cell.exact().holes) write_ring(out, hole);
  return out;
}

std::string exact_text(const Path& path) {
  std::string out = "path ";
  if (path.size() > 0)
    for (const exact::Point& p : path.exact().points) write_point(out, p, exact::to_plain(p));
  return out;
}

}  // namespace geom

namespace geom {
namespace {

// Reads exact_text's words back, one at a time.
class ExactTextReader {
 public:
  explicit ExactTextReader(std::string_view text) : text_(text) {}
  bool done() const { return at_ >= text_.size(); }
  std::string_view word() {
    const auto end = text_.find(' ', at_);
    if (end == std::string_view::npos) fail();
    const std::string_view w = text_.substr(at_, end - at_);
    at_ = end + 1;
    return w;
  }
  void expect(std::string_view w) {
    if (word() != w) fail();
  }
  long number() {
    const std::string_view w = word();
    long v = 0;
    if (std::from_chars(w.data(), w.data() + w.size(), v).ec != std::errc()) fail();
    return v;
  }
  // write_coordinate's text: a hex double, or 'q' and the exact rational.
  exact::FT coordinate() {
    const std::string_view w = word();
    if (!w.empty() && w[0] == 'q') {
#if !defined(EXACITY_FLOAT_KERNEL)
      std::istringstream in{std::string(w.substr(1))};
      exact::FT::ET value;
      if (!(in >> value) || !in.eof()) fail();
      return exact::FT(value);
#else
      fail();  // the float builds write every coordinate as a double
#endif
    }
    const bool negative = !w.empty() && w[0] == '-';
    const std::string_view digits = w.substr(negative ? 1 : 0);
    double v = 0;
    if (digits.substr(0, 2) != "0x" ||
        std::from_chars(digits.data() + 2, digits.data() + digits.size(), v, std::chars_format::hex).ptr !=
            digits.data() + digits.size())
      fail();
    return exact::FT(negative ? -v : v);
  }
  Point point() {
    exact::FT x = coordinate();
    return Point(x, coordinate());
  }
  [[noreturn]] void fail() const {
    throw std::invalid_argument("not an exact text of a cell or path at character " + std::to_string(at_));
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
};

KindRing read_ring(ExactTextReader& in) {
  KindRing ring;
  const long n = in.number();
  if (n < 0) in.fail();
  for (long i = 0; i < n; ++i) {
    ring.points.push_back(in.point());
    ring.kinds.push_back(static_cast<int>(in.number()));
  }
  return ring;
}

}  // namespace

Cell cell_from_exact_text(std::string_view text) {
  if (text.empty()) return Cell();
  ExactTextReader in(text);
  in.expect("ring");
  KindRing outer = read_ring(in);
  std::vector<KindRing> holes;
  while (!in.done()) in.expect("ring"), holes.push_back(read_ring(in));
  return make_cell(std::move(outer), std::move(holes));
}

Path path_from_exact_text(std::string_view text) {
  ExactTextReader in(text);
  in.expect("path");
  if (in.done()) return Path();
  auto impl = std::make_shared<Path::Impl>();
  while (!in.done()) impl->points.push_back(in.point());
  return Path(std::move(impl));
}

}  // namespace geom
