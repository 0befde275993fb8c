// OUT/city.city.json: CityJSON 2.0. Buildings as LOD1 and LOD2 solids (LOD2 with
// GroundSurface, WallSurface and RoofSurface semantics), roads, land use and water as LOD1
// surfaces, a TINRelief under the city; vertices quantised to millimetres by `transform`.
// And with --cityjson-seq the same objects as CityJSONSeq (OUT/city.city.jsonl), the form cjio and 3D BAG
// stream large cities in: a first line with what the objects share (transform, templates,
// appearance, reference system), then one CityJSONFeature a line, each with its own vertices.
#pragma once

#include <filesystem>

#include "generate/export/meshed_city.h"

namespace exacity {

// The city's terrain and bridges as its ground layers have them. Placed models are
// instances of templates, one per library model; on terrain, ground surfaces are draped
// over it. Models' textures are written once each into `textures/` beside the file, which
// the appearance names. With `sequence`, the same objects as CityJSONSeq there too.
void write_cityjson(const MeshedCity& city, const std::filesystem::path& document,
                    const std::filesystem::path& sequence = {});

}  // namespace exacity
