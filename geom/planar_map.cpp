// The arrangement behind PlanarMap (docs/design.md, Algorithms: The exact city map): curves
// queued and inserted in batches, faces labelled by their windings, and what the map is asked
// of its edges and faces. Insertion within a block, snap rounding, tracing cells and point
// location are in planar_map_within.cpp, planar_map_snap_round.cpp, planar_map_cells.cpp and
// planar_map_locate.cpp. This is the heavy translation unit: CGAL's sweep is compiled here.
#include "geom/planar_map_arrangement.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <deque>
#include <list>
#include <map>
#include <tuple>

#include <CGAL/Arr_accessor.h>
#include <CGAL/Surface_sweep_2.h>
#include <CGAL/Surface_sweep_2/Arr_construction_event.h>
#include <CGAL/Surface_sweep_2/Arr_construction_subcurve.h>
#include <CGAL/Surface_sweep_2/Arr_construction_ss_visitor.h>
#include <CGAL/Surface_sweep_2/Arr_insertion_ss_visitor.h>
#include <CGAL/Surface_sweep_2/Arr_insertion_traits_2.h>
#include <CGAL/Surface_sweep_2/Surface_sweep_2_utils.h>

#include "geom/grid.h"

namespace geom {
using namespace arrangement;

namespace arrangement {

void add_curve(std::vector<Curve>& curves, const Point& a, const Point& b, CurveTag tag) {
  if (a == b) return;
  if (CGAL::compare_xy(a, b) == CGAL::LARGER) tag.sign = -tag.sign;
  curves.emplace_back(exact::Segment(a, b), Tags{tag});
}

void add_ring_curves(std::vector<Curve>& curves, const std::vector<Point>& ring, int counter) {
  for (std::size_t i = 0; i < ring.size(); ++i) add_curve(curves, ring[i], ring[(i + 1) % ring.size()], {counter, +1, 0});
}

#if defined(EXACITY_SNAPPED_KERNEL)
namespace {

// The pieces of a polyline as curves with `tags`, given relative to the left-to-right
// direction of the segment first -> last: a ring tag's sign follows each piece's own. Each
// piece runs left to right, as every edge's curve then does: where a piece runs along an
// edge the map has, CGAL gives that edge the overlap's curve, which must equal its own, and
// the kernel's segments are equal only running the same way.
void add_pieces(std::vector<Curve>& out, const Polyline& line, const Tags& tags) {
  if (line.size() < 2) return;
  const bool line_left_to_right = CGAL::compare_xy(to_exact(line.front()), to_exact(line.back())) == CGAL::SMALLER;
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Point a = to_exact(line[k]), b = to_exact(line[k + 1]);
    const bool left_to_right = CGAL::compare_xy(a, b) == CGAL::SMALLER;
    Tags piece = tags;
    if (left_to_right != line_left_to_right)
      for (CurveTag& t : piece) t.sign = -t.sign;
    out.emplace_back(left_to_right ? exact::Segment(a, b) : exact::Segment(b, a), std::move(piece));
  }
}

}  // namespace

// Inserts the curves noded by snap rounding in doubles (geom/snap_noding.h) together with
// the edges the arrangement has already. An edge the rounding routes through new hot pixels
// is bent off its line, so it is taken out and its pieces go in with the new curves, each
// keeping its tags, and CGAL's insertion works out from the geometry where they lie. Split
// in place instead, the arrangement failed its own validity check right after the splits
// (the order of the edges around each vertex still held; what a bent piece moved to its
// other side was not found), and CGAL's precondition `f == f2` stopped the insertion. The
// sweep then meets only shared ends and equal pieces and constructs no point of its own.
// Faces lose their labels here, as in every build: each batch is labelled again after it.
void insert_curves(Arrangement& arr, std::vector<Curve>& curves, std::size_t given_from) {
  std::vector<Arrangement::Halfedge_handle> edges;  // each left to right
  std::vector<std::pair<Vec2, Vec2>> ends;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    edges.push_back(left_to_right(Arrangement::Halfedge_handle(e)));
    ends.push_back({to_plain(edges.back()->source()->point()), to_plain(edges.back()->target()->point())});
  }
  // Edges the arrangement has (their ends are its vertices: a new end this near one moves
  // onto it), map edges a region's arrangement splits, and a cell's edges in a map of the
  // cell alone (PlanarMap::of_cell: a block's edges as the city's map has them, which its
  // lots' map must keep where they are, or its lots leave the block the city writes): all
  // keep their ends and their pieces in order along them (a region's map edges are split in
  // place in the map).
  std::vector<bool> monotone(edges.size(), true), given(edges.size(), false);
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const Curve& c = curves[i];
    ends.push_back({to_plain(c.source()), to_plain(c.target())});
    monotone.push_back(std::any_of(c.data().begin(), c.data().end(),
                                   [](const CurveTag& t) { return t.counter == kMapEdge || t.counter == kCellEdge; }));
    given.push_back(i >= given_from);
  }
  const std::vector<Polyline> lines = snap_round_segments(ends, exact::kSnapStep, monotone, given);
  std::vector<Curve> noded;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (lines[i].size() <= 2) continue;
    add_pieces(noded, lines[i], edges[i]->curve().data());
    arr.remove_edge(edges[i]);
  }
  for (std::size_t i = 0; i < curves.size(); ++i) {
    // The tags are relative to the curve's left-to-right direction, which is its snapped
    // line's unless snapping swapped its ends' order.
    const Polyline& line = lines[edges.size() + i];
    if (line.size() < 2) continue;
    const bool given_left_to_right = CGAL::compare_xy(curves[i].source(), curves[i].target()) == CGAL::SMALLER;
    const bool line_left_to_right = CGAL::compare_xy(to_exact(line.front()), to_exact(line.back())) == CGAL::SMALLER;
    Tags tags = curves[i].data();
    if (given_left_to_right != line_left_to_right)
      for (CurveTag& t : tags) t.sign = -t.sign;
    add_pieces(noded, line, tags);
  }
  CGAL::insert(arr, noded.begin(), noded.end());
}
#else
namespace {

// CGAL's sweep visitor `Base` that ends the sweep after the event under way once the build is
// cancelled. Throwing out of a sweep would leak its subcurves (it frees them only when it
// completes), so the sweep is stopped (CGAL's stop_sweep), completes over what it has, and
// insert_curves throws after it.
template <template <typename, typename> class Base, typename Helper>
class StoppableSweep : public Base<Helper, StoppableSweep<Base, Helper>> {
 public:
  StoppableSweep(CGAL::Arrangement_on_surface_2<Traits, Arrangement::Topology_traits>* arr,
                 const exacity::CancelCheck& cancel)
      : Base<Helper, StoppableSweep>(arr), cancel_(cancel) {}

