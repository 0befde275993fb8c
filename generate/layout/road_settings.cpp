#include "generate/layout/road_settings.h"

#include <algorithm>

#include "generate/city/named_row.h"

namespace exacity {

// Each layout's reader, in its layout's file.
std::shared_ptr<const RoadLayoutChoice> read_growth_layout(const RoadLayoutReading& reading);
std::shared_ptr<const RoadLayoutChoice> read_grammar_layout(const RoadLayoutReading& reading);
std::shared_ptr<const RoadLayoutChoice> read_voronoi_layout(const RoadLayoutReading& reading);
std::shared_ptr<const RoadLayoutChoice> read_streets_layout(const RoadLayoutReading& reading);

const std::vector<RoadLayoutType>& road_layout_types() {
  static const std::vector<RoadLayoutType> table{
      {"growth", "recursive road growth", {}, read_growth_layout},
      {"grammar", "a split grammar, with \"grammar\": FILE", {"grammar", "grammar_depth", "grow_large_pieces"},
       read_grammar_layout},
      {"voronoi", "streets along Voronoi cells", {"cell_size", "junction_spacing"}, read_voronoi_layout},
      {"streets", "the sketch's roads only", {}, read_streets_layout},
  };
  return table;
}

const RoadLayoutType& road_layout_type(std::string_view name) { return named_row(road_layout_types(), name, "road layout"); }

namespace {

void read_growth(const SettingsReader& s, GrowthSettings& g) {
  s.number("block_area", g.block_area, 100, 1e9);
  s.number("segment_length", g.segment_length, 1, 10000);
  double branches = g.branches;
  s.number("branches", branches, 1, 16);
  g.branches = static_cast<int>(branches);
  s.number("jitter", g.jitter, 0, 180);
  s.number("segment_deviation", g.segment_deviation, 0, 90);
  s.number("origin_deviation", g.origin_deviation, 0, 80);  // below 90, so every road makes progress
}

// The widths every layout uses, by level.
void read_widths(const SettingsReader& s, std::vector<double>& widths) {
  if (!s.has("road_widths")) return;
  const nlohmann::json& w = s.at("road_widths");
  if (!w.is_array() || w.empty()) s.fail("road_widths", "give a list of widths in metres, one per level");
  widths.clear();
  for (std::size_t i = 0; i < w.size(); ++i)
    widths.push_back(read_number(w[i], s.file(), s.where("road_widths") + "[" + std::to_string(i) + "]", 0.5, 200));
}

}  // namespace

RoadSettings default_road_settings(ZoneType type) {
  RoadSettings r;
  static const nlohmann::json none = nlohmann::json::object();
  r.layout = road_layout_types().front().read({SettingsReader(none, "", ""), r, false, true});
  if (type == ZoneType::Commercial || type == ZoneType::Industrial) {
    // Manhattan grid (recursive road growth's commercial setting): straight roads, smaller jitter.
    r.growth.jitter = 10;
    r.growth.segment_deviation = 0;
    r.growth.origin_deviation = 0;
    r.growth.block_area = type == ZoneType::Commercial ? 15000 : 30000;
  }
  return r;
}

double road_width(const RoadSettings& s, int level) {
  return s.road_widths[std::min<std::size_t>(level, s.road_widths.size() - 1)];
}

const std::set<std::string>& road_setting_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k{"layout",           "road_widths", "bridges",           "block_area",
                            "segment_length",   "branches",    "jitter",            "segment_deviation",
                            "origin_deviation"};
    for (const RoadLayoutType& t : road_layout_types()) k.insert(t.keys.begin(), t.keys.end());
    return k;
  }();
  return keys;
}

RoadSettings read_road_settings(const SettingsReader& s, RoadSettings r, bool read_grammars) {
  read_growth(s, r.growth);
  read_widths(s, r.road_widths);
  const auto& table = road_layout_types();
  const RoadLayoutType& chosen = s.row("layout", table, road_layout_type(r.layout->name()));
  // Every layout's keys are checked where written, so that a wrong value is caught before
  // the zone switches to that layout; the chosen one's reading is kept.
  for (const RoadLayoutType& t : table) {
    auto layout = t.read({s, r, read_grammars, &t == &chosen});
    if (&t == &chosen) r.layout = std::move(layout);
  }
  s.boolean("bridges", r.bridges);
  return r;
}

}  // namespace exacity
