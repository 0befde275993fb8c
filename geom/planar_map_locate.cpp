// PlanarMap::label_at: the face holding a point, found by shooting a vertical ray through a
// grid of the map's edges, built once after the edges change (docs/design.md, Algorithms:
// The exact city map).
#include "geom/planar_map_arrangement.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

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

  // The face just below the hit: below the edge, or at a vertex (face_below_vertex).
  Face face_below(const Hit& hit) const {
    if (!hit.vertex) return edges_[hit.edge].h->twin()->face();
    return face_below_vertex(*hit.vertex);
  }

  Face unbounded_;
  std::vector<Edge> edges_;
  std::vector<GridCell> cells_;  // sorted: each column's squares from the bottom up
  std::vector<int> wide_;        // edges on no square: tried by every query
  double side_ = 1;
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

// FaceLocator: EdgeGrid's walk (above) on a copy of what it reads of the map: each vertex's
// exact point, each edge's ends, and the labels of the faces below them, so that it stays
// when the arrangement is freed. Every decision is the same exact predicate on the same
// points, so every answer is label_at's.
struct FaceLocator::Impl {
  struct Vertex {
    Point at;
    int below = -1;  // the label of the face around it that holds the direction straight down
  };
  struct Edge {
    int left = 0, right = 0;  // vertices, left to right (upwards where vertical)
    int below = -1;           // the label of the face below it
  };
  struct GridCell {
    int column, row, edge;
    friend auto operator<=>(const GridCell&, const GridCell&) = default;
  };
  // What a vertical ray from the query point hits first on an edge: its interior, or one
  // of its ends (`vertex`).
  struct Hit {
    int edge = -1;
    int vertex = -1;
  };
  static constexpr long kMaxKey = 1L << 30;
  static constexpr std::size_t kMaxCells = 4096;

  std::vector<Vertex> vertices;
  std::vector<Edge> edges;
  std::vector<Point> isolated;  // isolated vertices: a point on one is on no face
  std::vector<GridCell> cells;  // sorted: each column's squares from the bottom up
  std::vector<int> wide;        // edges on no square: tried by every query
  double side = 1;
  int unbounded = -1;  // the unbounded face's label

  const Point& left(int i) const { return vertices[static_cast<std::size_t>(edges[static_cast<std::size_t>(i)].left)].at; }
  const Point& right(int i) const { return vertices[static_cast<std::size_t>(edges[static_cast<std::size_t>(i)].right)].at; }
  const Point& at(int v) const { return vertices[static_cast<std::size_t>(v)].at; }
  // Holds the edge: its ends' intervals.
  Box box(int i) const {
    const auto a = exact::approx(left(i)), b = exact::approx(right(i));
    return {std::min(a[0].inf(), b[0].inf()), std::min(a[1].inf(), b[1].inf()), std::max(a[0].sup(), b[0].sup()),
            std::max(a[1].sup(), b[1].sup())};
  }

