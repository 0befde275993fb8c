#include "generate/layout/road_layout.h"

namespace exacity {

std::vector<std::pair<geom::Vec2, geom::Vec2>> edges_to_reach(const geom::Cell& cell, bool top) {
  if (!top) return cell.edges_of_kind(GrowthEdge::kGrownRoad);
  std::vector<std::pair<geom::Vec2, geom::Vec2>> edges;
  for (const geom::KindedRing& r : cell.kinded_rings())
    for (std::size_t i = 0; i < r.points.size(); ++i)
      if (GrowthEdge::sketch_road_of(r.kinds[i]) >= 0) edges.push_back({r.points[i], r.points[(i + 1) % r.points.size()]});
  return edges;
}

std::unique_ptr<RoadLayout> make_road_layout(const Sketch& sketch, ZoneType type, const SketchLines& sketch_roads) {
  const RoadSettings& settings = sketch.zone_settings.at(type).roads;
  if (settings.layout == "grammar") return make_grammar_layout(sketch, type, sketch_roads);
  if (settings.layout == "voronoi") return make_voronoi_layout(settings, sketch_roads);
  if (settings.layout == "streets") return make_streets_layout();
  return nullptr;
}

}  // namespace exacity
