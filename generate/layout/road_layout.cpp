#include "generate/layout/road_layout.h"

namespace exacity {

std::unique_ptr<RoadLayout> make_road_layout(const ZoneParams& params, ZoneType type) {
  if (params.layout == "grammar") return make_grammar_layout(params, type);
  if (params.layout == "voronoi") return make_voronoi_layout(params);
  if (params.layout == "streets") return make_streets_layout();
  return nullptr;
}

}  // namespace exacity
