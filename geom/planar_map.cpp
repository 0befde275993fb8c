// The CGAL arrangement behind PlanarMap and cell splitting. This is the heavy translation
// unit: keep CGAL arrangement code here and nowhere else.
#include "geom/planar_map.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_observer.h>
#include <CGAL/Arr_non_caching_segment_traits_2.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Polygon_2_algorithms.h>

#include "geom/cell_impl.h"
#include "geom/grid.h"
#include "geom/kernel.h"
#include "geom/segment_buckets.h"
#include "geom/split_loops.h"
#include "geom/untangle.h"

namespace geom {
namespace {

using exact::Kernel;
using exact::Point;
using exact::to_exact;
using exact::to_plain;

using Tags = std::vector<CurveTag>;

// Overlapping curves become one edge that carries the tags of all of them.
struct ConcatenateTags {
  Tags operator()(const Tags& a, const Tags& b) const {
    Tags r = a;
    r.insert(r.end(), b.begin(), b.end());
    return r;
  }
};

#if EXACITY_FLOAT_KERNEL == 3
// The snapped build splits an edge at a grid point near it, not on it: each piece must be
// the segment between its ends, not a part of the first segment's line.
using SegmentTraits = CGAL::Arr_non_caching_segment_traits_2<Kernel>;
#else
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
#endif
using Traits = CGAL::Arr_curve_data_traits_2<SegmentTraits, Tags, ConcatenateTags>;
using Dcel = CGAL::Arr_face_extended_dcel<Traits, int>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;
using Curve = Traits::Curve_2;
using Halfedge = Arrangement::Halfedge_const_handle;
using Face = Arrangement::Face_const_handle;

// When a batch splits a face, both parts keep the label the face had.
class LabelKeeper : public CGAL::Arr_observer<Arrangement> {
 public:
  explicit LabelKeeper(Arrangement& arr) : CGAL::Arr_observer<Arrangement>(arr) {}
  void after_split_face(Arrangement::Face_handle f, Arrangement::Face_handle new_f, bool) override {
    new_f->set_data(f->data());
  }
};

// Queues the edge a -> b; a tag's sign is stored relative to the edge's left-to-right direction.
void add_curve(std::vector<Curve>& curves, const Point& a, const Point& b, CurveTag tag) {
  if (a == b) return;
  if (CGAL::compare_xy(a, b) == CGAL::LARGER) tag.sign = -tag.sign;
  curves.emplace_back(exact::Segment(a, b), Tags{tag});
}

// Queues the edges of a ring around `counter`.
void add_ring_curves(std::vector<Curve>& curves, const std::vector<Point>& ring, int counter) {
  for (std::size_t i = 0; i < ring.size(); ++i) add_curve(curves, ring[i], ring[(i + 1) % ring.size()], {counter, +1, 0});
}

// The halfedge of h's edge that runs left to right.
template <typename Handle>
Handle left_to_right(Handle h) {
  return h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? h : h->twin();
}

constexpr int kMapEdge = INT_MIN;  // tag counter of a map edge copied into a region's own arrangement

#if EXACITY_FLOAT_KERNEL == 3
// Inserts the curves noded by snap rounding in doubles (geom/snap_noding.h) together with
// the edges the arrangement has already: those are split where the new curves' hot pixels
// lie on them, and the new curves go in as pieces between grid points, each keeping its
// curve's tags (a ring tag's sign follows the piece's own left-to-right direction). The
// sweep then meets only shared ends and constructs no point of its own.
void insert_curves(Arrangement& arr, std::vector<Curve>& curves) {
  std::vector<Arrangement::Halfedge_handle> edges;  // each left to right
  std::vector<std::pair<Vec2, Vec2>> ends;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    edges.push_back(left_to_right(Arrangement::Halfedge_handle(e)));
    ends.push_back({to_plain(edges.back()->source()->point()), to_plain(edges.back()->target()->point())});
  }
  // Edges split in place, and a map edge a region's arrangement splits the same way, must
  // keep their pieces in order along them.
  std::vector<bool> monotone(edges.size(), true);
  for (const Curve& c : curves) {
    ends.push_back({to_plain(c.source()), to_plain(c.target())});
    monotone.push_back(std::any_of(c.data().begin(), c.data().end(), [](const CurveTag& t) { return t.counter == kMapEdge; }));
  }
  const std::vector<Polyline> lines = snap_round_segments(ends, exact::kSnapStep, monotone);
  const auto split = arr.geometry_traits()->split_2_object();
  for (std::size_t i = 0; i < edges.size(); ++i) {
    Arrangement::Halfedge_handle h = edges[i];
    for (std::size_t k = 1; k + 1 < lines[i].size(); ++k) {
      Traits::X_monotone_curve_2 left, right;
      split(h->curve(), to_exact(lines[i][k]), left, right);
      h = arr.split_edge(h, left, right)->next();
    }
  }
  std::vector<Curve> noded;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const Polyline& line = lines[edges.size() + i];
    const bool given_left_to_right = CGAL::compare_xy(curves[i].source(), curves[i].target()) == CGAL::SMALLER;
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const Point a = to_exact(line[k]), b = to_exact(line[k + 1]);
      Tags tags = curves[i].data();
      if ((CGAL::compare_xy(a, b) == CGAL::SMALLER) != given_left_to_right)
        for (CurveTag& t : tags) t.sign = -t.sign;
      noded.emplace_back(exact::Segment(a, b), std::move(tags));
    }
  }
  CGAL::insert(arr, noded.begin(), noded.end());
}
#else
// Inserts the curves in one sweep.
void insert_curves(Arrangement& arr, std::vector<Curve>& curves) { CGAL::insert(arr, curves.begin(), curves.end()); }
#endif

void add_winding(Windings& w, int counter, int delta) {
  auto it = std::lower_bound(w.begin(), w.end(), std::make_pair(counter, INT32_MIN));
  if (it != w.end() && it->first == counter) {
    it->second += delta;
    if (it->second == 0) w.erase(it);
  } else {
    w.insert(it, {counter, delta});
  }
}

// Calls f for every halfedge on every boundary cycle of face `face`.
template <typename F>
void for_each_boundary_halfedge(Face face, F&& f) {
  auto walk = [&](auto ccb) {
    auto h = ccb;
    do f(Halfedge(h)); while (++h != ccb);
  };
  for (auto c = face->outer_ccbs_begin(); c != face->outer_ccbs_end(); ++c) walk(*c);
  for (auto c = face->inner_ccbs_begin(); c != face->inner_ccbs_end(); ++c) walk(*c);
}

