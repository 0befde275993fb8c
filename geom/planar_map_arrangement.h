// The CGAL arrangement behind PlanarMap, shared by its translation units (docs/design.md,
// Algorithms: The exact city map): the arrangement's types, PlanarMap::Impl, and the helpers
// more than one of them uses. Only planar_map*.cpp include it; CGAL arrangement code stays
// in them.
#pragma once

#include <atomic>
#include <climits>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_observer.h>
#include <CGAL/Arr_non_caching_segment_traits_2.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>

#include "generate/cancel.h"
#include "geom/cell_impl.h"
#include "geom/kernel.h"
#include "geom/planar_map.h"
#include "geom/shared_ends.h"

namespace geom::arrangement {

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

#if defined(EXACITY_SNAPPED_KERNEL)
// The snapped build splits an edge at a grid point near it, not on it: each piece must be
// the segment between its ends, not a part of the first segment's line.
using SegmentTraits = CGAL::Arr_non_caching_segment_traits_2<Kernel>;
#elif defined(EXACITY_FLOAT_KERNEL)
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
#else
// CGAL's segment traits, with an intersection that constructs no point the segments do not
// have, between segments whose ends are doubles. CGAL's sweep asks for the intersection of
// every two curves that become neighbours; most share an end (every two edges at a ring's
// vertex) or one's end lies on the other (a lot's corner on its block's edge), and partial
// overlaps are common (a lot's frontage along its block's edge). CGAL's traits answer each
// through the crossing of the two supporting lines, a construction the sweep then compares
// with the ends: a tie the exact kernel settles only in exact rationals (most of validating
// the 10 km city's exact arithmetic). Exact orientations of the ends give the same answers:
// where an end of one lies on the other's line and the lines differ, that end is where they
// meet; where both ends do, the lines are one and CGAL's own overlap code follows, less the
// lines' intersection. Only a proper crossing is left to CGAL. The answers are CGAL's (the
// same points, multiplicities and overlaps), so every map is the same. Only validation's
// maps take this way (geom/shared_ends.h).
class SegmentTraits : public CGAL::Arr_segment_traits_2<Kernel> {
  using Base = CGAL::Arr_segment_traits_2<Kernel>;

 public:
  class Intersect_2 : public Base::Intersect_2 {
   public:
    explicit Intersect_2(const Base& traits) : Base::Intersect_2(traits) {}

    template <typename OutputIterator>
    OutputIterator operator()(const X_monotone_curve_2& a, const X_monotone_curve_2& b, OutputIterator oi) const {
      using Intersection_point = std::pair<Point_2, Multiplicity>;
      using Intersection_result = boost::variant<Intersection_point, X_monotone_curve_2>;
      // Only where validation asks (geom/shared_ends.h), between segments whose ends are
      // doubles: there the interval filter settles equality and every orientation but ties.
      if (!SharedEndsByOrientation::on() || !is_double(a.left()) || !is_double(a.right()) || !is_double(b.left()) ||
          !is_double(b.right()))
        return Base::Intersect_2::operator()(a, b, oi);
      const Kernel& kernel = this->m_traits;
      const auto equal = kernel.equal_2_object();
      const auto orientation = kernel.orientation_2_object();
      // A shared end (checked first: cheap, and the commonest case).
      const Point_2* end = equal(a.left(), b.left()) ? &a.left() : equal(a.right(), b.right()) ? &a.right() : nullptr;
      if (end) {
        const Point_2& other = end == &a.left() ? b.right() : b.left();
        if (orientation(a.left(), a.right(), other) == CGAL::COLLINEAR) return overlap(a, b, oi);
        *oi++ = Intersection_result(Intersection_point(*end, 1));
        return oi;
      }
      if (!this->do_bboxes_overlap(a, b) || !this->do_intersect(a.left(), a.right(), b.left(), b.right())) return oi;
      const CGAL::Orientation bl = orientation(a.left(), a.right(), b.left()),
                             br = orientation(a.left(), a.right(), b.right());
      if (bl == CGAL::COLLINEAR && br == CGAL::COLLINEAR) return overlap(a, b, oi);
      // They meet at one point; an end on the other's line is it.
      if (bl == CGAL::COLLINEAR) end = &b.left();
      else if (br == CGAL::COLLINEAR) end = &b.right();
      else if (orientation(b.left(), b.right(), a.left()) == CGAL::COLLINEAR) end = &a.left();
      else if (orientation(b.left(), b.right(), a.right()) == CGAL::COLLINEAR) end = &a.right();
      if (!end) return Base::Intersect_2::operator()(a, b, oi);  // a proper crossing: CGAL constructs it
      *oi++ = Intersection_result(Intersection_point(*end, 1));
      return oi;
    }

   private:
    // Whether the point is known as a pair of doubles (its interval approximation is exact).
    static bool is_double(const Point_2& p) {
      const auto& q = CGAL::approx(p);
      return q.x().is_point() && q.y().is_point();
    }

