// The planar map as the vector layers of docs/design.md's Outputs table.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "generate/parcels/blocks.h"
#include "generate/placement/buildings.h"
#include "generate/export/geojson.h"
#include "generate/parcels/lots.h"
#include "generate/city/sketch.h"
#include "generate/city/city_map.h"

namespace exacity {

struct CityLayers {
  Layer zones{"zones", false, {}}, water{"water", false, {}};
  Layer roads{"roads", true, {}}, road_areas{"road_areas", false, {}};
  Layer blocks{"blocks", false, {}}, lots{"lots", false, {}}, buildings{"buildings", false, {}};

  // The box around zones, water and road areas (what covers the ground); holds nothing
  // for an empty city.
  geom::Box ground_bounds() const {
    geom::Box box = geom::Box::none();
    for (const Layer* l : {&zones, &water, &road_areas})
      for (const auto& f : l->features)
        for (geom::Vec2 p : f.polygon.outer) box.add(p);
    return box;
  }
};

// The layers as written into an output folder's `vector/` (what validate and stats read);
// anything malformed is appended to `problems`, one line each.
CityLayers read_layers(const std::filesystem::path& vector_dir, std::vector<std::string>& problems);

CityLayers extract_layers(const CityMap& city_map, const std::vector<Block>& blocks, const std::vector<Lot>& lots,
                          const std::vector<Building>& buildings, const Sketch& sketch,
                          const ModelLibrary* library = nullptr);

}  // namespace exacity
