// The map's faces as polygons and cells (docs/design.md, Algorithms: The exact city map):
// edge-connected components of faces traced into simple loops (dissolve, cells,
// relabel_components), and a cell split by roads or inset in a small arrangement of its own
// (split_cell, inset_cell).
#include "geom/planar_map_arrangement.h"

#include <algorithm>
#include <unordered_map>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Unique_hash_map.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "geom/grid.h"
#include "geom/split_loops.h"
#include "geom/untangle.h"

namespace geom {
using namespace arrangement;

namespace {

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
  // CGAL's map by handle: a hash set of pointers spent a tenth of the lots stage.
  CGAL::Unique_hash_map<Face, bool> seen(false);
  for (auto start = arr.faces_begin(); start != arr.faces_end(); ++start) {
    int g = group_of(Face(start));
    if (g < 0 || seen[start]) continue;
    std::vector<Face> faces{start};
    std::vector<Halfedge> boundary;
    seen[start] = true;
    for (std::size_t i = 0; i < faces.size(); ++i)
      for_each_boundary_halfedge(faces[i], [&](Halfedge h) {
        Face t = h->twin()->face();
        if (group_of(t) != g) boundary.push_back(h);
        else if (!seen[t]) seen[t] = true, faces.push_back(t);
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
  CGAL::Unique_hash_map<Halfedge, bool> used(false);
  for_each_component(arr, group_of, [&](int g, const std::vector<Face>&, const std::vector<Halfedge>& boundary) {

    std::vector<std::vector<Halfedge>> outers, holes;
    std::vector<std::vector<Point>> outer_points;
    std::vector<int> neighbours;
    for (const Halfedge& first : boundary) {
      neighbours.push_back(first->twin()->face()->data());
      if (used[first]) continue;
      std::vector<Halfedge> walk;
      Halfedge h = first;
      do {
        used[h] = true;
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

// Each vertex's to_plain, kept by vertex while the map's edges are unchanged: the loops
// traced share most of their vertices, and rounding an exact one is costly. A PlanarMap's
// own are kept across its tracings (PlanarMap::Impl::rounded), which the lots and ground
// stages repeat after each relabelling; a small arrangement's, for one tracing.
//
// A tracing asks for each vertex's place in the table (which stays where it is as the
// table grows), then rounds the vertices new to it at once on TBB's threads (round_new),
// then reads the places: each rounding is the vertex's own, so the table is the same
// whatever the thread count.
class RoundedVertices {
 public:
  RoundedVertices() : rounded_(own_) {}
  explicit RoundedVertices(std::unordered_map<const void*, Vec2>& kept) : rounded_(kept) {}
  const Vec2* place(const Halfedge& h) {
    const auto [at, added] = rounded_.try_emplace(&*h->source());
    if (added) new_.push_back({&at->second, h->source()});
    return &at->second;
  }
  void round_new() {
    auto round = [&](std::size_t i) { *new_[i].first = to_plain(new_[i].second->point()); };
    if (new_.size() < 512) {  // a small arrangement's: not worth the threads
      for (std::size_t i = 0; i < new_.size(); ++i) round(i);
    } else {
      // Isolated: a thread waiting here takes no other task, which could trace this map
      // again under the lock the caller holds.
      tbb::this_task_arena::isolate([&] { tbb::parallel_for(std::size_t(0), new_.size(), round); });
    }
    new_.clear();
  }

 private:
  std::unordered_map<const void*, Vec2> own_;
  std::unordered_map<const void*, Vec2>& rounded_;
  std::vector<std::pair<Vec2*, Arrangement::Vertex_const_handle>> new_;
};

// A loop's vertices' places in RoundedVertices, rounded once round_new() has run.
using PlacedLoop = std::vector<const Vec2*>;

PlacedLoop placed_loop(const std::vector<Halfedge>& loop, RoundedVertices& rounded) {
  PlacedLoop places;
  places.reserve(loop.size());
  for (const Halfedge& h : loop) places.push_back(rounded.place(h));
  return places;
}

std::vector<Vec2> plain_ring(const PlacedLoop& places) {
  std::vector<Vec2> ring;
  ring.reserve(places.size());
  for (const Vec2* p : places) ring.push_back(*p);
  return ring;
}

// A cell traced, its rings' roundings still to read.
struct PlacedCell {
  KindRing outer;
  std::vector<KindRing> holes;
  PlacedLoop outer_places;
  std::vector<PlacedLoop> hole_places;
};

// Cells from traced polygons, to finish() once rounded; kind_of(h) gives the kind of
// boundary halfedge h.
template <typename KindOf>
void add_cells(const std::vector<LoopPolygon>& polygons, KindOf kind_of, RoundedVertices& rounded,
               std::vector<PlacedCell>& out) {
  auto ring = [&](const std::vector<Halfedge>& loop) {
    KindRing r;
    r.points.reserve(loop.size()), r.kinds.reserve(loop.size());
    for (const Halfedge& h : loop) r.points.push_back(h->source()->point()), r.kinds.push_back(kind_of(h));
    return r;
  };
  for (const LoopPolygon& p : polygons) {
    PlacedCell c{ring(p.outer), {}, placed_loop(p.outer, rounded), {}};
    for (const auto& h : p.holes) c.holes.push_back(ring(h)), c.hole_places.push_back(placed_loop(h, rounded));
    out.push_back(std::move(c));
  }
}

// The cells, their vertices rounded (RoundedVertices::round_new).
std::vector<Cell> finish(std::vector<PlacedCell> placed) {
  std::vector<Cell> cells;
  cells.reserve(placed.size());
  for (PlacedCell& c : placed) {
    c.outer.rounded = plain_ring(c.outer_places);
    for (std::size_t k = 0; k < c.holes.size(); ++k) c.holes[k].rounded = plain_ring(c.hole_places[k]);
    cells.push_back(make_cell(std::move(c.outer), std::move(c.holes)));
  }
  return cells;
}

}  // namespace

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
  const std::lock_guard lock(impl_->rounded_mutex);
  RoundedVertices rounded(impl_->rounded);
  struct Placed {
    int group, component;
    std::vector<PlacedLoop> loops;  // the outer loop, then the holes
  };
  std::vector<Placed> placed;
  std::vector<std::vector<int>> neighbours;  // per component
  trace_components(impl_->arr, impl_->group_function(group_of_label),
                   [&](int g, const std::vector<LoopPolygon>& polygons, const std::vector<int>& around) {
                     neighbours.push_back(around);
                     for (const LoopPolygon& lp : polygons) {
                       Placed p{g, static_cast<int>(neighbours.size()) - 1, {placed_loop(lp.outer, rounded)}};
                       for (const auto& h : lp.holes) p.loops.push_back(placed_loop(h, rounded));
                       placed.push_back(std::move(p));
                     }
                   });
  rounded.round_new();
  for (const Placed& p : placed) {
    std::vector<Ring> rings;
    for (const PlacedLoop& loop : p.loops) rings.push_back(plain_ring(loop));
    for (Polygon& polygon : untangle(rings)) result[p.group].push_back({std::move(polygon), neighbours[p.component]});
  }
  return result;
}

std::vector<Cell> PlanarMap::cells(const std::vector<int>& group_of_label, const std::vector<int>& kind_of_label,
                                   std::vector<int>* groups, std::vector<int>* components) const {
  std::vector<PlacedCell> cells;
  auto kind_of = [&](Halfedge h) {
    int l = h->twin()->face()->data();
    if (l == impl_->cell_outside && l >= 0)  // of_cell: the label across is the cell edge's
      for (const CurveTag& t : h->curve().data())
        if (t.counter == kCellEdge) l = impl_->cell_across[t.aux];
    return l >= 0 && l < static_cast<int>(kind_of_label.size()) ? kind_of_label[l] : 0;
  };
  int component = 0;
  const std::lock_guard lock(impl_->rounded_mutex);
  RoundedVertices rounded(impl_->rounded);
  trace_components(impl_->arr, impl_->group_function(group_of_label),
                   [&](int g, const std::vector<LoopPolygon>& polygons, const std::vector<int>&) {
                     add_cells(polygons, kind_of, rounded, cells);
                     if (groups) groups->resize(cells.size(), g);
                     if (components) components->resize(cells.size(), component);
                     ++component;
                   });
  rounded.round_new();
  return finish(std::move(cells));
}

PlanarMap PlanarMap::of_cell(const Cell& cell, int inside, int outside, const std::function<int(int)>& label_across) {
  PlanarMap map;
  std::vector<Curve> curves;
  std::vector<int>& across = map.impl_->cell_across;
  auto add_ring = [&](const KindRing& r) {
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      add_curve(curves, r.points[i], r.points[(i + 1) % r.points.size()],
                {kCellEdge, +1, static_cast<int>(across.size())});
      across.push_back(label_across(r.kinds[i]));
    }
  };
  add_ring(cell.exact().outer);
  for (const KindRing& h : cell.exact().holes) add_ring(h);
  insert_curves(map.impl_->arr, curves);
  label_all_faces(map.impl_->arr, [&](const Windings& w) { return winding_of(w, kCellEdge) != 0 ? inside : outside; });
  map.impl_->cell = cell;
  map.impl_->cell_outside = outside;
  return map;
}

Cell PlanarMap::outline_as_cut() const {
  const KindRing& outer = impl_->cell.exact().outer;
  std::vector<const KindRing*> rings{&outer};
  for (const KindRing& h : impl_->cell.exact().holes) rings.push_back(&h);
  // The map's vertices on each of the cell's edges: the ends of the pieces it was cut into.
  std::vector<std::vector<Arrangement::Vertex_const_handle>> on_edge(impl_->cell_across.size());
  for (auto e = impl_->arr.edges_begin(); e != impl_->arr.edges_end(); ++e)
    for (const CurveTag& t : e->curve().data())
      if (t.counter == kCellEdge) on_edge[t.aux].push_back(e->source()), on_edge[t.aux].push_back(e->target());
  const std::lock_guard lock(impl_->rounded_mutex);
  std::vector<KindRing> out;
  int index = 0;
  for (const KindRing* ring : rings) {
    KindRing r;
    for (std::size_t i = 0; i < ring->points.size(); ++i, ++index) {
      auto& vertices = on_edge[index];
      std::sort(vertices.begin(), vertices.end(), [](auto a, auto b) { return &*a < &*b; });
      vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
      // Along the edge, from its start (distinct vertices: compare_xy decides without a tie).
      const CGAL::Comparison_result forward =
          CGAL::compare_xy(ring->points[i], ring->points[(i + 1) % ring->points.size()]);
      std::sort(vertices.begin(), vertices.end(),
                [&](auto a, auto b) { return CGAL::compare_xy(a->point(), b->point()) == forward; });
      r.points.push_back(ring->points[i]), r.kinds.push_back(index), r.rounded.push_back(ring->rounded[i]);
      // The first is the edge's start and the last its end, the next edge's start.
      for (std::size_t k = 1; k + 1 < vertices.size(); ++k) {
        const auto [at, added] = impl_->rounded.try_emplace(&*vertices[k]);
        if (added) at->second = to_plain(vertices[k]->point());
        r.points.push_back(vertices[k]->point()), r.kinds.push_back(index), r.rounded.push_back(at->second);
      }
    }
    out.push_back(std::move(r));
  }
  KindRing outline = std::move(out.front());
  out.erase(out.begin());
  return make_cell(std::move(outline), std::move(out));
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
  std::vector<PlacedCell> parts;
  RoundedVertices rounded;
  trace_components(arr, group_of, [&](int, const std::vector<LoopPolygon>& polygons, const std::vector<int>&) {
    add_cells(polygons, kind_of, rounded, parts);
  });
  rounded.round_new();
  return finish(std::move(parts));
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
  std::vector<PlacedCell> parts;
  RoundedVertices rounded;
  trace_components(arr, [](Face f) { return f->data() == 1 ? 0 : -1; },
                   [&](int, const std::vector<LoopPolygon>& polygons, const std::vector<int>&) {
                     add_cells(polygons, [](Halfedge) { return 0; }, rounded, parts);
                   });
  rounded.round_new();
  return finish(std::move(parts));
}

}  // namespace geom
