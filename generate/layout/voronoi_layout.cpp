// The Voronoi layout (docs/design.md, Algorithms): points spread over the region, their Voronoi diagram clipped to it;
// main roads on the cell edges, inner roads by the junction heuristic (generate/layout/voronoi.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "generate/city/random.h"
#include "generate/layout/road_layout.h"
#include "generate/layout/settle.h"
#include "generate/layout/voronoi.h"
#include "geom/grid.h"

namespace exacity {
namespace {

// The Voronoi layout (docs/design.md, Road layouts).
struct VoronoiSettings {
  double cell_size = 180;         // m: one point per square this size
  double junction_spacing = 60;   // m: junctions at about this step along the cells' roads
};

class VoronoiLayout : public RoadLayout {
 public:
  VoronoiLayout(const RoadSettings& roads, const VoronoiSettings& voronoi, const SketchLines& sketch)
      : roads_(roads), voronoi_(voronoi), sketch_(sketch) {}

  RoadPlan plan(const Region& region) const override {
    Random random(region.stream);
    const geom::Cell& cell = region.cell;
    const geom::Box b = cell.bounds();
    const double size = voronoi_.cell_size;
    // One point in each square of a grid of cell_size, jittered, where it falls inside.
    std::vector<geom::Vec2> sites;
    for (double y = b.min_y; y < b.max_y; y += size)
      for (double x = b.min_x; x < b.max_x; x += size) {
        const geom::Vec2 p = geom::snap(geom::Vec2{x + random.uniform(0.15, 0.85) * size, y + random.uniform(0.15, 0.85) * size});
        if (cell.contains(p)) sites.push_back(p);
      }
    LinePlan plan;
    // Roads meet at shared points; a corner two cells computed apart may differ by a grid step.
    plan.join = 0.01;
    if (sites.size() < 2) return {};
    geom::Box box{b.min_x - size, b.min_y - size, b.max_x + size, b.max_y + size};
    const std::vector<VoronoiCell> cells = voronoi_cells(sites, box, size);
    // Each edge between two sites once, junctions along it.
    std::map<std::pair<int, int>, CellRoad> edges;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const auto& ring = cells[i].ring;
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const int j = cells[i].across[k];
        if (j <= static_cast<int>(i)) continue;
        const geom::Vec2 p = geom::snap(ring[k]), q = geom::snap(ring[(k + 1) % ring.size()]);
        if (p == q) continue;
        CellRoad road{p};
        for (geom::Vec2 v : junctions_along(p, q, voronoi_.junction_spacing)) road.push_back(v);
        road.push_back(q);
        edges[{static_cast<int>(i), j}] = std::move(road);
      }
    }
    for (auto& [key, road] : edges) add(plan, road, roads_.road_widths.front(), RoadClass::Main, cell);
    // Inner roads, cell by cell, from the roads around it.
    for (std::size_t i = 0; i < cells.size(); ++i) {
      std::vector<CellRoad> around;
      for (int j : cells[i].across) {
        if (j < 0) continue;
        const int me = static_cast<int>(i);
        auto it = edges.find({std::min(me, j), std::max(me, j)});
        if (it == edges.end()) continue;
        CellRoad road = it->second;
        if (j < me) std::reverse(road.begin(), road.end());
        around.push_back(std::move(road));
      }
      for (auto [p, q] : inner_roads(around)) add(plan, {p, q}, road_width(roads_, 1), RoadClass::Local, cell);
    }
    return settle(std::move(plan), cell, sketch_);
  }

 private:
  // The pieces of `line` inside the region: a segment leaving it stops at its last grid point
  // inside (the roads stage runs it on to the edge exactly).
  static void add(LinePlan& plan, const geom::Polyline& line, double width, RoadClass c, const geom::Cell& cell) {
    geom::Polyline piece;
    auto flush = [&] {
      if (piece.size() >= 2) plan.roads.push_back({piece, width, c});
      piece.clear();
    };
    auto last_inside = [&](geom::Vec2 in, geom::Vec2 out) {
      geom::Vec2 best = in;
      double lo = 0, hi = 1;
      for (int k = 0; k < 40; ++k) {
        const double t = (lo + hi) / 2;
        const geom::Vec2 p = geom::snap(geom::Vec2{in.x + t * (out.x - in.x), in.y + t * (out.y - in.y)});
        if (cell.contains(p)) best = p, lo = t;
        else hi = t;
      }
      return best;
    };
    std::vector<char> inside;
    for (geom::Vec2 p : line) inside.push_back(cell.contains(p));
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const geom::Vec2 p = line[k], q = line[k + 1];
      if (inside[k]) {
        if (piece.empty()) piece.push_back(p);
        if (inside[k + 1]) {
          piece.push_back(q);
        } else {
          if (const geom::Vec2 e = last_inside(p, q); !(e == p)) piece.push_back(e);
          flush();
        }
      } else if (inside[k + 1]) {
        const geom::Vec2 s = last_inside(q, p);
        piece.push_back(s);
        if (!(s == q)) piece.push_back(q);
      }
    }
    flush();
  }

  RoadSettings roads_;
  VoronoiSettings voronoi_;
  const SketchLines& sketch_;
};

class VoronoiChoice : public RoadLayoutChoice {
 public:
  explicit VoronoiChoice(const VoronoiSettings& settings) : RoadLayoutChoice("voronoi"), settings_(settings) {}
  std::unique_ptr<RoadLayout> make(const LayoutSite& site) const override {
    return std::make_unique<VoronoiLayout>(site.roads(), settings_, site.sketch_roads);
  }
  // Its plots are split into lots unless the zone says otherwise.
  const char* default_lots() const override { return "split"; }

 private:
  VoronoiSettings settings_;
};

}  // namespace

// "cell_size" is checked against the road widths, so it is read after them.
std::shared_ptr<const RoadLayoutChoice> read_voronoi_layout(const RoadLayoutReading& reading) {
  const SettingsReader& s = reading.settings;
  VoronoiSettings v;
  s.number("cell_size", v.cell_size, 20, 1e5);
  const std::vector<double>& widths = reading.shared.road_widths;
  const double widest = *std::max_element(widths.begin(), widths.end());
  if (reading.chosen && v.cell_size < 4 * widest)
    s.fail("cell_size", nlohmann::json(v.cell_size).dump() + " m is under 4 road widths (" +
                            nlohmann::json(4 * widest).dump() +
                            " m): the cells would be all road; raise \"cell_size\" or narrow \"road_widths\"");
  s.number("junction_spacing", v.junction_spacing, 5, 1e5);
  return std::make_shared<VoronoiChoice>(v);
}

}  // namespace exacity