    // Two intersecting segments on one line: CGAL's own answer (Arr_segment_traits_2.h, the
    // end of Intersect_2) once it has found the lines equal.
    template <typename OutputIterator>
    OutputIterator overlap(const X_monotone_curve_2& cv1, const X_monotone_curve_2& cv2, OutputIterator oi) const {
      using Intersection_point = std::pair<Point_2, Multiplicity>;
      using Intersection_result = boost::variant<Intersection_point, X_monotone_curve_2>;
      const Kernel& kernel = this->m_traits;
      const auto compare_xy = kernel.compare_xy_2_object();
      const Point_2& p_l = compare_xy(cv1.left(), cv2.left()) == CGAL::SMALLER ? cv2.left() : cv1.left();
      const Point_2& p_r = compare_xy(cv1.right(), cv2.right()) == CGAL::SMALLER ? cv1.right() : cv2.right();
      if (compare_xy(p_l, p_r) == CGAL::EQUAL) {
        *oi++ = Intersection_result(Intersection_point(p_r, 0));
        return oi;
      }
      if (cv1.is_directed_right() == cv2.is_directed_right() && !cv1.is_directed_right())
        *oi++ = Intersection_result(X_monotone_curve_2(cv1.line(), p_r, p_l));
      else
        *oi++ = Intersection_result(X_monotone_curve_2(cv1.line(), p_l, p_r));
      return oi;
    }
  };

  Intersect_2 intersect_2_object() const { return Intersect_2(*this); }
};
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
void add_curve(std::vector<Curve>& curves, const Point& a, const Point& b, CurveTag tag);

// Queues the edges of a ring around `counter`.
void add_ring_curves(std::vector<Curve>& curves, const std::vector<Point>& ring, int counter);

// The halfedge of h's edge that runs left to right.
template <typename Handle>
Handle left_to_right(Handle h) {
  return h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? h : h->twin();
}

constexpr int kMapEdge = INT_MIN;  // tag counter of a map edge copied into a region's own arrangement
// Tag counter of a cell's edge in PlanarMap::of_cell's map; its aux is the edge's index in
// the cell (the outer ring's edges, then each hole's).
constexpr int kCellEdge = INT_MIN + 1;

// Inserts the curves into the arrangement in one sweep (the snapped build: noded first). The
// curves from `given_from` on are edges given as doubles (PlanarMap::add_ring, add_edge).
void insert_curves(Arrangement& arr, std::vector<Curve>& curves, std::size_t given_from = SIZE_MAX);

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
// walking out from the unbounded face.
void label_all_faces(Arrangement& arr, int from_counter, const std::function<int(const Windings&, int)>& label_of);
void label_all_faces(Arrangement& arr, const std::function<int(const Windings&)>& label_of);

// label_at's point location (planar_map_locate.cpp).
class EdgeGrid;

}  // namespace geom::arrangement

namespace geom {

struct PlanarMap::Impl {
  using Arrangement = arrangement::Arrangement;
  using Curve = arrangement::Curve;
  using EdgeGrid = arrangement::EdgeGrid;
  using Face = arrangement::Face;
  using Point = exact::Point;
  using Tags = arrangement::Tags;

  Impl();
  ~Impl();

  Arrangement arr;
  arrangement::LabelKeeper keeper{arr};
  // label_at's point location: built by the first query after the edges last changed
  // (threads that query at once wait for one to build it), then only read.
  mutable std::mutex grid_mutex;
  mutable std::unique_ptr<const EdgeGrid> grid;
  mutable std::atomic<const EdgeGrid*> ready_grid{nullptr};

  const EdgeGrid& edge_grid() const;
  // Each vertex traced so far (cells, dissolve) rounded to doubles, by vertex, until the
  // edges change; tracings of one map lock it, one at a time.
  mutable std::mutex rounded_mutex;
  mutable std::unordered_map<const void*, Vec2> rounded;
  // Called before the edges change (never while label_at, cells or dissolve runs).
  void edges_change();
  // In a map of one cell (PlanarMap::of_cell): the cell, its outside's label (else -1), and
  // the label across each of its edges, by index.
  Cell cell;
  int cell_outside = -1;
  std::vector<int> cell_across;
  std::vector<Curve> pending;
  std::vector<std::vector<Curve>> within;  // per region, for insert_within()
  std::map<int, std::vector<Point>> polylines;
  // Edges given as doubles, kept aside until the batch: ends in left-to-right order.
  struct PlainEdge {
    Vec2 a, b;
    CurveTag tag;
  };
  std::vector<PlainEdge> plain_pending;

  void add_edge(const Point& a, const Point& b, CurveTag tag) { arrangement::add_curve(pending, a, b, tag); }

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
      pending.emplace_back(exact::Segment(exact::to_exact(plain_pending[k].a), exact::to_exact(plain_pending[k].b)),
                           std::move(tags));
      k = next;
    }
    plain_pending.clear();
  }

  void add_exact_ring(const exact::ExactRing& ring, int counter) { arrangement::add_ring_curves(pending, ring, counter); }

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

}  // namespace geom
