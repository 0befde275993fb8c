// The city in memory, every stage up to the vector layers: what the exports and the
// renderer read (docs/design.md, The city model).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city/channels.h"
#include "generate/city/features.h"
#include "generate/city/ground.h"
#include "generate/city/terrain.h"
#include "generate/city/zone_settings.h"
#include "generate/export/vector_layers.h"
#include "generate/layout/road_network.h"
#include "generate/parcels/blocks.h"
#include "generate/parcels/lots.h"
#include "generate/placement/buildings.h"
#include "generate/placement/clutter.h"
#include "generate/placement/mapped_buildings.h"
#include "generate/placement/model_library.h"

namespace exacity {

struct RegionCache;  // generate/regenerate.h

struct City {
  CitySettings settings;  // the sketch's: its file, seed, CRS, zone settings
  DrawnFeatures drawn;    // the sketch's zones and roads
  std::string camera;     // the sketch's still camera (exacity render's --camera syntax), or empty
  std::optional<Terrain> terrain;
  Channels channels;  // empty when the sketch has none
  std::optional<ModelLibrary> library;
  // The network, blocks and lots, and held_lots and held_m2, are empty once the ground is
  // made, unless build_city was asked to keep them (ExactWork, generate/pipeline.h).
  RoadNetwork network;
  std::vector<Block> blocks;
  std::vector<Lot> lots;
  UnbuiltLots unbuilt_lots;  // lots merged into a neighbour or left open: no placer could build on them
  std::map<ZoneType, LotLand> lot_land;  // where the blocks' land went, as the lots ended
  std::vector<Building> buildings;  // extruded, then the mapped ones kept
  MappedTally mapped;  // what became of the sketch's mapped buildings
  std::vector<char> held_lots;  // per lot: a mapped building stands on it (empty with the lots)
  std::vector<double> held_m2;  // per lot: the mapped footprints' area on it
  std::vector<ModelInstance> models;  // placed from the library
  StreetClutter clutter;  // along the streets; written as vector/clutter.geojson
  Ground ground;
  CityLayers layers;  // as written into vector/
  // What report.json says of the network, the blocks and the lots (exact_work_report,
  // generate/city_report.h), counted before build_city frees them.
  nlohmann::ordered_json exact_report;
  // What a build kept for the next one (generate/regenerate.h), when built with a cache.
  std::shared_ptr<RegionCache> regions;

  const Terrain* heightmap() const { return terrain ? &*terrain : nullptr; }  // null without one
  const ModelLibrary* model_library() const { return library ? &*library : nullptr; }
};

}  // namespace exacity
