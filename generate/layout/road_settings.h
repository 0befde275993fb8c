// A zone type's road settings ("exacity".zones.TYPE, docs/design.md, The sketch): the
// widths and bridges every layout shares, growth's settings, and the road layout the zone
// names, parsed once from the table of road layouts into the chosen layout with its own
// settings (generate/city/zone_settings.h).
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

// What a layout's reader is given: the zone's settings object, the settings every layout
// shares (widths read), and whether grammar files are read.
struct RoadLayoutReading {
  const SettingsReader& settings;
  const RoadSettings& shared;
  bool read_grammars;
  // The zone chose this layout; else its keys, where written, are only checked.
  bool chosen;
};

// A row of the table of road layouts: a new layout is a file defining its RoadLayout, its
// RoadLayoutChoice and its reader, and one row here (road_settings.cpp).
struct RoadLayoutType {
  std::string_view name;
  std::string_view what;  // how the error for an unknown name describes it
  std::set<std::string> keys;  // its own settings' keys
  std::shared_ptr<const RoadLayoutChoice> (*read)(const RoadLayoutReading& reading);
};
const std::vector<RoadLayoutType>& road_layout_types();
const RoadLayoutType& road_layout_type(std::string_view name);  // one of the table's

RoadSettings default_road_settings(ZoneType type);
double road_width(const RoadSettings& s, int level);

// The keys read_road_settings reads: the shared ones and every layout's.
const std::set<std::string>& road_setting_keys();

// `settings` over `defaults`. With `read_grammars` false (for `exacity validate`, which reads
// a copy of the sketch away from its files), grammar files are named but not read.
RoadSettings read_road_settings(const SettingsReader& settings, RoadSettings defaults, bool read_grammars);

}  // namespace exacity
