// The street-graph layout: the sketch's roads are the whole network, so a region gets none.
#include "generate/layout/road_layout.h"

namespace exacity {

class StreetsLayout : public RoadLayout {
 public:
  RoadPlan plan(const Region&) const override { return {}; }
};

std::unique_ptr<RoadLayout> make_streets_layout() { return std::make_unique<StreetsLayout>(); }

}  // namespace exacity