  template <typename Event, typename Place>
  bool after_handle_event(Event* event, Place place, bool on_above) {
    const bool free = Base<Helper, StoppableSweep>::after_handle_event(event, place, on_above);
    if (cancel_.requested()) this->stop_sweep();
    return free;
  }

 private:
  const exacity::CancelCheck& cancel_;
};

}  // namespace

// Inserts the curves in one sweep: CGAL::insert's aggregated insertion of x-monotone curves
// (Arrangement_on_surface_2_global.h, insert_empty and insert_non_empty), with a sweep that
// stops once the build is cancelled, so a large map stops within a second.
void insert_curves(Arrangement& arr, std::vector<Curve>& curves, std::size_t) {
  using Surface = CGAL::Arrangement_on_surface_2<Traits, Arrangement::Topology_traits>;
  using Allocator = Surface::Allocator;
  Surface& surface = arr;
  const exacity::CancelCheck cancel;
  CGAL::Arr_accessor<Surface> access(surface);
  access.notify_before_global_change();
  if (arr.is_empty()) {
    using Event = CGAL::Arr_construction_event<Traits, Surface, Allocator>;
    using Subcurve = CGAL::Arr_construction_subcurve<Traits, Event, Allocator>;
    using Helper = Arrangement::Topology_traits::Construction_helper<Event, Subcurve>;
    using Visitor = StoppableSweep<CGAL::Arr_construction_ss_visitor, Helper>;
    Visitor visitor(&surface, cancel);
    CGAL::Surface_sweep_2::Surface_sweep_2<Visitor> sweep(arr.geometry_traits(), &visitor);
    sweep.sweep(curves.begin(), curves.end());
  } else {
    using InsertionTraits = CGAL::Arr_insertion_traits_2<Traits, Surface>;
    using Event = CGAL::Arr_construction_event<InsertionTraits, Surface, Allocator>;
    using Subcurve = CGAL::Arr_construction_subcurve<InsertionTraits, Event, Allocator>;
    using Helper = Arrangement::Topology_traits::Insertion_helper<Event, Subcurve>;
    using Visitor = StoppableSweep<CGAL::Arr_insertion_ss_visitor, Helper>;
    const InsertionTraits traits(*arr.geometry_traits());
    std::list<InsertionTraits::X_monotone_curve_2> all_curves;
    std::list<InsertionTraits::Point_2> points;
    const std::vector<Traits::Point_2> no_points;
    CGAL::Surface_sweep_2::prepare_for_sweep(surface, curves.begin(), curves.end(), no_points.begin(), no_points.end(),
                                             std::back_inserter(all_curves), std::back_inserter(points), &traits);
    Visitor visitor(&surface, cancel);
    CGAL::Surface_sweep_2::Surface_sweep_2<Visitor> sweep(&traits, &visitor);
    sweep.sweep(all_curves.begin(), all_curves.end(), points.begin(), points.end());
  }
  access.notify_after_global_change();
  cancel.check();
}
#endif

namespace {

void add_winding(Windings& w, int counter, int delta) {
  auto it = std::lower_bound(w.begin(), w.end(), std::make_pair(counter, INT32_MIN));
  if (it != w.end() && it->first == counter) {
    it->second += delta;
    if (it->second == 0) w.erase(it);
  } else {
    w.insert(it, {counter, delta});
  }
}

}  // namespace

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
  const exacity::CancelCheck cancel;
  while (!queue.empty()) {
    cancel.check();
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

}  // namespace arrangement

int winding_of(const Windings& w, int counter) {
  auto it = std::lower_bound(w.begin(), w.end(), std::make_pair(counter, INT32_MIN));
  return it != w.end() && it->first == counter ? it->second : 0;
}

PlanarMap::PlanarMap() : impl_(std::make_unique<Impl>()) {}
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
  const std::size_t given_from = impl_->pending.size();  // merge_plain_edges appends the edges given as doubles
  impl_->merge_plain_edges();
  insert_curves(impl_->arr, impl_->pending, given_from);
  impl_->pending.clear();
}

void PlanarMap::label_faces(const std::function<int(const Windings&)>& label_of) {
  label_all_faces(impl_->arr, label_of);
}

void PlanarMap::relabel_faces(int from_counter, const std::function<int(const Windings&, int)>& label_of) {
  label_all_faces(impl_->arr, from_counter, label_of);
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