// Gives every face label_of(its windings of counters >= from_counter, its label so far),
// walking out from the unbounded face. Faces are numbered through their data while the
// walk runs, so nothing is hashed.
void label_all_faces(Arrangement& arr, int from_counter, const std::function<int(const Windings&, int)>& label_of) {
  std::vector<int> previous;
  std::vector<Arrangement::Face_handle> faces;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    previous.push_back(f->data());
    f->set_data(static_cast<int>(faces.size()));
    faces.push_back(f);
  }
  std::vector<Windings> windings(faces.size());
  std::vector<char> reached(faces.size(), 0);
  std::vector<int> labels(faces.size(), -1);
  std::deque<int> queue{arr.unbounded_face()->data()};
  reached[queue.front()] = 1;
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    labels[i] = label_of(windings[i], previous[i]);
    for_each_boundary_halfedge(faces[i], [&](Halfedge h) {
      const int j = h->twin()->face()->data();
      if (reached[j]) return;
      reached[j] = 1;
      // h has face i on its left: crossing h from right to left raises a counter by one
      // for every ring edge running the same way as h.
      Windings wj = windings[i];
      bool left_to_right = h->direction() == CGAL::ARR_LEFT_TO_RIGHT;
      for (const CurveTag& t : h->curve().data())
        if (t.sign != 0 && t.counter >= from_counter) add_winding(wj, t.counter, (t.sign > 0) == left_to_right ? -1 : +1);
      windings[j] = std::move(wj);
      queue.push_back(j);
    });
    Windings().swap(windings[i]);
  }
  for (std::size_t i = 0; i < faces.size(); ++i) faces[i]->set_data(labels[i]);
}

void label_all_faces(Arrangement& arr, const std::function<int(const Windings&)>& label_of) {
  label_all_faces(arr, INT_MIN, [&](const Windings& w, int) { return label_of(w); });
}

std::vector<Point> loop_points(const std::vector<Halfedge>& loop) {
  std::vector<Point> pts;
  pts.reserve(loop.size());
  for (const Halfedge& h : loop) pts.push_back(h->source()->point());
  return pts;
}

CGAL::Orientation loop_orientation(const std::vector<Point>& pts) {
  auto lowest = std::min_element(pts.begin(), pts.end(), [](const Point& a, const Point& b) {
    return CGAL::compare_xy(a, b) == CGAL::SMALLER;
  });
  std::size_t i = lowest - pts.begin(), n = pts.size();
  return CGAL::orientation(pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
}

// A polygon of halfedge loops: one counter-clockwise outer loop, clockwise holes.
struct LoopPolygon {
  std::vector<Halfedge> outer;
  std::vector<std::vector<Halfedge>> holes;
};

// Calls f(group, faces, boundary) for each edge-connected component of faces that share a
// group (group_of(face) >= 0), in face order; boundary: the halfedges with the component on
// their left and another group on their right.
template <typename GroupOf, typename F>
void for_each_component(const Arrangement& arr, GroupOf group_of, F f) {
  std::unordered_set<const void*> seen;
  for (auto start = arr.faces_begin(); start != arr.faces_end(); ++start) {
    int g = group_of(Face(start));
    if (g < 0 || seen.count(&*start)) continue;
    std::vector<Face> faces{start};
    std::vector<Halfedge> boundary;
    seen.insert(&*start);
    for (std::size_t i = 0; i < faces.size(); ++i)
      for_each_boundary_halfedge(faces[i], [&](Halfedge h) {
        Face t = h->twin()->face();
        if (group_of(t) != g) boundary.push_back(h);
        else if (seen.insert(&*t).second) faces.push_back(t);
      });
    f(g, faces, boundary);
  }
}

// Calls emit(group, polygons, neighbour labels) for each edge-connected component of faces
// that share a group (group_of(face) >= 0), in face order. Boundaries are walked with the
// component on the left, turning as tightly as possible at each vertex, and cut where
// they touch themselves, so every loop is simple; a hole may touch its outer loop.
template <typename GroupOf, typename Emit>
void trace_components(const Arrangement& arr, GroupOf group_of, Emit emit) {
  std::unordered_set<const void*> used;
  for_each_component(arr, group_of, [&](int g, const std::vector<Face>&, const std::vector<Halfedge>& boundary) {

    std::vector<std::vector<Halfedge>> outers, holes;
    std::vector<std::vector<Point>> outer_points;
    std::vector<int> neighbours;
    for (const Halfedge& first : boundary) {
      neighbours.push_back(first->twin()->face()->data());
      if (used.count(&*first)) continue;
      std::vector<Halfedge> walk;
      Halfedge h = first;
      do {
        used.insert(&*h);
        walk.push_back(h);
        Halfedge next = h->next();
        while (group_of(next->twin()->face()) == g) next = next->twin()->next();
        h = next;
      } while (h != first);
      for (auto& loop : split_at_repeats<const void*>(walk, [](const Halfedge& h) -> const void* { return &*h->source(); })) {
        std::vector<Point> pts = loop_points(loop);
        if (loop_orientation(pts) == CGAL::COUNTERCLOCKWISE) {
          outers.push_back(std::move(loop));
          outer_points.push_back(std::move(pts));
        } else {
          holes.push_back(std::move(loop));
        }
      }
    }
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());

    std::vector<LoopPolygon> polygons;
    for (auto& o : outers) polygons.push_back({std::move(o), {}});
    for (auto& hole : holes) {
      std::size_t owner = 0;
      if (outer_points.size() > 1) {
        Point probe = CGAL::midpoint(hole[0]->source()->point(), hole[0]->target()->point());
        double best_area = 0;
        for (std::size_t k = 0; k < outer_points.size(); ++k) {
          const auto& o = outer_points[k];
          if (CGAL::bounded_side_2(o.begin(), o.end(), probe, Kernel()) != CGAL::ON_BOUNDED_SIDE) continue;
          double area = CGAL::to_double(CGAL::polygon_area_2(o.begin(), o.end(), Kernel()));
          if (best_area == 0 || area < best_area) best_area = area, owner = k;
        }
      }
      if (!polygons.empty()) polygons[owner].holes.push_back(std::move(hole));
    }
    emit(g, polygons, neighbours);
  });
}

Ring plain_ring(const std::vector<Halfedge>& loop) {
  Ring ring;
  for (const Halfedge& h : loop) ring.push_back(to_plain(h->source()->point()));
  return ring;
}

