// Cities that read as cities (docs/design.md, Plausibility), on shapes growth used to stall in:
// a U, a comb, a ring round a lake, a spiral, corridors, a narrow ring, zones cut by highways;
// and regions whose streets would be islands, apart from every other road.
// Each city validates exactly, and its statistics meet the targets: no block over 4x its
// zone's block_area, every lot on a road area and built on, no dead end inside the city and
// no grown road shorter than a block is wide,
// footprints shaped like buildings; a join of buildings to lots on `id` puts each footprint
// in its lot. Label slow: each shape is a whole city, too slow for the sanitizer run.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "generate/export/geojson.h"
#include "generate/pipeline.h"
#include "generate/export/statistics.h"
#include "generate/export/validate.h"
#include "tests/test_util.h"

using namespace exacity;
using geom::Vec2;
using nlohmann::ordered_json;

namespace {

std::string positions(const std::vector<Vec2>& points, bool closed) {
  std::string s = "[";
  for (std::size_t i = 0; i < points.size() + (closed ? 1 : 0); ++i) {
    Vec2 p = points[i % points.size()];
    s += (i ? "," : "") + std::string("[") + format_number(p.x) + "," + format_number(p.y) + "]";
  }
  return s + "]";
}

std::string zone(const std::string& type, const std::vector<std::vector<Vec2>>& rings) {
  std::string coordinates;
  for (const auto& r : rings) coordinates += (coordinates.empty() ? "" : ",") + positions(r, true);
  return R"({"type": "Feature", "properties": {"zone": ")" + type +
         R"("}, "geometry": {"type": "Polygon", "coordinates": [)" + coordinates + "]}}";
}

std::string road(const std::string& cls, double width, const std::vector<Vec2>& line) {
  return R"({"type": "Feature", "properties": {"road": ")" + cls + R"(", "width": )" + format_number(width) +
         R"(}, "geometry": {"type": "LineString", "coordinates": )" + positions(line, false) + "}}";
}

std::vector<Vec2> circle(Vec2 c, double r, int n) {
  std::vector<Vec2> out;
  for (int i = 0; i < n; ++i) out.push_back({c.x + r * std::cos(2 * M_PI * i / n), c.y + r * std::sin(2 * M_PI * i / n)});
  return out;
}

struct Shape {
  const char* name;
  std::vector<std::string> features;
  std::string zone_settings = "{}";  // "exacity".zones
};

