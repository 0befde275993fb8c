// Blocks: the faces left once road areas, water and parks are taken out, one per zone
// type where zones touch. Blocks too small or too thin to build on become green space,
// so the map still tiles the drawn zones.
#pragma once

#include <string>
#include <vector>

#include "generate/layout/road_layout.h"
#include "generate/city/features.h"
#include "generate/city/zone_settings.h"
#include "generate/city/city_map.h"

namespace exacity {

// The kind of a block cell's edge (its geom::Cell edge tag): the index of the road across
// it, or one of these.
struct BlockEdge {
  static constexpr int kNoRoad = -1;  // water, a park or another zone across
  static constexpr int kLotCut = -2;  // a cut between two of the block's split lots (parcels/split.cpp)
  static constexpr bool is_road(int kind) { return kind >= 0; }
};

struct Block {
  ZoneType zone = ZoneType::Residential;  // the drawn zone's type; Park for green space
  bool green = false;
  geom::Cell cell;         // exact; edge kinds are BlockEdge's
  geom::Polygon polygon;   // rounded
  std::vector<int> roads;  // indices into CityMap::roads of the roads it fronts
  std::string density;     // a grammar's _Dense or _Sparse ("dense", "sparse"); "" for the zone's own
};

// The blocks, in the map's face order; every face of block b gets a label whose `block` is b.
// The map is snap-rounded first, so a block's cell is its edges as the map keeps them, the
// edges of the map of the block alone its lots are made in (CityLots).
// A block takes the use of the layout's land around a point inside it: a grammar's Park
// makes it green space, its _Dense and _Sparse its density.
std::vector<Block> cut_blocks(CityMap& city_map, const CitySettings& city, const std::vector<ZoneFeature>& zones,
                              const std::vector<PlannedUse>& uses = {});

}  // namespace exacity
