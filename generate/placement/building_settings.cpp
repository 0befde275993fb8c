#include "generate/placement/building_settings.h"

#include "generate/city/named_row.h"

namespace exacity {

// Each placer's reader, in its placer's file.
std::shared_ptr<const PlacerChoice> read_row_placer(const PlacerReading& reading);
std::shared_ptr<const PlacerChoice> read_grid_filler(const PlacerReading& reading);

const std::vector<PlacerType>& placer_types() {
  static const std::vector<PlacerType> table{
      {"rows", "along the street", {}, read_row_placer},
      {"grid", "grid filling", {"grid_cell", "grid_passes", "nesting"}, read_grid_filler},
  };
  return table;
}

const PlacerType& placer_type(std::string_view name) { return named_row(placer_types(), name, "placer"); }

namespace {

void read_footprint_sizes(const SettingsReader& s, BuildingSettings& b) {
  s.number("setback", b.setback, 0, 1e3);
  s.number("min_footprint_area", b.min_footprint_area, 0, 1e8);
  s.number("building_gap", b.building_gap, 0, 1e3);
  s.number("min_footprint_width", b.min_footprint_width, 1, 1e4);
  s.number("max_footprint_area", b.max_footprint_area, 1, 1e8);
  s.number("perimeter_depth", b.perimeter_depth, 0, 1e3);
  s.number("lot_coverage", b.lot_coverage, 0, 1);
  s.range("footprint_width", b.footprint_width, 1, 1e4, "footprint width along the street in metres");
  s.range("footprint_depth", b.footprint_depth, 1, 1e4, "footprint depth back from the street in metres");
}

void read_heights(const SettingsReader& s, BuildingSettings& b) {
  if (!s.has("heights")) return;
  const nlohmann::json& h = s.at("heights");
  if (!h.is_array() || h.size() != 2) s.fail("heights", "give [lowest, highest] building heights in metres");
  b.min_height = read_number(h[0], s.file(), s.where("heights"), 0.5, 1000);
  b.max_height = read_number(h[1], s.file(), s.where("heights"), b.min_height, 1000);
}

}  // namespace

BuildingSettings default_building_settings(ZoneType type) {
  static const nlohmann::json none = nlohmann::json::object();
  BuildingSettings b;
  b.placement = placer_types().front().read({SettingsReader(none, "", ""), type, true});
  if (type == ZoneType::Commercial) {
    b.setback = 2, b.min_height = 12, b.max_height = 48;
    b.building_gap = 3, b.footprint_width = {14, 36}, b.footprint_depth = {12, 28};
    b.min_footprint_width = 8, b.max_footprint_area = 3000;
  }
  if (type == ZoneType::Industrial) {
    b.setback = 4, b.min_height = 5, b.max_height = 12;
    b.building_gap = 6, b.footprint_width = {20, 80}, b.footprint_depth = {15, 50};
    b.min_footprint_width = 10, b.max_footprint_area = 20000;
  }
  return b;
}

const std::set<std::string>& building_setting_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k{"setback",          "building_gap",       "footprint_width",    "footprint_depth",
                            "min_footprint_width", "max_footprint_area", "min_footprint_area", "heights",
                            "roof",             "roof_pitch",         "density",            "placement",
                            "height_channel",   "storey_height",      "footprint_areas",    "perimeter_depth",
                            "lot_coverage"};
    for (const PlacerType& t : placer_types()) k.insert(t.keys.begin(), t.keys.end());
    return k;
  }();
  return keys;
}

BuildingSettings read_building_settings(const SettingsReader& s, ZoneType type, BuildingSettings b) {
  read_footprint_sizes(s, b);
  s.number("roof_pitch", b.roof_pitch, 1, 75);
  s.number("storey_height", b.storey_height, 1, 20);
  s.choice("roof", b.roof, {"auto", "flat", "gabled", "hipped"}, "expected \"auto\", \"flat\", \"gabled\" or \"hipped\"");
  s.choice("density", b.density, {"dense", "normal", "sparse"},
           "expected \"dense\", \"normal\" or \"sparse\" (how far apart placed models stand)");
  read_heights(s, b);
  s.distribution("footprint_areas", b.footprint_areas, 1, 1e8, "footprint areas in m²", "[40, 90, 150, 400]");
  const auto& table = placer_types();
  const PlacerType& chosen = s.row("placement", table, placer_type(b.placement->name()));
  // As for road layouts: every placer's keys are checked where written; the chosen one's
  // reading is kept.
  for (const PlacerType& t : table) {
    auto placer = t.read({s, type, &t == &chosen});
    if (&t == &chosen) b.placement = std::move(placer);
  }
  if (s.has("height_channel")) {
    if (!s.at("height_channel").is_string() || s.at("height_channel").get<std::string>().empty())
      s.fail("height_channel", "expected the name of a channel (\"exacity\".channels)");
    b.height_channel = s.at("height_channel").get<std::string>();
  }
  return b;
}

}  // namespace exacity