std::vector<Shape> shapes() {
  std::vector<Vec2> comb{{0, 0}, {900, 0}};
  for (int i = 0; i < 3; ++i) {
    double x = 900 - 300.0 * i;
    comb.insert(comb.end(), {{x, 600}, {x - 120, 600}, {x - 120, 150}});
    if (i < 2) comb.push_back({x - 300, 150});
  }
  comb.push_back({comb.back().x, 600});
  comb.push_back({0, 600});
  std::vector<Vec2> spiral, outer_side;
  for (int k = 0; k < 120; ++k) {
    double a = k * 0.06, r = 120 + a * 50;
    spiral.push_back({r * std::cos(a), r * std::sin(a)});
    outer_side.push_back({(r + 80) * std::cos(a), (r + 80) * std::sin(a)});
  }
  spiral.insert(spiral.end(), outer_side.rbegin(), outer_side.rend());
  return {
      {"u", {zone("residential", {{{0, 0}, {900, 0}, {900, 900}, {650, 900}, {650, 250}, {250, 250}, {250, 900}, {0, 900}}})}},
      {"comb", {zone("residential", {comb})}},
      {"ring", {zone("residential", {circle({0, 0}, 600, 40)}), zone("water", {circle({0, 0}, 380, 40)})}},
      {"park-ring", {zone("residential", {circle({0, 0}, 550, 32), circle({0, 0}, 300, 32)}), zone("park", {circle({0, 0}, 300, 32)})}},
      {"spiral", {zone("commercial", {spiral})}},
      {"corridor", {zone("residential", {{{0, 0}, {1200, 0}, {1200, 60}, {60, 60}, {60, 900}, {0, 900}}})}},
      // A long L 80 m wide, whose far arm growth once left whole, and a narrow industrial ring
      // (70 m) its straight roads could only shave.
      {"long-l", {zone("residential", {{{0, 0}, {2000, 0}, {2000, 80}, {80, 80}, {80, 1500}, {0, 1500}}})}},
      {"narrow-ring", {zone("industrial", {circle({0, 0}, 800, 64), circle({0, 0}, 730, 64)})}},
      {"cut", {zone("residential", {{{0, 0}, {1000, 0}, {1000, 400}, {400, 400}, {400, 1000}, {0, 1000}}}),
               zone("industrial", {{{400, 0}, {1000, 0}, {1000, 400}, {400, 400}}}),
               road("highway", 24, {{-100, 200}, {1100, 230}}), road("main", 12, {{200, -100}, {215, 1100}})}},
      // Streets that would be islands: a zone drawn 5 m short of a highway's surface, a bow
      // tie whose lobe meets a road only at its pinch, and zones with no road between them.
      {"short-of-highway",
       {zone("residential", {{{0, 0}, {800, 0}, {800, 600}, {0, 600}}}),
        road("highway", 20, {{-100, 615}, {900, 615}})}},
      {"pinch",
       {zone("residential", {{{0, 0}, {600, 400}, {600, 0}, {0, 400}}}), road("main", 10, {{300, 200}, {900, 700}})}},
      {"no-roads",
       {zone("residential", {{{0, 0}, {500, 0}, {500, 500}, {0, 500}}}), zone("park", {{{500, 0}, {700, 0}, {700, 500}, {500, 500}}}),
        zone("commercial", {{{700, 100}, {1200, 100}, {1200, 600}, {700, 600}}})}},
      // One branch from each seed, and three (a strip's seed keeps only one of them across it):
      // a seed left with a single road must not become a dead end.
      {"few-branches",
       {zone("residential", {{{0, 0}, {700, 0}, {700, 500}, {0, 500}}}),
        zone("commercial", {{{700, 0}, {1000, 0}, {1000, 900}, {700, 900}}})},
       R"({"residential": {"branches": 1}, "commercial": {"branches": 3}})"},
      // The other layouts on shapes written to break them: a street graph drawn by
      // hand (ends short of and past the streets they meet), Voronoi streets in a comb, a
      // split grammar in a U.
      {"streets",
       {zone("residential", {{{0, 0}, {600, 0}, {600, 450}, {0, 450}}}),
        road("main", 12, {{0, 0}, {600, 0}, {600, 450}, {0, 450}, {0, 0}}), road("local", 8, {{200, 0.3}, {190, 450}}),
        road("local", 8, {{400, -0.2}, {420, 449.6}}), road("local", 8, {{0, 220}, {200 - 4.75, 220}}),
        road("local", 8, {{195.25, 220}, {407.8, 160}, {600.4, 200}}), road("local", 8, {{100, 0}, {100, 450}}),
        road("local", 8, {{500, 0}, {510, 450.3}}), road("local", 8, {{300, 0}, {300, 450}})},
       R"({"residential": {"layout": "streets"}})"},
      {"voronoi-comb", {zone("residential", {comb})}, R"({"residential": {"layout": "voronoi", "cell_size": 120}})"},
      {"grammar-u",
       {zone("residential", {{{0, 0}, {900, 0}, {900, 900}, {650, 900}, {650, 250}, {250, 250}, {250, 900}, {0, 900}}})},
       R"({"residential": {"layout": "grammar", "grammar": ")" EXACITY_SOURCE_DIR R"(/examples/grammars/town.grammar"}})"},
  };
}

struct Generated {
  std::filesystem::path out;
  Validation validation;
  ordered_json statistics;
};

