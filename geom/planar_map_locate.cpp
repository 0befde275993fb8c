// PlanarMap::label_at and FaceLocator: the face holding a point, found by shooting a
// vertical ray through a grid of the map's edges, built once after the edges change
// (docs/design.md, Algorithms: The exact city map).
#include "geom/planar_map_arrangement.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include "geom/face_locator.h"

namespace geom {
using namespace arrangement;

namespace arrangement {

// The face around vertex v that holds the direction straight down from it: below its
// lowest edge to the right, else below its lowest edge to the left (no edge runs down from
// a vertex a ray up from below first meets).
Face face_below_vertex(Arrangement::Vertex_const_handle v) {
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

// Point location by vertical ray shooting: the face holding a point lies just below the
// first edge (or vertex) straight above it. The edges are bucketed on a grid of squares
// whose side is a power of two, so the buckets a point falls in are found exactly; a
// column's buckets are walked upwards from the point until the lowest hit found cannot be
// beaten. Only the vertices' points are read, through exact predicates: CGAL's segments
// cache their supporting line on first use (mutable members, written by a const call), so
// CGAL's own point locations write into the map while they read it, and threads that use
// them at once corrupt it. Built once the edges stop changing, then only read.
//
// The edges come from a Source, which the grid does not hold: its size(), and for edge i
// left(i) and right(i) (its ends' exact points, left to right, upwards where vertical) and
// box(i) (a box holding both). The map's own grid reads its arrangement; a FaceLocator, a
// copy of the points that outlives it.
class RayGrid {
 public:
  // What a vertical ray from the query point hits first on an edge: its interior (end -1),
  // or its left (0) or right (1) end.
  struct Hit {
    int edge = -1;
    int end = -1;
  };

  template <class Source>
  explicit RayGrid(const Source& s) {
    std::vector<double> sizes;
    sizes.reserve(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      const Box b = s.box(static_cast<int>(i));
      sizes.push_back(std::max(b.width(), b.height()));
    }
    // Squares about twice the typical edge: a point's column holds few edges per square.
    if (!sizes.empty()) {
      std::nth_element(sizes.begin(), sizes.begin() + static_cast<long>(sizes.size() / 2), sizes.end());
      const double typical = sizes[sizes.size() / 2];
      if (std::isfinite(typical) && typical > 0) side_ = std::ldexp(1.0, std::clamp(std::ilogb(typical) + 2, -30, 30));
    }
    CGAL::Protect_FPU_rounding<true> rounding;  // for the intervals in add_cells()
    for (std::size_t i = 0; i < s.size(); ++i) {
      const std::size_t first = cells_.size();
      if (!add_cells(s, static_cast<int>(i))) cells_.resize(first), wide_.push_back(static_cast<int>(i));
    }
    // On TBB's threads (the order is total: the same cells whatever the thread count), isolated
    // as the map's own grid is built under a lock that a stolen task could ask for again.
    tbb::this_task_arena::isolate([&] { tbb::parallel_sort(cells_.begin(), cells_.end()); });
    cells_.shrink_to_fit();
  }

  // The first hit straight above p (q, its doubles); edge -1 where the ray meets nothing.
  // Sets on_boundary, and stops, where p lies on an edge or a vertex.
  template <class Source>
  Hit first_above(const Source& s, const Point& p, Vec2 q, bool& on_boundary) const {
    Hit best;
    auto consider = [&](int i) {
      const Hit hit = hit_above(s, p, q, i, on_boundary);
      if (hit.edge >= 0 && (best.edge < 0 || below(s, hit, best))) best = hit;
    };
    for (int i : wide_) {
      consider(i);
      if (on_boundary) return {};
    }
    long column, row;
    if (key(q.x, column)) {
      if (!key(q.y, row)) row = q.y < 0 ? -kMaxKey : kMaxKey;
      auto it = std::lower_bound(cells_.begin(), cells_.end(), GridCell{static_cast<int>(column), static_cast<int>(row), -1});
      for (; it != cells_.end() && it->column == column; ++it) {
        // A lower hit would have its point in a square below this row's, all walked.
        if (it->row != row && best.edge >= 0 && top_of(s, best, q.x) < (row + 1.0) * side_) break;
        row = it->row;
        consider(it->edge);
        if (on_boundary) return {};
      }
    }
    return best;
  }

 private:
  struct GridCell {
    int column, row, edge;
    friend auto operator<=>(const GridCell&, const GridCell&) = default;
  };

  static constexpr long kMaxKey = 1L << 30;        // keys fit an int, and squares stay exact doubles
  static constexpr std::size_t kMaxCells = 4096;  // an edge over more is tried by every query

  template <class Source>
  static const Point& point(const Source& s, const Hit& hit) {
    return hit.end == 0 ? s.left(hit.edge) : s.right(hit.edge);
  }

  // The square's row or column of a coordinate: exact, since the side is a power of two.
  bool key(double v, long& k) const {
    const double f = std::floor(v / side_);
    if (!(std::abs(f) < kMaxKey)) return false;
    k = static_cast<long>(f);
    return true;
  }

  // Files edge i under every square it may pass through; false where it would take too many.
  template <class Source>
  bool add_cells(const Source& s, int i) {
    const Box b = s.box(i);
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
    const auto a = exact::approx(s.left(i)), z = exact::approx(s.right(i));
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
      count += static_cast<std::size_t>(hi - lo + 1);
      if (count > kMaxCells) return false;
      for (long r = lo; r <= hi; ++r) cells_.push_back({static_cast<int>(c), static_cast<int>(r), i});
    }
    return true;
  }

  // Where a vertical ray up from p first meets edge i; none where it misses it. Sets
  // on_boundary where p lies on the edge.
  template <class Source>
  static Hit hit_above(const Source& s, const Point& p, Vec2 q, int i, bool& on_boundary) {
    const Box b = s.box(i);
    if (q.x < b.min_x || q.x > b.max_x || q.y > b.max_y) return {};
    const Point &a = s.left(i), &z = s.right(i);
    const CGAL::Comparison_result from_a = CGAL::compare_x(p, a), from_z = CGAL::compare_x(p, z);
    if (from_a == CGAL::SMALLER || from_z == CGAL::LARGER) return {};
    auto at_end = [&](int end) -> Hit {
      const CGAL::Comparison_result y = CGAL::compare_y(p, end == 0 ? a : z);
      if (y == CGAL::EQUAL) on_boundary = true;
      return y == CGAL::SMALLER ? Hit{i, end} : Hit{};
    };
    if (from_a == CGAL::EQUAL && from_z == CGAL::EQUAL) {  // vertical: hit at its lower end
      if (CGAL::compare_y(p, a) != CGAL::SMALLER && CGAL::compare_y(p, z) != CGAL::LARGER) {
        on_boundary = true;
        return {};
      }
      return at_end(0);
    }
    if (from_a == CGAL::EQUAL) return at_end(0);
    if (from_z == CGAL::EQUAL) return at_end(1);
    const CGAL::Orientation o = CGAL::orientation(a, z, p);
    if (o == CGAL::COLLINEAR) on_boundary = true;
    return o == CGAL::RIGHT_TURN ? Hit{i, -1} : Hit{};
  }

  // Whether hit x lies strictly below hit y, on the query's vertical line. Edges meet only
  // at their ends, so two edges over the line keep their order over the x-range they share.
  template <class Source>
  static bool below(const Source& s, const Hit& x, const Hit& y) {
    if (x.end >= 0 && y.end >= 0) return CGAL::compare_y(point(s, x), point(s, y)) == CGAL::SMALLER;
    if (x.end >= 0) return CGAL::orientation(s.left(y.edge), s.right(y.edge), point(s, x)) == CGAL::RIGHT_TURN;
    if (y.end >= 0) return CGAL::orientation(s.left(x.edge), s.right(x.edge), point(s, y)) == CGAL::LEFT_TURN;
    const Point &xa = s.left(x.edge), &xz = s.right(x.edge), &ya = s.left(y.edge), &yz = s.right(y.edge);
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
  template <class Source>
  static double top_of(const Source& s, const Hit& hit, double x) {
    if (hit.end >= 0) return exact::approx(point(s, hit))[1].sup();
    const auto a = exact::approx(s.left(hit.edge)), z = exact::approx(s.right(hit.edge));
    CGAL::Protect_FPU_rounding<true> rounding;
    using I = CGAL::Interval_nt<false>;
    const I dx = z[0] - a[0];
    const double top = s.box(hit.edge).max_y;
    if (dx.inf() <= 0) return top;
    return std::min(top, (a[1] + (I(x) - a[0]) * ((z[1] - a[1]) / dx)).sup());
  }

  std::vector<GridCell> cells_;  // sorted: each column's squares from the bottom up
  std::vector<int> wide_;        // edges on no square: tried by every query
  double side_ = 1;
};

// The box of the interval approximations of a and b.
Box box_of(const Point& a, const Point& b) {
  const auto x = exact::approx(a), y = exact::approx(b);
  return {std::min(x[0].inf(), y[0].inf()), std::min(x[1].inf(), y[1].inf()), std::max(x[0].sup(), y[0].sup()),
          std::max(x[1].sup(), y[1].sup())};
}

// The map's own grid, over its arrangement's edges (each's box kept: queries test it first).
class EdgeGrid {
 public:
  explicit EdgeGrid(const Arrangement& arr) : unbounded_(arr.unbounded_face()) {
    edges_.reserve(arr.number_of_edges());
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
      const Halfedge h = left_to_right(Halfedge(e));
      edges_.push_back({h, box_of(h->source()->point(), h->target()->point())});
    }
    rays_.emplace(*this);
  }

  // The face holding p (q, its doubles), or none where p lies on an edge or a vertex.
  std::optional<Face> face_at(const Point& p, Vec2 q) const {
    bool on_boundary = false;
    const RayGrid::Hit hit = rays_->first_above(*this, p, q, on_boundary);
    if (on_boundary) return std::nullopt;
    // Just below the hit: below the edge, or at a vertex (face_below_vertex).
    const Halfedge h = hit.edge < 0 ? Halfedge() : edges_[static_cast<std::size_t>(hit.edge)].h;
    const Face f = hit.edge < 0 ? unbounded_ : hit.end < 0 ? h->twin()->face() : face_below_vertex(hit.end == 0 ? h->source() : h->target());
    for (auto v = f->isolated_vertices_begin(); v != f->isolated_vertices_end(); ++v)
      if (v->point() == p) return std::nullopt;
    return f;
  }

  // RayGrid's Source.
  std::size_t size() const { return edges_.size(); }
  const Point& left(int i) const { return edges_[static_cast<std::size_t>(i)].h->source()->point(); }
  const Point& right(int i) const { return edges_[static_cast<std::size_t>(i)].h->target()->point(); }
  const Box& box(int i) const { return edges_[static_cast<std::size_t>(i)].box; }

 private:
  struct Edge {
    Halfedge h;  // runs left to right (upwards where vertical)
    Box box;     // holds the edge: its ends' intervals
  };
  Face unbounded_;
  std::vector<Edge> edges_;
  std::optional<RayGrid> rays_;
};

}  // namespace arrangement

// Here, where EdgeGrid is whole: the Impl's constructor and destructor destroy its grid.
PlanarMap::Impl::Impl() { arr.unbounded_face()->set_data(-1); }
PlanarMap::Impl::~Impl() = default;

const EdgeGrid& PlanarMap::Impl::edge_grid() const {
  if (const EdgeGrid* g = ready_grid.load(std::memory_order_acquire)) return *g;
  std::lock_guard<std::mutex> lock(grid_mutex);
  if (!grid) {
    grid = std::make_unique<const EdgeGrid>(arr);
    ready_grid.store(grid.get(), std::memory_order_release);
  }
  return *grid;
}

void PlanarMap::Impl::edges_change() {
  ready_grid.store(nullptr);
  grid.reset();
  // A vertex removed frees its address for another.
  std::unordered_map<const void*, Vec2>().swap(rounded);
}

// FaceLocator: the map's walk (RayGrid, above) on a copy of what it reads of the map: each
// vertex's exact point, each edge's ends, and the labels of the faces below them, so that
// it stays when the arrangement is freed. Every decision is the same exact predicate on the
// same points, so every answer is label_at's. No boxes are kept (they are made again from
// the points when asked): the copy is taken while the map still holds its memory.
struct FaceLocator::Impl {
  struct Vertex {
    Point at;
    int below = -1;  // the label of the face around it that holds the direction straight down
  };
  struct Edge {
    int left = 0, right = 0;  // vertices, left to right (upwards where vertical)
    int below = -1;           // the label of the face below it
  };