// Cells from traced polygons; kind_of(h) gives the kind of boundary halfedge h.
template <typename KindOf>
void add_cells(const std::vector<LoopPolygon>& polygons, KindOf kind_of, std::vector<Cell>& out) {
  auto ring = [&](const std::vector<Halfedge>& loop) {
    KindRing r;
    for (const Halfedge& h : loop) r.points.push_back(h->source()->point()), r.kinds.push_back(kind_of(h));
    return r;
  };
  for (const LoopPolygon& p : polygons) {
    std::vector<KindRing> holes;
    for (const auto& h : p.holes) holes.push_back(ring(h));
    out.push_back(make_cell(ring(p.outer), std::move(holes)));
  }
}

// Point location by vertical ray shooting: the face holding a point lies just below the
// first edge (or vertex) straight above it. The edges are bucketed on a grid of squares
// whose side is a power of two, so the buckets a point falls in are found exactly; a
// column's buckets are walked upwards from the point until the lowest hit found cannot be
// beaten. Only the vertices' points are read, through exact predicates: CGAL's segments
// cache their supporting line on first use (mutable members, written by a const call), so
// CGAL's own point locations write into the map while they read it, and threads that use
// them at once corrupt it. Built once the map stops changing, then only read.
class EdgeGrid {
 public:
  explicit EdgeGrid(const Arrangement& arr) : unbounded_(arr.unbounded_face()) {
    std::vector<double> sizes;
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
      const Halfedge h = left_to_right(Halfedge(e));
      const auto a = exact::approx(h->source()->point()), b = exact::approx(h->target()->point());
      edges_.push_back({h, {std::min(a[0].inf(), b[0].inf()), std::min(a[1].inf(), b[1].inf()),
                            std::max(a[0].sup(), b[0].sup()), std::max(a[1].sup(), b[1].sup())}});
      sizes.push_back(std::max(edges_.back().box.width(), edges_.back().box.height()));
    }
    // Squares about twice the typical edge: a point's column holds few edges per square.
    if (!sizes.empty()) {
      std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
      const double typical = sizes[sizes.size() / 2];
      if (std::isfinite(typical) && typical > 0) side_ = std::ldexp(1.0, std::clamp(std::ilogb(typical) + 2, -30, 30));
    }
    CGAL::Protect_FPU_rounding<true> rounding;  // for the intervals in rows_over()
    for (std::size_t i = 0; i < edges_.size(); ++i) {
      const std::size_t first = cells_.size();
      if (!add_cells(static_cast<int>(i))) cells_.resize(first), wide_.push_back(static_cast<int>(i));
    }
    std::sort(cells_.begin(), cells_.end());
    cells_.shrink_to_fit();
  }

  // The face holding p (q, its doubles), or none where p lies on an edge or a vertex.
  std::optional<Face> face_at(const Point& p, Vec2 q) const {
    Hit best;
    bool on_boundary = false;
    auto consider = [&](int i) {
      const Hit hit = hit_above(p, q, i, on_boundary);
      if (hit.edge >= 0 && (best.edge < 0 || below(hit, best))) best = hit;
    };
    for (int i : wide_) {
      consider(i);
      if (on_boundary) return std::nullopt;
    }
    long column, row;
    if (key(q.x, column)) {
      if (!key(q.y, row)) row = q.y < 0 ? -kMaxKey : kMaxKey;
      auto it = std::lower_bound(cells_.begin(), cells_.end(), GridCell{static_cast<int>(column), static_cast<int>(row), -1});
      for (; it != cells_.end() && it->column == column; ++it) {
        // A lower hit would have its point in a square below this row's, all walked.
        if (it->row != row && best.edge >= 0 && top_of(best, q.x) < (row + 1.0) * side_) break;
        row = it->row;
        consider(it->edge);
        if (on_boundary) return std::nullopt;
      }
    }
    Face f = best.edge < 0 ? unbounded_ : face_below(best);
    for (auto v = f->isolated_vertices_begin(); v != f->isolated_vertices_end(); ++v)
      if (v->point() == p) return std::nullopt;
    return f;
  }

 private:
  struct Edge {
    Halfedge h;  // runs left to right (upwards where vertical)
    Box box;     // holds the edge: its ends' intervals
  };
  struct GridCell {
    int column, row, edge;
    friend auto operator<=>(const GridCell&, const GridCell&) = default;
  };
  // What a vertical ray from the query point hits first on an edge: its interior, or one
  // of its ends (`vertex`).
  struct Hit {
    int edge = -1;
    std::optional<Arrangement::Vertex_const_handle> vertex;
  };

  static constexpr long kMaxKey = 1L << 30;        // keys fit an int, and squares stay exact doubles
  static constexpr std::size_t kMaxCells = 4096;  // an edge over more is tried by every query

  // The square's row or column of a coordinate: exact, since the side is a power of two.
  bool key(double v, long& k) const {
    const double f = std::floor(v / side_);
    if (!(std::abs(f) < kMaxKey)) return false;
    k = static_cast<long>(f);
    return true;
  }

  const Point& left(int i) const { return edges_[i].h->source()->point(); }
  const Point& right(int i) const { return edges_[i].h->target()->point(); }

  // Files edge i under every square it may pass through; false where it would take too many.
  bool add_cells(int i) {
    const Box& b = edges_[i].box;
    long c0, c1, r0, r1;
    if (!key(b.min_x, c0) || !key(b.max_x, c1) || !key(b.min_y, r0) || !key(b.max_y, r1)) return false;
    if (static_cast<double>(c1 - c0 + 1) * static_cast<double>(r1 - r0 + 1) <= kMaxCells) {
      for (long c = c0; c <= c1; ++c)
        for (long r = r0; r <= r1; ++r) cells_.push_back({static_cast<int>(c), static_cast<int>(r), i});
      return true;
    }
    if (c1 - c0 + 1 > static_cast<long>(kMaxCells)) return false;
    // A long slanted edge: per column, the rows its stretch over the column (widened a
    // little) may reach.
    const auto a = exact::approx(left(i)), z = exact::approx(right(i));
    using I = CGAL::Interval_nt<false>;
    const I dx = z[0] - a[0];
    if (dx.inf() <= 0) return false;
    const I slope = (z[1] - a[1]) / dx;
    std::size_t count = 0;
    for (long c = c0; c <= c1; ++c) {
      const double from = std::max(b.min_x, (c - 0.0625) * side_), to = std::min(b.max_x, (c + 1.0625) * side_);
      const I y = a[1] + (I(from, to) - a[0]) * slope;
      long lo, hi;
      if (!key(std::max(y.inf(), b.min_y), lo) || !key(std::min(y.sup(), b.max_y), hi)) return false;
      count += hi - lo + 1;
      if (count > kMaxCells) return false;
      for (long r = lo; r <= hi; ++r) cells_.push_back({static_cast<int>(c), static_cast<int>(r), i});
    }
    return true;
  }

  // Where a vertical ray up from p first meets edge i; none where it misses it. Sets
  // on_boundary where p lies on the edge.
  Hit hit_above(const Point& p, Vec2 q, int i, bool& on_boundary) const {
    const Box& b = edges_[i].box;
    if (q.x < b.min_x || q.x > b.max_x || q.y > b.max_y) return {};
    const Point &a = left(i), &z = right(i);
    const CGAL::Comparison_result from_a = CGAL::compare_x(p, a), from_z = CGAL::compare_x(p, z);
    if (from_a == CGAL::SMALLER || from_z == CGAL::LARGER) return {};
    auto at_vertex = [&](Arrangement::Vertex_const_handle v) -> Hit {
      const CGAL::Comparison_result y = CGAL::compare_y(p, v->point());
      if (y == CGAL::EQUAL) on_boundary = true;
      return y == CGAL::SMALLER ? Hit{i, v} : Hit{};
    };
    if (from_a == CGAL::EQUAL && from_z == CGAL::EQUAL) {  // vertical: hit at its lower end
      if (CGAL::compare_y(p, a) != CGAL::SMALLER && CGAL::compare_y(p, z) != CGAL::LARGER) {
        on_boundary = true;
        return {};
      }
      return at_vertex(edges_[i].h->source());
    }
    if (from_a == CGAL::EQUAL) return at_vertex(edges_[i].h->source());
    if (from_z == CGAL::EQUAL) return at_vertex(edges_[i].h->target());
    const CGAL::Orientation o = CGAL::orientation(a, z, p);
    if (o == CGAL::COLLINEAR) on_boundary = true;
    return o == CGAL::RIGHT_TURN ? Hit{i, std::nullopt} : Hit{};
  }

  // Whether hit x lies strictly below hit y, on the query's vertical line. Edges meet only
  // at their ends, so two edges over the line keep their order over the x-range they share.
  bool below(const Hit& x, const Hit& y) const {
    if (x.vertex && y.vertex) return CGAL::compare_y((*x.vertex)->point(), (*y.vertex)->point()) == CGAL::SMALLER;
    if (x.vertex) return CGAL::orientation(left(y.edge), right(y.edge), (*x.vertex)->point()) == CGAL::RIGHT_TURN;
    if (y.vertex) return CGAL::orientation(left(x.edge), right(x.edge), (*y.vertex)->point()) == CGAL::LEFT_TURN;
    const Point &xa = left(x.edge), &xz = right(x.edge), &ya = left(y.edge), &yz = right(y.edge);
    // Compare at an end of one that lies strictly inside the other's x-range.
    if (const auto c = CGAL::compare_x(xa, ya); c != CGAL::EQUAL)
      return c == CGAL::LARGER ? CGAL::orientation(ya, yz, xa) == CGAL::RIGHT_TURN
                               : CGAL::orientation(xa, xz, ya) == CGAL::LEFT_TURN;
    if (xa != ya) return CGAL::compare_y(xa, ya) == CGAL::SMALLER;
    if (const auto c = CGAL::compare_x(xz, yz); c != CGAL::EQUAL)
      return c == CGAL::SMALLER ? CGAL::orientation(ya, yz, xz) == CGAL::RIGHT_TURN
                                : CGAL::orientation(xa, xz, yz) == CGAL::LEFT_TURN;
    return CGAL::compare_y(xz, yz) == CGAL::SMALLER;
  }

  // A double at or above the hit's y.
  double top_of(const Hit& hit, double x) const {
    if (hit.vertex) return exact::approx((*hit.vertex)->point())[1].sup();
    const auto a = exact::approx(left(hit.edge)), z = exact::approx(right(hit.edge));
    CGAL::Protect_FPU_rounding<true> rounding;
    using I = CGAL::Interval_nt<false>;
    const I dx = z[0] - a[0];
    const double top = edges_[hit.edge].box.max_y;
    if (dx.inf() <= 0) return top;
    return std::min(top, (a[1] + (I(x) - a[0]) * ((z[1] - a[1]) / dx)).sup());
  }

  // The face just below the hit: below the edge, or, at a vertex, the face around it that
  // holds the direction straight down (below its lowest edge to the right, else below its
  // lowest edge to the left; no edge runs down from it, or the ray would have met that first).
  Face face_below(const Hit& hit) const {
    if (!hit.vertex) return edges_[hit.edge].h->twin()->face();
    const Arrangement::Vertex_const_handle v = *hit.vertex;
    const Point& o = v->point();
    std::optional<Halfedge> right_in, left_in;  // halfedges into v
    auto h = v->incident_halfedges();
    const auto first = h;
    do {
      const Point& u = h->source()->point();
      const CGAL::Comparison_result side = CGAL::compare_x(u, o);
      if (side == CGAL::LARGER) {
        if (!right_in || CGAL::orientation(o, (*right_in)->source()->point(), u) == CGAL::RIGHT_TURN) right_in = Halfedge(h);
      } else if (side == CGAL::SMALLER) {
        if (!left_in || CGAL::orientation(o, (*left_in)->source()->point(), u) == CGAL::LEFT_TURN) left_in = Halfedge(h);
      }
    } while (++h != first);
    // Into v from the right runs right to left: its face is below it; from the left, its twin's.
    if (right_in) return (*right_in)->face();
    if (left_in) return (*left_in)->twin()->face();
    return Halfedge(first)->face();
  }

  Face unbounded_;
  std::vector<Edge> edges_;
  std::vector<GridCell> cells_;  // sorted: each column's squares from the bottom up
  std::vector<int> wide_;        // edges on no square: tried by every query
  double side_ = 1;
};

}  // namespace

