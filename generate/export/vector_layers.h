// The planar map as the typed ground, and the city as the vector layers of docs/design.md's Outputs table.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "generate/parcels/blocks.h"
#include "generate/placement/buildings.h"
#include "generate/city/ground.h"
#include "generate/export/geojson.h"
#include "generate/parcels/lots.h"
#include "generate/city/features.h"
#include "generate/city/city_map.h"

namespace exacity {

struct CityLayers {
  Layer zones{"zones", false, {}}, water{"water", false, {}};
  Layer roads{"roads", true, {}}, road_areas{"road_areas", false, {}};
  Layer blocks{"blocks", false, {}}, lots{"lots", false, {}}, buildings{"buildings", false, {}};
};

// The layers as written into an output folder's `vector/` (what validate and stats read);
// anything malformed is appended to `problems`, one line each.
CityLayers read_layers(const std::filesystem::path& vector_dir, std::vector<std::string>& problems);

// Road areas under this (m2) are slivers: where two roads' strokes or a junction's outline
// nearly meet, rounding leaves a face or two of one road between the others'.
inline constexpr double kSliverRoadArea = 0.01;

// A road whose every face another road, or a junction, owns (a stub a few metres long
// inside a wider street's carriageway or a junction: the first road listed owns a
// crossing) takes the faces its own carriageway covers from them, unless that leaves their
// road less than kSliverRoadArea: the faces' labels change, nothing moves. Returns how many
// roads took faces.
int give_covered_roads_their_carriageway(CityMap& city_map);

// Gives each road area (a connected piece of one road's carriageway, sidewalk or junction)
// under kSliverRoadArea to the road area it shares the longest boundary with, in the map:
// the faces' labels change, nothing moves; one no road area touches along an edge stays. A road whose only area is a sliver takes in the road area beside
// it instead, when that is not its road's last; else the sliver stays. Returns how many
// areas changed hands.
int merge_sliver_road_areas(CityMap& city_map);

// The ground as the map leaves it: ids and properties as the layers write them.
Ground extract_ground(const CityMap& city_map, const std::vector<Block>& blocks, const std::vector<Lot>& lots,
                      const std::vector<ZoneFeature>& zones);

// A mapped building's attributes in every export: "mapped": true, its "osm_id" (null
// where it has none) and its "building" tag.
nlohmann::ordered_json mapped_attributes(const Building& b);

// A road's OpenStreetMap tags as roads.geojson and CityJSON carry them: under their keys,
// OSM's bridge as "osm_bridge" (the layer's own "bridge" says the piece crosses water).
nlohmann::ordered_json road_attributes(const RoadLine& road);

// The layers written into `vector/`.
CityLayers layers_of(const Ground& ground, const std::vector<Building>& buildings,
                     const std::vector<ModelInstance>& models, const ModelLibrary* library);

// extract_ground, then layers_of.
CityLayers extract_layers(const CityMap& city_map, const std::vector<Block>& blocks, const std::vector<Lot>& lots,
                          const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                          const std::vector<ZoneFeature>& zones, const ModelLibrary* library = nullptr);

}  // namespace exacity
