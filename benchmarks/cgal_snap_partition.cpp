// The robustness benchmark's CGAL baseline (docs/benchmarks.md): the partition stage as a CGAL
// user would first write it, before reaching for exact constructions: the inexact kernel
// (Epick: exact predicates, constructions in doubles) with CGAL's snap rounding
// (CGAL/Snap_rounding_2.h, iterated, pixels of 2^-24 m) of every constructed segment, then
// one arrangement. CGAL's manual asks for an exact kernel under snap rounding; this is the
// shortcut it warns against, and what the benchmark measures. All the linework goes into one
// overlay: the zones' rings (the last drawn on top, each inside where its rings wind an odd
// number of times), water, road surfaces (each centre-line segment's rectangle of the road's
// width, with a 16-gon at every bend) and a 25 m fishnet. Faces are labelled water over road
// over zone; each built zone's parts are blocks, and their faces cut by the fishnet are lots.
// The drawn centre lines, snap-rounded on their own, are the roads. No growth, no buildings:
// blocks and lots only, in Exacity's layer format, as exacity-geos writes them.
//
//   exacity-cgal-snap generate SKETCH.geojson -o OUT [-q] [--threads N]
//
// Exit 2 for bad input or usage, 3 when CGAL fails (a precondition, an exception).
#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Snap_rounding_2.h>
#include <CGAL/Snap_rounding_traits_2.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <list>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

#include "benchmarks/partition_program.h"

namespace {

using json = nlohmann::ordered_json;
using exacity::bench::Layers;
using exacity::bench::UsageError;

// The pixel: the snapped float build's grid and exacity-geos's fixed precision (geom/exact.h).
constexpr double kPixel = 1.0 / (1 << 24);
constexpr double kLotCell = 25;  // m, the fishnet that cuts blocks into lots
constexpr int kFishnet = -1;     // a tag's counter on a fishnet line: it bounds no area

// Which ring (a zone's, or a road piece's) an edge lies on, and whether it runs the ring's
// way when taken left to right (+1) or against it (-1).
struct Tag {
  int counter;
  int sign;
};
using Tags = std::vector<Tag>;
struct Concatenate {
  Tags operator()(const Tags& a, const Tags& b) const {
    Tags r = a;
    r.insert(r.end(), b.begin(), b.end());
    return r;
  }
};
// A face's label (water, road, outside, or the index of the zone it belongs to) and its
// number among the lots' faces.
struct FaceInfo {
  int label = 0;
  int serial = -1;
};
constexpr int kOutside = -1, kWater = -2, kRoad = -3;

// The partition on one kernel: the inexact one, as the baseline runs, or the exact one, which
// shows the same code sound where constructions are exact.
template <typename Kernel>
struct Partition {
  using Point = typename Kernel::Point_2;
  using Segment = typename Kernel::Segment_2;
  using Traits = CGAL::Arr_curve_data_traits_2<CGAL::Arr_segment_traits_2<Kernel>, Tags, Concatenate>;
  using Arrangement = CGAL::Arrangement_2<Traits, CGAL::Arr_face_extended_dcel<Traits, FaceInfo>>;
  using Face_handle = typename Arrangement::Face_handle;
  using Halfedge_handle = typename Arrangement::Halfedge_handle;
  using Vertex_handle = typename Arrangement::Vertex_handle;
  using Ccb = typename Arrangement::Ccb_halfedge_circulator;

  // A line's positions, repeats dropped.
  static std::vector<Point> line_points(const json& line) {
    std::vector<Point> out;
    for (const json& p : line) {
      const Point q(p.at(0).get<double>(), p.at(1).get<double>());
      if (out.empty() || out.back() != q) out.push_back(q);
    }
    return out;
  }

  // A polygon's ring, its closing point dropped.
  static std::vector<Point> ring_points(const json& ring) {
    std::vector<Point> out = line_points(ring);
    if (out.size() > 1 && out.front() == out.back()) out.pop_back();
    return out;
  }

  static std::vector<std::vector<Point>> polygon_rings(const json& geometry) {
    const std::string type = geometry.at("type").get<std::string>();
    std::vector<std::vector<Point>> rings;
    auto add_polygon = [&](const json& polygon) {
      for (const json& r : polygon) rings.push_back(ring_points(r));
    };
    if (type == "Polygon")
      add_polygon(geometry.at("coordinates"));
    else if (type == "MultiPolygon")
      for (const json& p : geometry.at("coordinates")) add_polygon(p);
    else
      throw UsageError("a zone's geometry is a " + type + ", not a Polygon or MultiPolygon");
    return rings;
  }

  // The segments to snap-round, each with the tag it will carry.
  struct Linework {
    std::vector<Segment> segments;
    std::vector<int> counters;

