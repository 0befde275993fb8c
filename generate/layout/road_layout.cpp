#include "generate/layout/road_layout.h"

#include "generate/layout/growth.h"

namespace exacity {

std::vector<std::pair<geom::Vec2, geom::Vec2>> edges_to_reach(const geom::Cell& cell, bool top) {
  if (!top) return cell.edges_of_kind(GrowthEdge::kGrownRoad);
  std::vector<std::pair<geom::Vec2, geom::Vec2>> edges;
  for (const geom::KindedRing& r : cell.kinded_rings())
    for (std::size_t i = 0; i < r.points.size(); ++i)
      if (GrowthEdge::sketch_road_of(r.kinds[i]) >= 0) edges.push_back({r.points[i], r.points[(i + 1) % r.points.size()]});
  return edges;
}


namespace {

// Growth's settings are every zone type's (RoadSettings::growth): a region spans the zone
// types laid out by growth, and each cell grows by the zone at its seed.
class GrowthChoice : public RoadLayoutChoice {
 public:
  GrowthChoice() : RoadLayoutChoice("growth") {}
  std::unique_ptr<RoadLayout> make(const LayoutSite& site) const override {
    return make_growth_layout(site.city, site.sketch_roads, site.zone_at);
  }
  bool spans_zone_types() const override { return true; }
};

}  // namespace

std::shared_ptr<const RoadLayoutChoice> read_growth_layout(const RoadLayoutReading&) {
  return std::make_shared<GrowthChoice>();
}

}  // namespace exacity
