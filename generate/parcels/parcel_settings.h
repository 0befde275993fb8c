// A zone type's block and lot settings ("exacity".zones.TYPE, docs/design.md, The sketch),
// read and checked here.
#pragma once

#include <set>
#include <string>

#include "generate/city/settings.h"
#include "generate/city/zone_type.h"

namespace exacity {

struct BlockSettings {
  double min_block_area = 200;  // m²: smaller blocks become green space
  double min_block_width = 6;   // m: so do thinner ones (2 x area / perimeter)
};

struct LotSettings {
  // "allocation" (measured from the street: lots side by side along every road
  // edge of a block, corner lots at its corners, the block's middle left open; some lots
  // dropped by chance in industrial blocks), "split" (halve perpendicular to the longest edge
  // down to lot_area) or "library" (the lots the model library's entries ask for,
  // along the streets).
  std::string layout = "allocation";
  Range lot_width{14, 24};   // m: frontage of an allocated lot, drawn per street side
  double lot_depth = 30;     // m: how far allocated lots reach back from the street
  double lot_area = 600;     // m²: split stops below this
  double min_lot_edge = 3;   // m: allocated lots with a shorter edge are dropped
  double min_lot_area = 20;  // m²: smaller pieces of lots are dropped
};

LotSettings default_lot_settings(ZoneType type);

// The keys the readers below read.
const std::set<std::string>& parcel_setting_keys();

BlockSettings read_block_settings(const SettingsReader& settings, BlockSettings defaults);
// `road_layout`: the Voronoi layout's plots are split into lots unless the zone says otherwise.
LotSettings read_lot_settings(const SettingsReader& settings, LotSettings defaults, const std::string& road_layout);

}  // namespace exacity
