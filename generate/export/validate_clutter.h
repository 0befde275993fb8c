// `exacity validate`'s checks of vector/clutter.geojson (street clutter), on the
// coordinates as written and exactly (docs/design.md, Exactness rule 7).
#pragma once

#include <string>
#include <vector>

#include "generate/export/validate.h"
#include "generate/export/vector_layers.h"

namespace exacity {

// Each piece of clutter a Point with a unique id, a clutter kind and a heading, naming a
// centre line of roads.geojson; standing strictly inside a sidewalk that is no bridge's or a
// lot, and in (or on the edge of) no carriageway, junction, water or building. Appends to
// `v` the problems of reading the layer (read_geojson's of vector/clutter.geojson), then
// those of its features, in their order.
void validate_clutter(const Layer& clutter, const std::vector<std::string>& read_problems, const CityLayers& layers,
                      Validation& v);

}  // namespace exacity