int winding_of(const Windings& w, int counter) {
  auto it = std::lower_bound(w.begin(), w.end(), std::make_pair(counter, INT32_MIN));
  return it != w.end() && it->first == counter ? it->second : 0;
}

struct PlanarMap::Impl {
  Arrangement arr;
  LabelKeeper keeper{arr};
  // label_at's point location: built by the first query after the edges last changed
  // (threads that query at once wait for one to build it), then only read.
  mutable std::mutex grid_mutex;
  mutable std::unique_ptr<const EdgeGrid> grid;
  mutable std::atomic<const EdgeGrid*> ready_grid{nullptr};

  const EdgeGrid& edge_grid() const {
    if (const EdgeGrid* g = ready_grid.load(std::memory_order_acquire)) return *g;
    std::lock_guard<std::mutex> lock(grid_mutex);
    if (!grid) {
      grid = std::make_unique<const EdgeGrid>(arr);
      ready_grid.store(grid.get(), std::memory_order_release);
    }
    return *grid;
  }
  // Called before the edges change (never while label_at runs).
  void edges_change() {
    ready_grid.store(nullptr);
    grid.reset();
  }
  std::vector<Curve> pending;
  std::vector<std::vector<Curve>> within;  // per region, for insert_within()
  std::map<int, std::vector<Point>> polylines;
  // Edges given as doubles, kept aside until the batch: ends in left-to-right order.
  struct PlainEdge {
    Vec2 a, b;
    CurveTag tag;
  };
  std::vector<PlainEdge> plain_pending;

