#include "generate/layout/road_settings.h"

#include <algorithm>
#include <filesystem>

#include "generate/layout/grammar.h"

namespace exacity {
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

// "cell_size" is checked against the road widths, so it is read after them.
void read_voronoi(const SettingsReader& s, const RoadSettings& r, VoronoiSettings& v) {
  s.number("cell_size", v.cell_size, 20, 1e5);
  const double widest = *std::max_element(r.road_widths.begin(), r.road_widths.end());
  if (r.layout == "voronoi" && v.cell_size < 4 * widest)
    s.fail("cell_size", nlohmann::json(v.cell_size).dump() + " m is under 4 road widths (" +
                            nlohmann::json(4 * widest).dump() +
                            " m): the cells would be all road; raise \"cell_size\" or narrow \"road_widths\"");
  s.number("junction_spacing", v.junction_spacing, 5, 1e5);
}

void read_grammar(const SettingsReader& s, const std::string& layout, bool read_grammars, GrammarSettings& g) {
  s.whole_number("grammar_depth", g.depth, 1, 32, "rules");
  if (s.has("grammar")) {
    if (!s.at("grammar").is_string())
      s.fail("grammar", "expected the path of a grammar file (a string), relative to the sketch");
    const std::filesystem::path file = std::filesystem::path(s.file()).parent_path() / s.at("grammar").get<std::string>();
    g.file = std::make_shared<Grammar>(read_grammars ? load_grammar(file) : Grammar{file, {}});
  }
  if (layout == "grammar" && !g.file) s.fail("layout", "\"grammar\" needs \"grammar\": the path of a grammar file");
  s.boolean("grow_large_pieces", g.grow_large_pieces);
}

}  // namespace

RoadSettings default_road_settings(ZoneType type) {
  RoadSettings r;
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
  static const std::set<std::string> keys{"layout",        "road_widths",      "bridges",          "block_area",
                                          "segment_length", "branches",        "jitter",           "segment_deviation",
                                          "origin_deviation", "cell_size",     "junction_spacing", "grammar_depth",
                                          "grammar",        "grow_large_pieces"};
  return keys;
}

RoadSettings read_road_settings(const SettingsReader& s, RoadSettings r, bool read_grammars) {
  read_growth(s, r.growth);
  read_widths(s, r.road_widths);
  s.choice("layout", r.layout, {"growth", "grammar", "voronoi", "streets"},
           "expected \"growth\" (seed 000's growing roads), \"grammar\" (seed 002's split grammar, with \"grammar\": "
           "FILE), \"voronoi\" (seed 003's Voronoi streets) or \"streets\" (the sketch's roads only)");
  read_voronoi(s, r, r.voronoi);
  read_grammar(s, r.layout, read_grammars, r.grammar);
  s.boolean("bridges", r.bridges);
  return r;
}

}  // namespace exacity
