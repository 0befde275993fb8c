// PlanarMap::insert_within: rings (lots) put into the faces of their own region (a block)
// only, cut in an arrangement of the region's own, so nothing outside it is looked at
// (docs/design.md, Exactness, rule 4).
#include "geom/planar_map_arrangement.h"

#include <algorithm>
#include <deque>
#include <optional>
#include <unordered_map>
#include <unordered_set>

namespace geom {
using namespace arrangement;

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

}  // namespace

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

std::vector<std::vector<VertexOnEdge>> PlanarMap::add_outlines(const std::vector<int>& region_of_label,
                                                                 const std::vector<Cell>& outline_of_region) {
  using Vertex = Arrangement::Vertex_handle;
  using MapHalfedge = Arrangement::Halfedge_handle;
  const int regions = static_cast<int>(outline_of_region.size());
  std::vector<std::vector<VertexOnEdge>> beyond(regions);
  Arrangement& arr = impl_->arr;
  // Splitting edges keeps every vertex, so the roundings traced so far stay true.
  std::unordered_map<const void*, Vec2> rounded;
  rounded.swap(impl_->rounded);
  impl_->edges_change();
  auto round = [&](Vertex v) {
    const auto [at, added] = rounded.try_emplace(&*v);
    if (added) at->second = to_plain(v->point());
    return at->second;
  };
  const auto region_of = impl_->group_function(region_of_label);
  auto wanted = [&](int r) { return r >= 0 && r < regions && outline_of_region[r].has_value(); };

  // Each region's boundary edges (the region on their left, another face on their right),
  // found by their ends as rounded: the outline's edges are the same exact segments.
  struct Boundary {
    int region;
    Vec2 from, to;
    MapHalfedge h;
  };
  auto key = [](const Boundary& b) { return std::tuple(b.region, b.from.x, b.from.y, b.to.x, b.to.y); };
  std::vector<Boundary> boundary;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    const int r = region_of(f);
    if (!wanted(r)) continue;
    for_each_boundary_halfedge(f, [&](Halfedge h) {
      if (region_of(h->twin()->face()) == r) return;
      MapHalfedge m = arr.non_const_handle(h);
      boundary.push_back({r, round(m->source()), round(m->target()), m});
    });
  }
  std::sort(boundary.begin(), boundary.end(), [&](const Boundary& a, const Boundary& b) { return key(a) < key(b); });

  // Each outline edge: the region's boundary edge it lies on, and the outline's vertices inside it.
  struct OwnPoint {
    Point point;
    Vec2 rounded;
    Vertex vertex;  // once the map has it
  };
  struct OutlineEdge {
    int region;
    Vertex from, to;
    Vec2 from_rounded, to_rounded;
    std::vector<OwnPoint> points;  // in order from `from`
  };
  std::vector<OutlineEdge> edges;
  std::unordered_map<const void*, std::vector<std::pair<int, int>>> points_on;  // map edge -> (outline edge, point)
  std::vector<MapHalfedge> split_order;  // the map edges to split, each once, left to right
  for (int r = 0; r < regions; ++r) {
    if (!wanted(r)) continue;
    const Cell::Impl& outline = outline_of_region[r].exact();
    std::vector<const KindRing*> rings{&outline.outer};
    for (const KindRing& h : outline.holes) rings.push_back(&h);
    for (const KindRing* ring : rings) {
      const std::size_t n = ring->points.size();
      for (std::size_t j = 0; j < n; ++j) {
        if (ring->kinds[j] == ring->kinds[(j + n - 1) % n]) continue;  // inside an edge of the cell, not its start
        std::size_t end = (j + 1) % n;
        while (ring->kinds[end] == ring->kinds[j] && end != j) end = (end + 1) % n;
        const Boundary probe{r, ring->rounded[j], ring->rounded[end], {}};
        auto [first, last] = std::equal_range(boundary.begin(), boundary.end(), probe,
                                              [&](const Boundary& a, const Boundary& b) { return key(a) < key(b); });
        if (last - first > 1)  // ends that round alike: the one with the same exact ends
          first = std::find_if(first, last, [&](const Boundary& b) {
            return b.h->source()->point() == ring->points[j] && b.h->target()->point() == ring->points[end];
          });
        if (first == last) continue;  // no edge of the region's there: not an outline of it
        OutlineEdge e{r, first->h->source(), first->h->target(), ring->rounded[j], ring->rounded[end], {}};
        for (std::size_t k = (j + 1) % n; k != end; k = (k + 1) % n) e.points.push_back({ring->points[k], ring->rounded[k], {}});
        if (!e.points.empty()) {
          const MapHalfedge lr = left_to_right(first->h);
          auto& on = points_on[&*lr];
          if (on.empty()) split_order.push_back(lr);
          for (std::size_t k = 0; k < e.points.size(); ++k) on.push_back({static_cast<int>(edges.size()), static_cast<int>(k)});
        }
        edges.push_back(std::move(e));
      }
    }
  }

  // Each map edge split once, at the points of every outline on it (two regions share an
  // edge where no road runs between them), in order left to right; a point both have is
  // one vertex.
  const auto split = arr.geometry_traits()->split_2_object();
  for (MapHalfedge h : split_order) {
    auto& on = points_on.at(&*h);
    auto point = [&](std::pair<int, int> p) -> const Point& { return edges[p.first].points[p.second].point; };
    std::sort(on.begin(), on.end(), [&](auto a, auto b) { return CGAL::compare_xy(point(a), point(b)) == CGAL::SMALLER; });
    for (std::size_t k = 0; k < on.size(); ++k) {
      OwnPoint& own = edges[on[k].first].points[on[k].second];
      if (k > 0 && point(on[k - 1]) == own.point) {
        own.vertex = edges[on[k - 1].first].points[on[k - 1].second].vertex;
        continue;
      }
      Traits::X_monotone_curve_2 left, right;
      split(h->curve(), own.point, left, right);
      h = arr.split_edge(h, left, right);
      own.vertex = h->target();
      rounded.emplace(&*own.vertex, own.rounded);
      h = h->next();
    }
  }
  snap_round();

  // Along each outline edge, the vertices the map has that the outline lacks, between the
  // outline's vertices they lie between.
  for (const OutlineEdge& e : edges) {
    // The boundary edge leaving `from` with the region on its left towards `to`: one, but
    // where the boundary touches itself at `from`.
    MapHalfedge start;
    int found = 0;
    auto around = e.from->incident_halfedges(), first = around;  // each with `from` as target
    do {
      MapHalfedge out = around->twin();
      if (region_of(out->face()) != e.region || region_of(out->twin()->face()) == e.region) continue;
      if (found++ == 0 || (CGAL::collinear(e.from->point(), out->target()->point(), e.to->point()) &&
                           CGAL::collinear_are_ordered_along_line(e.from->point(), out->target()->point(), e.to->point())))
        start = out;
    } while (++around != first);
    if (found == 0) continue;
    Vec2 last = e.from_rounded;
    std::vector<Vec2> waiting;  // vertices the outline lacks, since its last vertex
    std::size_t next = 0;       // the outline's next vertex along the edge
    for (MapHalfedge h = start; h->target() != e.to; h = h->next()) {
      const Vertex v = h->target();
      if (next < e.points.size() && v == e.points[next].vertex) {
        for (Vec2 at : waiting) beyond[e.region].push_back({last, e.points[next].rounded, at});
        waiting.clear();
        last = e.points[next++].rounded;
      } else {
        waiting.push_back(round(v));
      }
      if (h->next() == start) break;  // not an edge of the outline after all
    }
    for (Vec2 at : waiting) beyond[e.region].push_back({last, e.to_rounded, at});
  }
  impl_->rounded.swap(rounded);
  return beyond;
}

}  // namespace geom