  void add_edge(const Point& a, const Point& b, CurveTag tag) { add_curve(pending, a, b, tag); }

  void add_plain_edge(Vec2 a, Vec2 b, CurveTag tag) {
    if (a == b) return;
    if (b.x < a.x || (b.x == a.x && b.y < a.y)) std::swap(a, b), tag.sign = -tag.sign;
    plain_pending.push_back({a, b, tag});
  }

  // An edge given more than once (the edge two rings share) becomes one curve carrying
  // every tag, in the order given, so the sweep has no overlap between them to resolve.
  // Only edges given as doubles are compared: cheaply, and so exactly.
  void merge_plain_edges() {
    auto key = [](const PlainEdge& e) { return std::tuple(e.a.x, e.a.y, e.b.x, e.b.y); };
    std::stable_sort(plain_pending.begin(), plain_pending.end(),
                     [&](const PlainEdge& p, const PlainEdge& q) { return key(p) < key(q); });
    for (std::size_t k = 0; k < plain_pending.size();) {
      Tags tags;
      std::size_t next = k;
      for (; next < plain_pending.size() && key(plain_pending[next]) == key(plain_pending[k]); ++next)
        tags.push_back(plain_pending[next].tag);
      pending.emplace_back(exact::Segment(to_exact(plain_pending[k].a), to_exact(plain_pending[k].b)), std::move(tags));
      k = next;
    }
    plain_pending.clear();
  }

  void add_exact_ring(const exact::ExactRing& ring, int counter) { add_ring_curves(pending, ring, counter); }

  std::vector<Curve>& within_region(int region) {
    if (static_cast<int>(within.size()) <= region) within.resize(region + 1);
    return within[region];
  }

  void add_polyline(std::vector<Point> pts, int tag) {
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) add_edge(pts[i], pts[i + 1], {tag, 0, static_cast<int>(i)});
    polylines[tag] = std::move(pts);
  }

  auto group_function(const std::vector<int>& group_of_label) const {
    return [&group_of_label](Face f) {
      int l = f->data();
      return l >= 0 && l < static_cast<int>(group_of_label.size()) ? group_of_label[l] : -1;
    };
  }
};

PlanarMap::PlanarMap() : impl_(std::make_unique<Impl>()) { impl_->arr.unbounded_face()->set_data(-1); }
PlanarMap::~PlanarMap() = default;
PlanarMap::PlanarMap(PlanarMap&&) noexcept = default;
PlanarMap& PlanarMap::operator=(PlanarMap&&) noexcept = default;

void PlanarMap::add_ring(const Ring& ring, int counter, int aux) {
  for (std::size_t i = 0; i < ring.size(); ++i) impl_->add_plain_edge(ring[i], ring[(i + 1) % ring.size()], {counter, +1, aux});
}

void PlanarMap::add_edge(Vec2 a, Vec2 b, int counter) { impl_->add_plain_edge(a, b, {counter, +1, 0}); }

void PlanarMap::add_stroke(const Polyline& line, double half_width, int counter) {
  for (const exact::ExactRing& piece : exact::stroke_pieces(line, half_width)) impl_->add_exact_ring(piece, counter);
}

void PlanarMap::add_joint(Vec2 a, Vec2 q, Vec2 b, double half_width, int counter) {
  impl_->add_exact_ring(exact::joint_piece(a, q, b, half_width), counter);
}

void PlanarMap::add_disc(Vec2 centre, double radius, int counter) {
  impl_->add_exact_ring(exact::disc_piece(centre, radius), counter);
}

bool PlanarMap::add_junction(Vec2 q, const std::vector<JunctionArm>& arms, int counter) {
  exact::ExactRing ring = exact::junction_piece(q, arms);
  if (ring.empty()) return false;
  impl_->add_exact_ring(ring, counter);
  return true;
}

void PlanarMap::add_polyline(const Polyline& line, int tag) {
  std::vector<Point> pts;
  for (Vec2 p : line) pts.push_back(to_exact(p));
  impl_->add_polyline(std::move(pts), tag);
}

void PlanarMap::add_ring_within(int region, const Ring& ring, int counter) {
  std::vector<Point> points;
  for (Vec2 v : ring) points.push_back(to_exact(v));
  add_ring_curves(impl_->within_region(region), points, counter);
}

void PlanarMap::add_cell_within(int region, const Cell& cell, int counter) {
  std::vector<Curve>& curves = impl_->within_region(region);
  add_ring_curves(curves, cell.exact().outer.points, counter);
  for (const KindRing& h : cell.exact().holes) add_ring_curves(curves, h.points, counter);
}

void PlanarMap::add_path(const Path& path, int tag) { impl_->add_polyline(path.exact().points, tag); }

void PlanarMap::add_path_stroke(const Path& path, double half_width, int counter) {
  add_stroke(path.to_plain(), half_width, counter);
}

void PlanarMap::insert_batch() {
  impl_->edges_change();
  impl_->merge_plain_edges();
  insert_curves(impl_->arr, impl_->pending);
  impl_->pending.clear();
}