  void index() {
    std::vector<double> sizes;
    sizes.reserve(edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const Box b = box(static_cast<int>(i));
      sizes.push_back(std::max(b.width(), b.height()));
    }
    if (!sizes.empty()) {
      std::nth_element(sizes.begin(), sizes.begin() + static_cast<long>(sizes.size() / 2), sizes.end());
      const double typical = sizes[sizes.size() / 2];
      if (std::isfinite(typical) && typical > 0) side = std::ldexp(1.0, std::clamp(std::ilogb(typical) + 2, -30, 30));
    }
    CGAL::Protect_FPU_rounding<true> rounding;  // for the intervals in add_cells()
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const std::size_t first = cells.size();
      if (!add_cells(static_cast<int>(i))) cells.resize(first), wide.push_back(static_cast<int>(i));
    }
    std::sort(cells.begin(), cells.end());
    cells.shrink_to_fit();
  }

  bool key(double v, long& k) const {
    const double f = std::floor(v / side);
    if (!(std::abs(f) < kMaxKey)) return false;
    k = static_cast<long>(f);
    return true;
  }

  bool add_cells(int i) {
    const Box b = box(i);
    long c0, c1, r0, r1;
    if (!key(b.min_x, c0) || !key(b.max_x, c1) || !key(b.min_y, r0) || !key(b.max_y, r1)) return false;
    if (static_cast<double>(c1 - c0 + 1) * static_cast<double>(r1 - r0 + 1) <= kMaxCells) {
      for (long c = c0; c <= c1; ++c)
        for (long r = r0; r <= r1; ++r) cells.push_back({static_cast<int>(c), static_cast<int>(r), i});
      return true;
    }
    if (c1 - c0 + 1 > static_cast<long>(kMaxCells)) return false;
    const auto a = exact::approx(left(i)), z = exact::approx(right(i));
    using I = CGAL::Interval_nt<false>;
    const I dx = z[0] - a[0];
    if (dx.inf() <= 0) return false;
    const I slope = (z[1] - a[1]) / dx;
    std::size_t count = 0;
    for (long c = c0; c <= c1; ++c) {
      const double from = std::max(b.min_x, (c - 0.0625) * side), to = std::min(b.max_x, (c + 1.0625) * side);
      const I y = a[1] + (I(from, to) - a[0]) * slope;
      long lo, hi;
      if (!key(std::max(y.inf(), b.min_y), lo) || !key(std::min(y.sup(), b.max_y), hi)) return false;
      count += static_cast<std::size_t>(hi - lo + 1);
      if (count > kMaxCells) return false;
      for (long r = lo; r <= hi; ++r) cells.push_back({static_cast<int>(c), static_cast<int>(r), i});
    }
    return true;
  }

  Hit hit_above(const Point& p, Vec2 q, int i, bool& on_boundary) const {
    const Box b = box(i);
    if (q.x < b.min_x || q.x > b.max_x || q.y > b.max_y) return {};
    const Point &a = left(i), &z = right(i);
    const CGAL::Comparison_result from_a = CGAL::compare_x(p, a), from_z = CGAL::compare_x(p, z);
    if (from_a == CGAL::SMALLER || from_z == CGAL::LARGER) return {};
    auto at_vertex = [&](int v) -> Hit {
      const CGAL::Comparison_result y = CGAL::compare_y(p, at(v));
      if (y == CGAL::EQUAL) on_boundary = true;
      return y == CGAL::SMALLER ? Hit{i, v} : Hit{};
    };
    const Edge& e = edges[static_cast<std::size_t>(i)];
    if (from_a == CGAL::EQUAL && from_z == CGAL::EQUAL) {  // vertical: hit at its lower end
      if (CGAL::compare_y(p, a) != CGAL::SMALLER && CGAL::compare_y(p, z) != CGAL::LARGER) {
        on_boundary = true;
        return {};
      }
      return at_vertex(e.left);
    }
    if (from_a == CGAL::EQUAL) return at_vertex(e.left);
    if (from_z == CGAL::EQUAL) return at_vertex(e.right);
    const CGAL::Orientation o = CGAL::orientation(a, z, p);
    if (o == CGAL::COLLINEAR) on_boundary = true;
    return o == CGAL::RIGHT_TURN ? Hit{i, -1} : Hit{};
  }

  bool below(const Hit& x, const Hit& y) const {
    if (x.vertex >= 0 && y.vertex >= 0) return CGAL::compare_y(at(x.vertex), at(y.vertex)) == CGAL::SMALLER;
    if (x.vertex >= 0) return CGAL::orientation(left(y.edge), right(y.edge), at(x.vertex)) == CGAL::RIGHT_TURN;
    if (y.vertex >= 0) return CGAL::orientation(left(x.edge), right(x.edge), at(y.vertex)) == CGAL::LEFT_TURN;
    const Point &xa = left(x.edge), &xz = right(x.edge), &ya = left(y.edge), &yz = right(y.edge);
    if (const auto c = CGAL::compare_x(xa, ya); c != CGAL::EQUAL)
      return c == CGAL::LARGER ? CGAL::orientation(ya, yz, xa) == CGAL::RIGHT_TURN
                               : CGAL::orientation(xa, xz, ya) == CGAL::LEFT_TURN;
    if (xa != ya) return CGAL::compare_y(xa, ya) == CGAL::SMALLER;
    if (const auto c = CGAL::compare_x(xz, yz); c != CGAL::EQUAL)
      return c == CGAL::SMALLER ? CGAL::orientation(ya, yz, xz) == CGAL::RIGHT_TURN
                                : CGAL::orientation(xa, xz, yz) == CGAL::LEFT_TURN;
    return CGAL::compare_y(xz, yz) == CGAL::SMALLER;
  }

  double top_of(const Hit& hit, double x) const {
    if (hit.vertex >= 0) return exact::approx(at(hit.vertex))[1].sup();
    const auto a = exact::approx(left(hit.edge)), z = exact::approx(right(hit.edge));
    CGAL::Protect_FPU_rounding<true> rounding;
    using I = CGAL::Interval_nt<false>;
    const I dx = z[0] - a[0];
    const double top = box(hit.edge).max_y;
    if (dx.inf() <= 0) return top;
    return std::min(top, (a[1] + (I(x) - a[0]) * ((z[1] - a[1]) / dx)).sup());
  }

  int label_at(const Point& p, Vec2 q) const {
    Hit best;
    bool on_boundary = false;
    auto consider = [&](int i) {
      const Hit hit = hit_above(p, q, i, on_boundary);
      if (hit.edge >= 0 && (best.edge < 0 || below(hit, best))) best = hit;
    };
    for (int i : wide) {
      consider(i);
      if (on_boundary) return -1;
    }
    long column, row;
    if (key(q.x, column)) {
      if (!key(q.y, row)) row = q.y < 0 ? -kMaxKey : kMaxKey;
      auto it = std::lower_bound(cells.begin(), cells.end(), GridCell{static_cast<int>(column), static_cast<int>(row), -1});
      for (; it != cells.end() && it->column == column; ++it) {
        if (it->row != row && best.edge >= 0 && top_of(best, q.x) < (row + 1.0) * side) break;
        row = it->row;
        consider(it->edge);
        if (on_boundary) return -1;
      }
    }
    // A point on an isolated vertex lies in the face around it, which the walk found.
    for (const Point& v : isolated)
      if (v == p) return -1;
    if (best.edge < 0) return unbounded;
    return best.vertex >= 0 ? vertices[static_cast<std::size_t>(best.vertex)].below
                            : edges[static_cast<std::size_t>(best.edge)].below;
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
  out->vertices.reserve(arr.number_of_vertices());
  for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
    if (v->is_isolated()) {
      out->isolated.push_back(v->point());
      continue;
    }
    index.emplace(&*v, static_cast<int>(out->vertices.size()));
    out->vertices.push_back({v->point(), face_below_vertex(v)->data()});
  }
  out->edges.reserve(arr.number_of_edges());
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const Halfedge h = left_to_right(Halfedge(e));
    out->edges.push_back({index.at(&*h->source()), index.at(&*h->target()), h->twin()->face()->data()});
  }
  out->index();
  return FaceLocator(std::move(out));
}

int PlanarMap::label_at(Vec2 point) const {
  const std::optional<Face> f = impl_->edge_grid().face_at(to_exact(point), point);
  return f ? (*f)->data() : -1;
}

}  // namespace geom