    void add_ring(const std::vector<Point>& ring, int counter) {
      for (std::size_t i = 0; i < ring.size(); ++i) add(ring[i], ring[(i + 1) % ring.size()], counter);
    }
    void add(const Point& a, const Point& b, int counter) {
      if (a == b) return;
      segments.emplace_back(a, b);
      counters.push_back(counter);
    }
  };

  // The surface of a road of half width h along `line`: a rectangle per segment and a 16-gon
  // at each bend, every corner computed in doubles (on either kernel, so both snap-round the
  // same segments).
  static void add_surface(Linework& work, const std::vector<Point>& line, double h, int& counter) {
    auto at = [&](std::size_t i, double dx, double dy) {
      return Point(CGAL::to_double(line[i].x()) + dx, CGAL::to_double(line[i].y()) + dy);
    };
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const double dx = CGAL::to_double(line[i + 1].x() - line[i].x()),
                   dy = CGAL::to_double(line[i + 1].y() - line[i].y());
      const double length = std::hypot(dx, dy), nx = -dy / length * h, ny = dx / length * h;
      work.add_ring({at(i, -nx, -ny), at(i + 1, -nx, -ny), at(i + 1, nx, ny), at(i, nx, ny)}, counter++);
    }
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      std::vector<Point> disc;
      for (int k = 0; k < 16; ++k) disc.push_back(at(i, h * std::cos(k * M_PI / 8), h * std::sin(k * M_PI / 8)));
      work.add_ring(disc, counter++);
    }
  }

  // Snap-rounds the linework with CGAL and inserts the pieces into the arrangement, each with
  // its segment's tag (a piece that snaps to one point is dropped).
  static void insert_snap_rounded(Arrangement& arr, const Linework& work) {
    std::list<std::list<Point>> polylines;
    CGAL::snap_rounding_2<CGAL::Snap_rounding_traits_2<Kernel>>(work.segments.begin(), work.segments.end(), polylines,
                                                                kPixel, true, false);
    std::vector<typename Traits::Curve_2> curves;
    std::size_t i = 0;
    for (const std::list<Point>& polyline : polylines) {
      const int counter = work.counters.at(i++);
      if (polyline.size() < 2) continue;
      for (auto p = polyline.begin(), q = std::next(p); p != polyline.end() && q != polyline.end(); ++p, ++q) {
        if (*p == *q) continue;
        const int sign = CGAL::compare_xy(*p, *q) == CGAL::SMALLER ? 1 : -1;
        curves.emplace_back(Segment(*p, *q), Tags{{counter, sign}});
      }
    }
    CGAL::insert(arr, curves.begin(), curves.end());
  }

  template <typename F>
  static void for_each_boundary_halfedge(Face_handle f, F visit) {
    auto ccb = [&](Ccb first) {
      auto h = first;
      do visit(h);
      while (++h != first);
    };
    if (!f->is_unbounded()) ccb(f->outer_ccb());
    for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole) ccb(*hole);
  }

  // Every face's windings of every counter, walking out from the unbounded face; then its label
  // by `label_of`.
  template <typename LabelOf>
  static void label_faces(Arrangement& arr, LabelOf label_of) {
    int faces = 0;
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) f->data().serial = faces++;
    std::vector<std::map<int, int>> windings(faces);
    std::vector<char> reached(faces, 0);
    std::deque<Face_handle> queue{arr.unbounded_face()};
    reached[arr.unbounded_face()->data().serial] = 1;
    while (!queue.empty()) {
      const Face_handle f = queue.front();
      queue.pop_front();
      const std::map<int, int>& here = windings[f->data().serial];
      f->data().label = label_of(here);
      for_each_boundary_halfedge(f, [&](Halfedge_handle h) {
        const Face_handle g = h->twin()->face();
        if (reached[g->data().serial]) return;
        reached[g->data().serial] = 1;
        // Crossing h from its left to its right leaves every ring edge running h's way.
        std::map<int, int> there = here;
        const int along = h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? 1 : -1;
        for (const Tag& t : h->curve().data())
          if (t.counter != kFishnet) there[t.counter] -= t.sign * along;
        windings[g->data().serial] = std::move(there);
        queue.push_back(g);
      });
    }
  }

  static bool fishnet_edge(Halfedge_handle h) {
    const Tags& tags = h->curve().data();
    return std::any_of(tags.begin(), tags.end(), [](const Tag& t) { return t.counter == kFishnet; });
  }

  // Removes the edges with one label on both sides that `removed` picks: their faces merge.
  template <typename Pick>
  static void merge_faces(Arrangement& arr, Pick removed) {
    std::vector<Halfedge_handle> edges;
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
      if (e->face()->data().label == e->twin()->face()->data().label && removed(Halfedge_handle(e))) edges.push_back(e);
    for (Halfedge_handle e : edges) arr.remove_edge(e);
  }

  static json positions(const std::vector<Point>& ring) {
    json out = json::array();
    for (const Point& p : ring) out.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y())});
    out.push_back({CGAL::to_double(ring.front().x()), CGAL::to_double(ring.front().y())});
    return out;
  }

  // Whether the simple ring runs counter-clockwise: the turn at its lowest-leftmost vertex.
  static bool counter_clockwise(const std::vector<Point>& ring) {
    const std::size_t n = ring.size(), i = std::min_element(ring.begin(), ring.end()) - ring.begin();
    return CGAL::orientation(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]) == CGAL::LEFT_TURN;
  }

  // The face as OGC polygons: each boundary cut into simple loops where it passes a vertex
  // twice; loops running counter-clockwise (the face on their left) are shells, the others
  // holes, each in the shell around one of its edges' midpoints.
  static std::vector<json> face_polygons(Face_handle f) {
    std::vector<std::vector<Point>> loops;
    auto cut = [&](Ccb first) {
      std::vector<Vertex_handle> path;
      auto h = first;
      do {
        const Vertex_handle v = h->source();
        const auto again = std::find(path.begin(), path.end(), v);
        if (again != path.end()) {
          std::vector<Point> loop;
          for (auto k = again; k != path.end(); ++k) loop.push_back((*k)->point());
          loops.push_back(std::move(loop));
          path.erase(again, path.end());
        }
        path.push_back(v);
      } while (++h != first);
      std::vector<Point> loop;
      for (const auto& v : path) loop.push_back(v->point());
      loops.push_back(std::move(loop));
    };
    if (!f->is_unbounded()) cut(f->outer_ccb());
    for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole) cut(*hole);
    std::vector<std::vector<Point>> shells, holes;
    for (std::vector<Point>& loop : loops) {
      if (loop.size() < 3) continue;  // an antenna's way out and back
      (counter_clockwise(loop) ? shells : holes).push_back(std::move(loop));
    }
    std::vector<json> polygons;
    for (const auto& shell : shells) polygons.push_back(json::array({positions(shell)}));
    for (const auto& hole : holes) {
      std::size_t in = 0;
      const Point mid = CGAL::midpoint(hole[0], hole[1]);
      for (std::size_t s = 0; s < shells.size(); ++s)
        if (CGAL::bounded_side_2(shells[s].begin(), shells[s].end(), mid, Kernel()) == CGAL::ON_BOUNDED_SIDE) in = s;
      if (!shells.empty()) polygons[in].push_back(positions(hole));
    }
    std::vector<json> out;
    for (json& rings : polygons) out.push_back({{"type", "Polygon"}, {"coordinates", std::move(rings)}});
    return out;
  }

  static Layers run(const json& sketch) {
    struct Zone {
      std::string type;
      bool built;
    };
    std::vector<Zone> zones;
    Linework areas, centre_lines;
    std::vector<std::pair<std::vector<Point>, double>> roads;  // centre line, half width
    CGAL::Bbox_2 extent;
    bool any_zone = false;
    for (const json& f : sketch.at("features")) {
      const json& props = f.value("properties", json::object());
      if (props.contains("zone")) {
        const std::string type = props["zone"].get<std::string>();
        const int counter = static_cast<int>(zones.size());
        zones.push_back({type, type != "water" && type != "park"});
        for (const std::vector<Point>& ring : polygon_rings(f.at("geometry"))) {
          areas.add_ring(ring, counter);
          for (const Point& p : ring) extent += p.bbox(), any_zone = true;
        }
      } else if (props.contains("road")) {
        const json& g = f.at("geometry");
        if (g.at("type") != "LineString") throw UsageError("a road's geometry is not a LineString");
        const std::vector<Point> line = line_points(g.at("coordinates"));
        const double width = props.contains("width") ? props["width"].get<double>()
                                                     : exacity::bench::default_width(props["road"].get<std::string>());
        roads.push_back({line, width / 2});
        for (std::size_t i = 0; i + 1 < line.size(); ++i) centre_lines.add(line[i], line[i + 1], 0);
      }
    }
    // Road pieces count after the zones; the fishnet spans the zones' extent.
    int counter = static_cast<int>(zones.size());
    const int first_road = counter;
    for (const auto& [line, h] : roads) add_surface(areas, line, h, counter);
    if (any_zone) {
      const double x0 = std::floor(extent.xmin() / kLotCell) * kLotCell,
                   y0 = std::floor(extent.ymin() / kLotCell) * kLotCell;
      for (double x = x0; x <= extent.xmax(); x += kLotCell)
        areas.add({x, extent.ymin()}, {x, extent.ymax()}, kFishnet);
      for (double y = y0; y <= extent.ymax(); y += kLotCell)
        areas.add({extent.xmin(), y}, {extent.xmax(), y}, kFishnet);
    }

    Arrangement arr;
    insert_snap_rounded(arr, areas);
    label_faces(arr, [&](const std::map<int, int>& w) {
      int zone = kOutside;
      bool road = false;
      for (const auto& [c, n] : w) {
        if (c >= first_road)
          road |= n != 0;
        else if (n % 2 != 0)
          zone = c;  // the last drawn wins, a water zone as any other
      }
      // Water over road over zone; a road off every zone is nothing.
      if (zone != kOutside && zones[zone].type == "water") return kWater;
      if (zone == kOutside) return kOutside;
      return road ? kRoad : zone;
    });
    Layers layers;
    // Lots: the built zones' faces, merged across every edge but the fishnet's.
    merge_faces(arr, [](Halfedge_handle h) { return !fishnet_edge(h); });
    std::vector<std::tuple<json, int, std::string>> lots;  // (polygon, face serial, zone)
    int serials = 0;
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
      f->data().serial = serials++;
      if (f->data().label >= 0 && zones[f->data().label].built)
        for (json& p : face_polygons(f)) lots.push_back({std::move(p), f->data().serial, zones[f->data().label].type});
    }
    // The fishnet's faces of one block join it: each lot's block is its face's root.
    std::vector<int> parent(serials);
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
      if (e->face()->data().label == e->twin()->face()->data().label)
        parent[root(e->face()->data().serial)] = root(e->twin()->face()->data().serial);
    merge_faces(arr, [](Halfedge_handle) { return true; });
    std::map<int, std::vector<std::pair<int, std::vector<Point>>>> blocks_of_root;  // (id, shell)
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
      const int label = f->data().label;
      if (label == kOutside) continue;
      for (json& p : face_polygons(f)) {
        if (label == kWater)
          layers.add("water", std::move(p), json::object());
        else if (label == kRoad)
          layers.add("road_areas", std::move(p), {{"bridge", false}});
        else {
          const std::string& type = zones[label].type;
          layers.add("zones", p, {{"zone", type}});
          if (!zones[label].built) continue;
          std::vector<Point> shell;
          for (const json& q : p["coordinates"][0]) shell.emplace_back(q[0].get<double>(), q[1].get<double>());
          shell.pop_back();
          blocks_of_root[root(f->data().serial)].push_back(
              {layers.add("blocks", std::move(p), {{"zone", type}}), shell});
        }
      }
    }
    // A face that passes a vertex twice makes several blocks: a lot is in the one around its
    // first corner.
    for (auto& [polygon, serial, type] : lots) {
      int block = -1;
      const json& corner = polygon["coordinates"][0][0];
      const Point p(corner[0].get<double>(), corner[1].get<double>());
      for (const auto& [id, shell] : blocks_of_root[root(serial)]) {
        if (block < 0) block = id;
        if (CGAL::bounded_side_2(shell.begin(), shell.end(), p, Kernel()) != CGAL::ON_UNBOUNDED_SIDE) {
          block = id;
          break;
        }
      }
      layers.add("lots", std::move(polygon), {{"zone", type}, {"block", block}});
    }

    // The drawn centre lines, snap-rounded and noded on their own: each edge is a road.
    Arrangement network;
    insert_snap_rounded(network, centre_lines);
    for (auto e = network.edges_begin(); e != network.edges_end(); ++e)
      layers.add("roads",
                 {{"type", "LineString"},
                  {"coordinates",
                   {{CGAL::to_double(e->source()->point().x()), CGAL::to_double(e->source()->point().y())},
                    {CGAL::to_double(e->target()->point().x()), CGAL::to_double(e->target()->point().y())}}}},
                 {{"level", nullptr}, {"region", nullptr}, {"bridge", false}});
    return layers;
  }
};

}  // namespace

int main(int argc, char** argv) {
  bool exact = false;
  return exacity::bench::partition_main(
      argc, argv, "exacity-cgal-snap", "exacity-cgal-snap generate SKETCH.geojson -o OUT [--kernel inexact|exact]",
      [&](const std::string& name, const std::string& value) {
        if (name != "--kernel") return false;
        if (value != "inexact" && value != "exact") throw UsageError("--kernel: inexact or exact, not " + value);
        exact = value == "exact";
        return true;
      },
      [&](const json& sketch) {
        return exact ? Partition<CGAL::Exact_predicates_exact_constructions_kernel>::run(sketch)
                     : Partition<CGAL::Exact_predicates_inexact_constructions_kernel>::run(sketch);
      });
}