namespace {

// One region's rings, cut against the region's faces in an arrangement of their own, then
// put into the map: map edges split where the rings touch them, ring edges inside the
// region added between vertices (CGAL's low-level insertions, each local to a face), and
// the faces labelled. Nothing outside the region's faces is looked at.
class RegionInsertion {
 public:
  RegionInsertion(Arrangement& map, const std::vector<Arrangement::Face_handle>& faces, std::vector<Curve> rings,
                  const std::function<bool(Face)>& in_region)
      : map_(map) {
    std::unordered_set<const void*> seen;
    std::vector<Curve> curves = std::move(rings);
    for (Arrangement::Face_handle f : faces) {
      for_each_boundary_halfedge(f, [&](Halfedge h) {
        if (!seen.insert(std::min<const void*>(&*h, &*h->twin())).second) return;
        h = left_to_right(h);
        // The map's own curve, so points found on it come from its supporting line (the
        // line of the segment first inserted), as the map's would: tight approximations.
        curves.emplace_back(h->curve(), Tags{{kMapEdge, 0, static_cast<int>(map_edges_.size())}});
        map_edges_.push_back(map_.non_const_handle(h));
      });
      for (auto v = f->isolated_vertices_begin(); v != f->isolated_vertices_end(); ++v) isolated_.push_back(v);
    }
    insert_curves(local_, curves);
    for (auto v : isolated_) vertex_of_.emplace(&*CGAL::insert_point(local_, v->point()), v);
    // Each local face's windings, and the map face it lies in (none outside the region):
    // known across a map edge's piece, the same on both sides of a ring edge.
    label_all_faces(local_, [&](const Windings& w) {
      windings_.push_back(w);
      return static_cast<int>(windings_.size()) - 1;
    });
    owner_.assign(windings_.size(), Face());
    std::vector<char> known(windings_.size(), 0);
    std::deque<int> queue;
    for (auto h = local_.halfedges_begin(); h != local_.halfedges_end(); ++h) {
      const int k = map_edge_of(h);
      if (k < 0 || known[h->face()->data()]) continue;
      Face side = h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? Face(map_edges_[k]->face()) : Face(map_edges_[k]->twin()->face());
      known[h->face()->data()] = 1;
      if (in_region(side)) owner_[h->face()->data()] = side, queue.push_back(h->face()->data());
    }
    std::vector<Face> local_faces(windings_.size());  // by number
    for (auto f = local_.faces_begin(); f != local_.faces_end(); ++f) local_faces[f->data()] = f;
    while (!queue.empty()) {
      const int i = queue.front();
      queue.pop_front();
      for_each_boundary_halfedge(local_faces[i], [&](Halfedge h) {
        const int j = h->twin()->face()->data();
        if (map_edge_of(h) >= 0 || known[j]) return;
        known[j] = 1, owner_[j] = owner_[i], queue.push_back(j);
      });
    }
  }

  // Puts the cut into the map and labels the faces inside the region.
  void apply(const std::function<int(const Windings&, int)>& label_of) {
    std::vector<int> previous(owner_.size(), -1);
    for (std::size_t i = 0; i < owner_.size(); ++i)
      if (owner_[i] != Face()) previous[i] = owner_[i]->data();
    split_map_edges();
    add_ring_edges();
    for (auto f = local_.faces_begin(); f != local_.faces_end(); ++f) {
      const int i = f->data();
      if (owner_[i] == Face() || f->is_unbounded()) continue;
      const int label = label_of(windings_[i], previous[i]);
      auto h = f->outer_ccb();
      do {
        if (auto g = map_halfedge(h)) {
          (*g)->face()->set_data(label);
          break;
        }
      } while (++h != f->outer_ccb());
    }
  }

 private:
  using LocalHalfedge = Arrangement::Halfedge_const_handle;

  static int map_edge_of(LocalHalfedge h) {
    for (const CurveTag& t : h->curve().data())
      if (t.counter == kMapEdge) return t.aux;
    return -1;
  }

  bool inside(LocalHalfedge h) const { return owner_[h->face()->data()] != Face() || owner_[h->twin()->face()->data()] != Face(); }

  // Splits each map edge at the points where the region's rings meet it, in order along it.
  void split_map_edges() {
    std::vector<std::vector<LocalHalfedge>> pieces(map_edges_.size());
    for (auto e = local_.edges_begin(); e != local_.edges_end(); ++e) {
      LocalHalfedge h = left_to_right(LocalHalfedge(e));
      if (int k = map_edge_of(h); k >= 0) pieces[k].push_back(h);
    }
    const auto split = map_.geometry_traits()->split_2_object();
    for (std::size_t k = 0; k < map_edges_.size(); ++k) {
      auto& p = pieces[k];
      if (p.empty()) continue;
      std::unordered_map<const void*, LocalHalfedge> from;  // piece by its left vertex
      std::unordered_set<const void*> rights;
      for (LocalHalfedge h : p) from.emplace(&*h->source(), h), rights.insert(&*h->target());
      LocalHalfedge piece = *std::find_if(p.begin(), p.end(), [&](LocalHalfedge h) { return !rights.count(&*h->source()); });
      Arrangement::Halfedge_handle h = map_edges_[k];
      vertex_of_.emplace(&*piece->source(), h->source());
      for (std::size_t n = 1; n < p.size(); ++n) {
        Traits::X_monotone_curve_2 left, right;
        split(h->curve(), piece->target()->point(), left, right);
        h = map_.split_edge(h, left, right);
        vertex_of_.emplace(&*piece->target(), h->target());
        h = h->next();
        piece = from.at(&*piece->target());
      }
      vertex_of_.emplace(&*piece->target(), h->target());
    }
  }

  // Adds the ring edges inside the region, each from a vertex the map has already, so the
  // face it goes into follows from the edges around that vertex.
  void add_ring_edges() {
    std::unordered_map<const void*, std::vector<LocalHalfedge>> at;  // ring edges by vertex
    std::vector<LocalHalfedge> ready;
    for (auto e = local_.edges_begin(); e != local_.edges_end(); ++e) {
      LocalHalfedge h = left_to_right(LocalHalfedge(e));
      if (map_edge_of(h) >= 0 || !inside(h)) continue;
      at[&*h->source()].push_back(h), at[&*h->target()].push_back(h);
      if (vertex_of_.count(&*h->source()) || vertex_of_.count(&*h->target())) ready.push_back(h);
    }
    while (!ready.empty()) {
      LocalHalfedge h = ready.back();  // left to right
      ready.pop_back();
      if (added_.count(&*h)) continue;
      Traits::X_monotone_curve_2 curve(h->curve(), Tags{});
      auto left = vertex_of_.find(&*h->source()), right = vertex_of_.find(&*h->target());
      Arrangement::Halfedge_handle g;  // left to right
      const void* reached = nullptr;
      if (left != vertex_of_.end() && right != vertex_of_.end()) {
        g = map_.insert_at_vertices(curve, left->second, right->second);
      } else if (left != vertex_of_.end()) {
        g = map_.insert_from_left_vertex(curve, left->second);
        vertex_of_.emplace(reached = &*h->target(), g->target());
      } else {
        g = map_.insert_from_right_vertex(curve, right->second)->twin();
        vertex_of_.emplace(reached = &*h->source(), g->source());
      }
      added_.emplace(&*h, g);
      if (reached)
        for (LocalHalfedge next : at[reached]) ready.push_back(next);
    }
  }

