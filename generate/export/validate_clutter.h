// `exacity validate`'s checks of vector/clutter.geojson (street clutter), on the
// coordinates as written and exactly (docs/design.md, Exactness rule 7).
#pragma once

#include <filesystem>

#include "generate/export/validate.h"
#include "generate/export/vector_layers.h"

namespace exacity {

struct ReadLines;  // generate/export/read_lines.h

// Each piece of clutter a Point with a unique id, a clutter kind and a heading, naming a
// centre line of roads.geojson; standing strictly inside a sidewalk that is no bridge's or a
// lot, and in (or on the edge of) no carriageway, junction, water or building. Appends
// problems to `v`. With `known`, the file is read with read_geojson's ReadLines.
void validate_clutter(const std::filesystem::path& out_dir, const CityLayers& layers, Validation& v,
                      ReadLines* known = nullptr);

}  // namespace exacity
