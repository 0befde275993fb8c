// Street clutter (docs/design.md, Placement): the library's lamps, signs, traffic lights, benches, hydrants and
// trees dress the streets by the rules each entry sets (spacing along the street, offset in from
// the kerb, both sides or alternate ones), after the buildings stand (docs/design.md,
// Placement). Lamps, benches and hydrants line every street, trees residential ones; traffic
// lights stand at the corners of junctions of major roads, stop signs on local roads'
// approaches to major ones. Which entry of a kind stands at a spot is drawn by its weight
// times its channel affinity there.
//
// A piece of clutter stands on a sidewalk or in a lot (the setback strip between the street
// and the buildings), decided exactly: its spot strictly inside a sidewalk face of the map
// (PlanarMap::label_at, through StandingMap once the map is freed) or a lot's exact cell, its base (the model's outline at ground level)
// on sidewalk faces or strictly inside that lot, meeting no footprint and no other clutter.
// Spots that find no such place are counted by why (report.json's clutter.not_placed).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "generate/city/channels.h"
#include "generate/city/city_map.h"
#include "geom/face_locator.h"
#include "generate/city/ground.h"
#include "generate/city/features.h"
#include "generate/city/zone_settings.h"
#include "generate/city/terrain.h"
#include "generate/parcels/lots.h"
#include "generate/placement/buildings.h"
#include "generate/placement/model_library.h"

namespace exacity {

// One piece of clutter; its instance's id is its index in the city's clutter, its
// stable_id its id in the outputs.
struct Clutter {
  ModelInstance instance;  // kind, model, placement; polygon: its base on the grid; lot -1 on a sidewalk
  geom::Vec2 spot;         // where it stands: its base's centre, on the grid (the layer's point)
  int road = -1;           // the centre line it dresses (an index into Ground::roads)
  double heading = 0;      // degrees counter-clockwise from east: where its front faces
};

// Why spots found no place, for report.json.
struct ClutterTally {
  std::map<std::string, int> placed;                          // by kind
  std::map<std::pair<std::string, std::string>, int> missed;  // (kind, why) -> spots
};

struct StreetClutter {
  std::vector<Clutter> items;
  ClutterTally tally;
};

// What the clutter asks of the final map and the lots, taken from them so that they can be
// freed before it (docs/design.md, The pipeline): the map's faces, located as
// PlanarMap::label_at locates them, and each lot's exact cell (shared with the lot).
struct StandingMap {
  geom::FaceLocator faces;
  std::vector<FaceLabel> labels;  // the faces' labels (CityMap::labels)
  std::vector<geom::Cell> lot_cells;
};

// From the final map, with its labels as they are, and its lots.
StandingMap standing_map(const CityMap& map, const std::vector<Lot>& lots);

// What the clutter stands among: the final map's faces and lots, its ground, what stands on them.
struct ClutterGround {
  const StandingMap& map;
  const Ground& ground;
  const std::vector<Building>& buildings;
  const std::vector<ModelInstance>& models;
};

// The parks' trees one run plants: their area over the square of 1.5 tree spacings (each a
// model instance in every export, about 4 kB in memory), and the squares of their boxes,
// each walked to find its spot. Past either, place_clutter throws UserError before placing any.
inline constexpr double kMaxParkTrees = 100000, kMaxParkSquares = 1e8;

// Every street's clutter, road by road in parallel, gathered in road order; none without a
// library or clutter entries.
StreetClutter place_clutter(const ClutterGround& ground, const ModelLibrary* library, const Channels& channels,
                            const CitySettings& city, const std::vector<ZoneFeature>& zones, const Terrain* terrain);

}  // namespace exacity
