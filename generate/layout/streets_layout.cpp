// The street-graph layout: the sketch's roads are the whole network, so a region gets none.
#include "generate/layout/road_layout.h"

namespace exacity {

class StreetsLayout : public RoadLayout {
 public:
  RoadPlan plan(const Region&) const override { return {}; }
};

// Lays no roads, so a generated road (a link) passing through paves nothing of the zone.
class StreetsChoice : public RoadLayoutChoice {
 public:
  StreetsChoice() : RoadLayoutChoice("streets") {}
  std::unique_ptr<RoadLayout> make(const LayoutSite&) const override { return std::make_unique<StreetsLayout>(); }
  bool generates_roads() const override { return false; }
};

std::shared_ptr<const RoadLayoutChoice> read_streets_layout(const RoadLayoutReading&) {
  return std::make_shared<StreetsChoice>();
}

}  // namespace exacity
