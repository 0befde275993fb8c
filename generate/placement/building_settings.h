// A zone type's building settings ("exacity".zones.TYPE, docs/design.md, The sketch): the
// extruded footprints' sizes, heights and roofs, how densely placed models stand, and the
// placer the zone names, parsed once from the table of placers into the chosen placer with
// its own settings.
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

// What a placer's reader is given: the zone's settings object and type.
struct PlacerReading {
  const SettingsReader& settings;
  ZoneType zone;
  // The zone chose this placer; else its keys, where written, are only checked.
  bool chosen;
};

// A row of the table of placers, how a zone's lots are filled with the model library's
// buildings: a new placer is a file defining its Placer, its PlacerChoice and its reader,
// and one row here (building_settings.cpp).
struct PlacerType {
  std::string_view name;
  std::string_view what;  // how the error for an unknown name describes it
  std::set<std::string> keys;  // its own settings' keys
  std::shared_ptr<const PlacerChoice> (*read)(const PlacerReading& reading);
};
// The first row is the default.
const std::vector<PlacerType>& placer_types();
const PlacerType& placer_type(std::string_view name);  // one of the table's

BuildingSettings default_building_settings(ZoneType type);

// The keys read_building_settings reads: the shared ones and every placer's.
const std::set<std::string>& building_setting_keys();

BuildingSettings read_building_settings(const SettingsReader& settings, ZoneType type, BuildingSettings defaults);

}  // namespace exacity