  // The map's halfedge for a local one, once both its ends are map vertices.
  std::optional<Arrangement::Halfedge_handle> map_halfedge(LocalHalfedge h) const {
    const bool reversed = h->direction() != CGAL::ARR_LEFT_TO_RIGHT;
    if (auto it = added_.find(reversed ? &*h->twin() : &*h); it != added_.end())
      return reversed ? it->second->twin() : it->second;
    auto from = vertex_of_.find(&*h->source()), to = vertex_of_.find(&*h->target());
    if (from == vertex_of_.end() || to == vertex_of_.end()) return std::nullopt;
    auto around = from->second->incident_halfedges(), first = around;  // each with `from` as target
    do
      if (around->source() == to->second) return around->twin();
    while (++around != first);
    return std::nullopt;
  }

  Arrangement& map_;
  Arrangement local_;
  std::vector<Arrangement::Halfedge_handle> map_edges_;  // left to right
  std::vector<Arrangement::Vertex_handle> isolated_;
  std::vector<Windings> windings_;  // per local face
  std::vector<Face> owner_;         // per local face: the map face it lies in, or none
  std::unordered_map<const void*, Arrangement::Vertex_handle> vertex_of_;  // local vertex -> map vertex
  std::unordered_map<const void*, Arrangement::Halfedge_handle> added_;   // local halfedge -> map halfedge, left to right
};

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
  for_each_near_pair(near, ends, 16 * step + 2 * widest, [&](int v, int e) {
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

void PlanarMap::insert_within(const std::vector<int>& region_of_label,
                               const std::function<int(const Windings&, int)>& label_of) {
  impl_->edges_change();
  auto region_of = impl_->group_function(region_of_label);
  std::vector<std::vector<Arrangement::Face_handle>> faces(impl_->within.size());
  for (auto f = impl_->arr.faces_begin(); f != impl_->arr.faces_end(); ++f)
    if (int r = region_of(f); r >= 0 && r < static_cast<int>(faces.size())) faces[r].push_back(f);
  for (std::size_t r = 0; r < faces.size(); ++r) {
    if (impl_->within[r].empty() || faces[r].empty()) continue;
    RegionInsertion cut(impl_->arr, faces[r], std::move(impl_->within[r]),
                        [&](Face f) { return region_of(f) == static_cast<int>(r); });
    cut.apply(label_of);
  }
  impl_->within.clear();
}

void PlanarMap::label_faces(const std::function<int(const Windings&)>& label_of) {
  label_all_faces(impl_->arr, label_of);
}

void PlanarMap::relabel_faces(int from_counter, const std::function<int(const Windings&, int)>& label_of) {
  label_all_faces(impl_->arr, from_counter, label_of);
}

void PlanarMap::relabel_components(const std::vector<int>& group_of_label, const std::function<int(int, int)>& relabel) {
  // Collected first: relabelled faces would change the groups the walk still reads.
  std::vector<std::vector<Face>> components;
  for_each_component(impl_->arr, impl_->group_function(group_of_label),
                     [&](int, const std::vector<Face>& faces, const std::vector<Halfedge>&) { components.push_back(faces); });
  for (std::size_t c = 0; c < components.size(); ++c)
    for (Face f : components[c]) impl_->arr.non_const_handle(f)->set_data(relabel(static_cast<int>(c), f->data()));
}

std::vector<std::vector<Dissolved>> PlanarMap::dissolve(const std::vector<int>& group_of_label,
                                                        int group_count) const {
  std::vector<std::vector<Dissolved>> result(group_count);
  trace_components(impl_->arr, impl_->group_function(group_of_label),
                   [&](int g, const std::vector<LoopPolygon>& polygons, const std::vector<int>& neighbours) {
                     for (const LoopPolygon& lp : polygons) {
                       std::vector<Ring> rings{plain_ring(lp.outer)};
                       for (const auto& h : lp.holes) rings.push_back(plain_ring(h));
                       for (Polygon& p : untangle(rings)) result[g].push_back({std::move(p), neighbours});
                     }
                   });
  return result;
}

std::vector<Cell> PlanarMap::cells(const std::vector<int>& group_of_label, const std::vector<int>& kind_of_label,
                                   std::vector<int>* groups, std::vector<int>* components) const {
  std::vector<Cell> cells;
  auto kind_of = [&](Halfedge h) {
    int l = h->twin()->face()->data();
    return l >= 0 && l < static_cast<int>(kind_of_label.size()) ? kind_of_label[l] : 0;
  };
  int component = 0;
  trace_components(impl_->arr, impl_->group_function(group_of_label),
                   [&](int g, const std::vector<LoopPolygon>& polygons, const std::vector<int>&) {
                     add_cells(polygons, kind_of, cells);
                     if (groups) groups->resize(cells.size(), g);
                     if (components) components->resize(cells.size(), component);
                     ++component;
                   });
  return cells;
}

std::vector<Cell> split_cell(const Cell& cell, const std::vector<Path>& roads, int road_kind) {
  // A small arrangement of the cell's boundary (winding around counter 0, tagged with each
  // edge's kind) and the roads (counter 1); every face inside becomes a cell.
  Arrangement arr;
  std::vector<Curve> curves;
  auto add_ring = [&](const KindRing& r) {
    for (std::size_t i = 0; i < r.points.size(); ++i)
      add_curve(curves, r.points[i], r.points[(i + 1) % r.points.size()], {0, +1, r.kinds[i]});
  };
  add_ring(cell.exact().outer);
  for (const auto& h : cell.exact().holes) add_ring(h);
  for (const Path& road : roads) {
    const auto& p = road.exact().points;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) add_curve(curves, p[i], p[i + 1], {1, 0, 0});
  }
  insert_curves(arr, curves);
  label_all_faces(arr, [](const Windings& w) { return winding_of(w, 0) != 0 ? 1 : -1; });

  std::unordered_map<const void*, int> index;  // each face inside is its own group
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
    if (f->data() == 1) index.emplace(&*f, static_cast<int>(index.size()));
  auto group_of = [&](Face f) {
    auto it = index.find(&*f);
    return it == index.end() ? -1 : it->second;
  };
  auto kind_of = [&](Halfedge h) {
    int kind = 0;
    for (const CurveTag& t : h->curve().data()) {
      if (t.counter == 1) return road_kind;
      kind = t.aux;
    }
    return kind;
  };
  std::vector<Cell> parts;
  trace_components(arr, group_of, [&](int, const std::vector<LoopPolygon>& polygons, const std::vector<int>&) {
    add_cells(polygons, kind_of, parts);
  });
  return parts;
}

std::vector<Cell> inset_cell(const Cell& cell, double s) {
  // The cell winds around counter 0, the bands around counter 1; what is inside the
  // first and outside every band is left.
  Arrangement arr;
  std::vector<Curve> curves;
  auto add_ring = [&](const std::vector<Point>& r, int counter, int kind) {
    for (std::size_t i = 0; i < r.size(); ++i) add_curve(curves, r[i], r[(i + 1) % r.size()], {counter, +1, kind});
  };
  auto add_bands = [&](const KindRing& r) {
    add_ring(r.points, 0, 0);
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      Vec2 a = to_plain(r.points[i]), b = to_plain(r.points[(i + 1) % r.points.size()]);
      double len = std::hypot(b.x - a.x, b.y - a.y);
      if (len == 0) continue;
      Vec2 t{(b.x - a.x) / len, (b.y - a.y) / len}, n{-t.y, t.x};  // the cell is on the left
      const double out = 1.0;  // reaches past the edge's exact position, whatever the rounding
      auto at = [&](Vec2 p, double along, double across) {
        return to_exact(snap(Vec2{p.x + t.x * along + n.x * across, p.y + t.y * along + n.y * across}));
      };
      add_ring({at(a, -s, -out), at(b, s, -out), at(b, s, s), at(a, -s, s)}, 1, 0);
    }
  };
  add_bands(cell.exact().outer);
  for (const KindRing& h : cell.exact().holes) add_bands(h);
  insert_curves(arr, curves);
  label_all_faces(arr, [](const Windings& w) { return winding_of(w, 0) != 0 && winding_of(w, 1) == 0 ? 1 : -1; });
  std::vector<Cell> parts;
  trace_components(arr, [](Face f) { return f->data() == 1 ? 0 : -1; },
                   [&](int, const std::vector<LoopPolygon>& polygons, const std::vector<int>&) {
                     add_cells(polygons, [](Halfedge) { return 0; }, parts);
                   });
  return parts;
}

std::map<int, std::vector<PolylinePiece>> PlanarMap::polyline_pieces() const {
  struct Item {
    int segment;
    Halfedge h;  // running the polyline's way
  };
  std::map<int, std::vector<Item>> items;
  for (auto e = impl_->arr.edges_begin(); e != impl_->arr.edges_end(); ++e) {
    for (const CurveTag& t : e->curve().data()) {
      auto line = impl_->polylines.find(t.counter);
      if (t.sign != 0 || line == impl_->polylines.end()) continue;
      const std::vector<Point>& pts = line->second;
      bool segment_left_to_right = CGAL::compare_xy(pts[t.aux], pts[t.aux + 1]) == CGAL::SMALLER;
      bool edge_left_to_right = e->direction() == CGAL::ARR_LEFT_TO_RIGHT;
      items[t.counter].push_back({t.aux, segment_left_to_right == edge_left_to_right ? Halfedge(e) : Halfedge(e->twin())});
    }
  }
  std::map<int, std::vector<PolylinePiece>> result;
  for (auto& [tag, list] : items) {
    const std::vector<Point>& pts = impl_->polylines.at(tag);
    std::sort(list.begin(), list.end(), [&](const Item& a, const Item& b) {
      if (a.segment != b.segment) return a.segment < b.segment;
      return CGAL::compare_distance_to_point(pts[a.segment], a.h->source()->point(), b.h->source()->point()) ==
             CGAL::SMALLER;
    });
    std::vector<PolylinePiece>& pieces = result[tag];
    for (const Item& it : list)
      pieces.push_back({it.segment, to_plain(it.h->source()->point()), to_plain(it.h->target()->point()),
                        it.h->face()->data(), it.h->twin()->face()->data()});
  }
  return result;
}

int PlanarMap::label_at(Vec2 point) const {
  const std::optional<Face> f = impl_->edge_grid().face_at(to_exact(point), point);
  return f ? (*f)->data() : -1;
}

std::map<int, int> PlanarMap::polyline_degrees() const {
  std::map<int, int> degrees;
  for (auto v = impl_->arr.vertices_begin(); v != impl_->arr.vertices_end(); ++v) {
    int degree = 0;
    if (v->is_isolated()) continue;
    auto h = v->incident_halfedges();
    auto first = h;
    do {
      for (const CurveTag& t : h->curve().data())
        if (t.sign == 0) {
          ++degree;
          break;
        }
    } while (++h != first);
    if (degree > 0) ++degrees[degree];
  }
  return degrees;
}

void PlanarMap::for_each_edge(const std::function<void(const std::vector<CurveTag>&, Vec2, Vec2)>& f) const {
  for (auto e = impl_->arr.edges_begin(); e != impl_->arr.edges_end(); ++e)
    f(e->curve().data(), to_plain(e->source()->point()), to_plain(e->target()->point()));
}

bool PlanarMap::point_near_label(int label, Vec2& out) const {
  for (auto f = impl_->arr.faces_begin(); f != impl_->arr.faces_end(); ++f) {
    if (f->data() != label) continue;
    bool found = false;
    for_each_boundary_halfedge(f, [&](Halfedge h) {
      if (!found) out = to_plain(h->source()->point()), found = true;
    });
    if (found) return true;
  }
  return false;
}

std::vector<double> PlanarMap::widest_faces(int labels) const {
  std::vector<double> widest(labels, 0.0);
  for (auto f = impl_->arr.faces_begin(); f != impl_->arr.faces_end(); ++f) {
    if (f->data() < 0 || f->data() >= labels || f->is_unbounded()) continue;
    double twice_area = 0, perimeter = 0;
    bool first = true;
    Vec2 o;
    for_each_boundary_halfedge(f, [&](Halfedge h) {
      const Vec2 a = to_plain(h->source()->point()), b = to_plain(h->target()->point());
      if (first) o = a, first = false;
      twice_area += (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
      perimeter += std::hypot(b.x - a.x, b.y - a.y);
    });
    if (perimeter > 0) widest[f->data()] = std::max(widest[f->data()], std::abs(twice_area) / perimeter);
  }
  return widest;
}

PlanarMapCounts PlanarMap::counts() const {
  const Arrangement& arr = impl_->arr;
  return {arr.number_of_vertices(), arr.number_of_edges(), arr.number_of_faces()};
}

const char* kernel_name() { return exact::kKernelName; }

bool kernel_validates_its_output() { return !exact::kSnapped; }

}  // namespace geom
