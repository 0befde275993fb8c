// A zone type's block and lot settings ("exacity".zones.TYPE, docs/design.md, The sketch):
// the blocks', the lots' smallest area, and the lot layout the zone names, parsed once from
// the table of lot layouts into the chosen layout with its own settings.
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

// What a lot layout's reader is given: the zone's settings object and type (its defaults
// differ by zone type).
struct LotLayoutReading {
  const SettingsReader& settings;
  ZoneType zone;
  // The zone chose this layout; else its keys, where written, are only checked.
  bool chosen;
};

// A row of the table of lot layouts: a new layout is a file defining its LotLayout, its
// LotLayoutChoice and its reader, and one row here (parcel_settings.cpp).
struct LotLayoutType {
  std::string_view name;
  std::string_view what;  // how the error for an unknown name describes it
  std::set<std::string> keys;  // its own settings' keys
  std::shared_ptr<const LotLayoutChoice> (*read)(const LotLayoutReading& reading);
};
const std::vector<LotLayoutType>& lot_layout_types();
const LotLayoutType& lot_layout_type(std::string_view name);  // one of the table's

LotSettings default_lot_settings(ZoneType type);

// The keys the readers below read: the shared ones and every layout's.
const std::set<std::string>& parcel_setting_keys();

BlockSettings read_block_settings(const SettingsReader& settings, BlockSettings defaults);
// `road_layout`: the zone's, whose default lot layout it takes unless the zone names one.
LotSettings read_lot_settings(const SettingsReader& settings, ZoneType type, LotSettings defaults,
                              const RoadLayoutChoice& road_layout);

}  // namespace exacity
