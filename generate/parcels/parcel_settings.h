// A zone type's block and lot settings ("exacity".zones.TYPE, docs/design.md, The sketch),
// read and checked here.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "generate/city/settings.h"
#include "generate/city/zone_settings.h"
#include "generate/city/zone_type.h"

namespace exacity {

class LotLayout;
struct ModelLibrary;
class Channels;

// A row of the table of lot layouts: a new layout is a file defining its LotLayout and
// its factory, and one row here (parcel_settings.cpp).
struct LotLayoutType {
  std::string_view name;
  std::string_view what;  // how the error for an unknown name describes it
  // `library` may be null, unless the lots are the library's (check_lot_library).
  std::unique_ptr<LotLayout> (*make)(const LotSettings& settings, ZoneType zone, const ModelLibrary* library,
                                     const Channels& channels);
  // Its lots are the model library's own, each for one model (Lot::model), which stands
  // on it: no block is one lot when it fits none.
  bool models_own_lots = false;
};
const std::vector<LotLayoutType>& lot_layout_types();
const LotLayoutType& lot_layout_type(std::string_view name);  // one of the table's

LotSettings default_lot_settings(ZoneType type);

// The keys the readers below read.
const std::set<std::string>& parcel_setting_keys();

BlockSettings read_block_settings(const SettingsReader& settings, BlockSettings defaults);
// `road_layout`: the zone's, whose default lot layout it takes unless the zone names one.
LotSettings read_lot_settings(const SettingsReader& settings, LotSettings defaults, const RoadLayoutChoice& road_layout);

}  // namespace exacity
