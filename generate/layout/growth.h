// Recursive road growth (docs/design.md, Algorithms) in exact vector form: from a seed point in each region,
// roads grow step by step until they meet a road or the region's edge; they split the
// region, and each part above its zone's block area is grown again, one level deeper.
#pragma once

#include <functional>
#include <memory>
#include <optional>

#include "generate/layout/road_layout.h"

namespace exacity {

// The type of the zone whose face holds a point (not on an edge), if roads grow in it.
using ZoneAt = std::function<std::optional<ZoneType>(geom::Vec2)>;

// A growth region may span zones of several types: each cell grows as the zone at its seed.
std::unique_ptr<RoadLayout> make_growth_layout(const CitySettings& sketch, const SketchLines& sketch_lines, ZoneAt zone_at);

}  // namespace exacity
