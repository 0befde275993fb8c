// A zone type's building settings ("exacity".zones.TYPE, docs/design.md, The sketch): the
// extruded footprints' sizes, heights and roofs, and how densely placed models stand; read
// and checked here.
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

class Placer;
struct ModelLibrary;
class Channels;

// A row of the table of placers, how a zone's lots are filled with the model library's
// buildings: a new placer is a file defining its Placer and its factory, and one row here
// (building_settings.cpp).
struct PlacerType {
  std::string_view name;
  std::string_view what;  // how the error for an unknown name describes it
  // None when the library has no building for the zone.
  std::unique_ptr<Placer> (*make)(const ModelLibrary& library, ZoneType zone, const Channels& channels);
  bool nests = false;  // it may stand a model under another's overhang ("nesting")
};
// The first row is the default.
const std::vector<PlacerType>& placer_types();
const PlacerType& placer_type(std::string_view name);  // one of the table's

BuildingSettings default_building_settings(ZoneType type);

// The keys read_building_settings reads.
const std::set<std::string>& building_setting_keys();

BuildingSettings read_building_settings(const SettingsReader& settings, BuildingSettings defaults);

}  // namespace exacity