  std::vector<Vertex> vertices;
  std::vector<Edge> edges;
  std::vector<Point> isolated;  // isolated vertices: a point on one is on no face
  std::optional<RayGrid> rays;  // made once the vertices and edges are in
  int unbounded = -1;           // the unbounded face's label

  // RayGrid's Source.
  std::size_t size() const { return edges.size(); }
  const Point& left(int i) const { return vertices[static_cast<std::size_t>(edges[static_cast<std::size_t>(i)].left)].at; }
  const Point& right(int i) const { return vertices[static_cast<std::size_t>(edges[static_cast<std::size_t>(i)].right)].at; }
  Box box(int i) const { return box_of(left(i), right(i)); }

  int label_at(const Point& p, Vec2 q) const {
    bool on_boundary = false;
    const RayGrid::Hit hit = rays->first_above(*this, p, q, on_boundary);
    if (on_boundary) return -1;
    // A point on an isolated vertex lies in the face around it, which the walk found.
    for (const Point& v : isolated)
      if (v == p) return -1;
    if (hit.edge < 0) return unbounded;
    const Edge& e = edges[static_cast<std::size_t>(hit.edge)];
    return hit.end < 0 ? e.below : vertices[static_cast<std::size_t>(hit.end == 0 ? e.left : e.right)].below;
  }
};

int FaceLocator::label_at(Vec2 point) const {
  return impl_ ? impl_->label_at(to_exact(point), point) : -1;
}

FaceLocator PlanarMap::face_locator() const {
  const Arrangement& arr = impl_->arr;
  auto out = std::make_shared<FaceLocator::Impl>();
  out->unbounded = arr.unbounded_face()->data();
  std::unordered_map<const void*, int> index;  // by the vertex's address
  index.reserve(arr.number_of_vertices());
  std::vector<Arrangement::Vertex_const_handle> vertices;
  vertices.reserve(arr.number_of_vertices());
  for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
    if (v->is_isolated()) {
      out->isolated.push_back(v->point());
      continue;
    }
    index.emplace(&*v, static_cast<int>(vertices.size()));
    vertices.push_back(v);
  }
  std::vector<Halfedge> edges;  // left to right
  edges.reserve(arr.number_of_edges());
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) edges.push_back(left_to_right(Halfedge(e)));
  // Each vertex's and edge's entry is its own: made at once on TBB's threads, in the map's order.
  out->vertices.resize(vertices.size());
  out->edges.resize(edges.size());
  tbb::parallel_for(std::size_t(0), vertices.size(), [&](std::size_t i) {
    out->vertices[i] = {vertices[i]->point(), face_below_vertex(vertices[i])->data()};
  });
  tbb::parallel_for(std::size_t(0), edges.size(), [&](std::size_t i) {
    const Halfedge& h = edges[i];
    out->edges[i] = {index.at(&*h->source()), index.at(&*h->target()), h->twin()->face()->data()};
  });
  out->rays.emplace(*out);
  return FaceLocator(std::move(out));
}

int PlanarMap::label_at(Vec2 point) const {
  const std::optional<Face> f = impl_->edge_grid().face_at(to_exact(point), point);
  return f ? (*f)->data() : -1;
}

}  // namespace geom