Generated generate(const Shape& shape) {
  auto dir = testing_util::temp_dir("plausible-" + std::string(shape.name));
  std::string features;
  for (const auto& f : shape.features) features += (features.empty() ? "" : ",") + f;
  std::ofstream(dir / "in.geojson") << R"({"type": "FeatureCollection", "exacity": {"seed": 11, "zones": )"
                                    << shape.zone_settings << R"(}, "features": [)" << features << "]}";
  std::filesystem::create_directories(dir / "out");
  auto result = generate_city(load_sketch(dir / "in.geojson"), dir / "out", nullptr);
  return {dir / "out", validate_output(dir / "out"), result.report["statistics"]};
}

// So ctest names a failing shape instead of dumping its bytes.
void PrintTo(const Shape& shape, std::ostream* os) { *os << shape.name; }

class Plausibility : public testing::TestWithParam<Shape> {};

}  // namespace

TEST_P(Plausibility, CityMeetsEveryTargetAndJoinsOnId) {
  const Generated g = generate(GetParam());
  ASSERT_TRUE(g.validation.ok()) << g.validation.problems[0];
  const ordered_json& zones = g.statistics["zones"];
  ASSERT_TRUE(zones.contains("all"));
  for (const auto& [name, z] : zones.items()) {
    SCOPED_TRACE(name);
    EXPECT_EQ(z["blocks"]["share_area_over_4x_block_area"].get<double>(), 0.0);
    EXPECT_EQ(z["lots"]["share_touching_road"].get<double>(), 1.0);
    EXPECT_EQ(z["lots"]["share_depth_over_width_outside_0.5_5"].get<double>(), 0.0);
    EXPECT_LE(z["lots"]["share_without_building"].get<double>(), 0.03);
    EXPECT_LT(z["footprints"]["share_sharp_angle"].get<double>(), 0.01);
    if (name == "residential") {
      EXPECT_LT(z["footprints"]["share_under_5m_across"].get<double>(), 0.05);
      EXPECT_LE(z["footprints"]["area_m2"]["max"].get<double>(), 2000);
    }
  }
  EXPECT_GT(zones["all"]["lots"]["area_m2"]["count"].get<int>(), 20);
  EXPECT_GT(zones["all"]["footprints"]["area_m2"]["count"].get<int>(), 10);
  EXPECT_EQ(g.statistics["streets"]["dead_ends"].get<int>(), 0);

  std::vector<std::string> problems;
  // No grown road is a stub: each is at least the zones' min_block_width (6 m by default)
  // long. The Voronoi layout's settled streets are not grown and may join nearer.
  const Layer roads = read_geojson(g.out / "vector" / "roads.geojson", problems);
  if (std::string(GetParam().zone_settings).find("voronoi") == std::string::npos)
    for (const auto& f : roads.features) {
      double length = 0;
      for (std::size_t i = 1; i < f.line.size(); ++i) length += geom::distance(f.line[i - 1], f.line[i]);
      EXPECT_GE(length, 6) << "road " << f.properties["id"] << " ends at (" << f.line.back().x << ", " << f.line.back().y << ")";
    }

  // A join of buildings to lots on id puts each footprint in its lot.
  Layer lots = read_geojson(g.out / "vector" / "lots.geojson", problems);
  Layer buildings = read_geojson(g.out / "vector" / "buildings.geojson", problems);
  ASSERT_TRUE(problems.empty()) << problems[0];
  std::map<int, const geom::Polygon*> lot_by_id;
  for (const auto& f : lots.features) lot_by_id[f.properties["id"].get<int>()] = &f.polygon;
  ASSERT_FALSE(buildings.features.empty());
  for (const auto& b : buildings.features) {
    auto it = lot_by_id.find(b.properties["lot"].get<int>());
    ASSERT_NE(it, lot_by_id.end());
    for (Vec2 v : b.polygon.outer) EXPECT_TRUE(geom::odd_crossings(it->second->outer, v));
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, Plausibility, testing::ValuesIn(shapes()),
                         [](const testing::TestParamInfo<Shape>& info) {
                           std::string n = info.param.name;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });
