// Regenerating a city after an edit of its sketch (docs/design.md, Regions and
// regenerating): each region's road plan, each block's lot plan and each lot's structures
// are kept by the whole of their input, and a build reuses those whose input the edit left
// as it was. The result is the city a full build of the edited sketch makes, byte for byte.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city.h"
#include "generate/pipeline.h"
#include "generate/city/memo.h"
#include "generate/export/ground_layers.h"
#include "generate/mesh/building_mesh.h"
#include "generate/sketch/sketch.h"

namespace exacity {

struct ValidatedPolygons;  // generate/export/validate_window.h

// A tile of exacity serve's 3D view as written (serve/city_tiles.cpp): each level's file
// and its triangles.
struct TileFiles {
  std::vector<std::string> bytes;
  std::vector<std::size_t> triangles;
};

struct RegionCache {
  Memo<RoadPlan> road_plans;                // per region of the road stage
  Memo<std::vector<PlannedLot>> lot_plans;  // per block
  Memo<BlockLots> block_lots;               // per block and merge of its unbuilt lots: its lots, from its own map
  Memo<Structures> placements;              // per lot, before it stands on the terrain
  Memo<Mesh> meshes;                        // per building or placed model, for the exports and tiles
  Memo<GroundMesh> ground_pieces;           // per zone, water and road area polygon draped, likewise
  Memo<TileFiles> tiles;                    // per tile of the 3D view, after the build (not in hits())
  // The last written city's polygons if it passed validation: the next one is validated
  // where it changed (validate_window.h). Whatever the settings, since validation reads only files.
  std::shared_ptr<ValidatedPolygons> validated;
  // Starts a build of `sketch`: a change in what every item reads (the settings, the CRS,
  // the sketch roads, the files the sketch names) forgets everything.
  void next_build(const Sketch& sketch);
  // Items reused and computed in the last build, over the memos.
  int hits() const {
    return road_plans.hits() + lot_plans.hits() + block_lots.hits() + placements.hits() + meshes.hits() +
           ground_pieces.hits();
  }
  int misses() const {
    return road_plans.misses() + lot_plans.misses() + block_lots.misses() + placements.misses() + meshes.misses() +
           ground_pieces.misses();
  }

 private:
  int unknown_ = 0;  // builds of sketches whose settings_text is unknown, each its own context
};

// What the last build reused, per kind of item: {"region_plans": {"reused": n, "of": m},
// ...}, for report.json and the page.
nlohmann::ordered_json reuse_report(const RegionCache& cache);

// What every cached item reads besides its own input: the sketch's settings and CRS
// (Sketch::settings_text), its roads as joined, and the size and time of each file it
// names (heightmap, channel images, model library manifest).
std::string shared_input(const Sketch& sketch);

// structure_meshes of the city's buildings and models; with the city's cache, a structure's
// mesh is reused where the structure is as it was (the exports and the tiles of one build
// ask twice, and so make each mesh once). With the cache, `keys` (when given) receives
// each mesh's key by id: all that its mesh is made from.
std::vector<Mesh> city_meshes(const City& city, std::vector<std::string>* keys = nullptr);

// ground_layers of the city's ground; with the city's cache, a polygon's piece is reused
// where it is as it was (the exports and the tiles of one build ask twice).
std::vector<GroundLayer> city_ground_layers(const City& city);

// The city of `edited`, built with `previous`'s cache (a new one when it has none), which
// the new city then holds: the same city build_city(edited) makes.
City regenerate(const City& previous, const Sketch& edited, StageClock& clock);

}  // namespace exacity
