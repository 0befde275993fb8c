// Looking like a place (docs/gis.md): `generate --like FILE` and the sketch's "like" take
// the zone parameters from the mapped buildings of a real place, measured per zone type.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

#include "tests/cli_util.h"
#include "tests/place_sketch.h"
#include "tests/test_util.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

using place_sketch::measured_place;
using place_sketch::rectangle;

// A residential zone with streets every 120 m and no buildings: all of it generated.
ordered_json empty_place() {
  ordered_json features = ordered_json::array();
  features.push_back({{"type", "Feature"}, {"properties", {{"zone", "residential"}}},
                      {"geometry", {{"type", "Polygon"}, {"coordinates", rectangle(0, 0, 480, 360)}}}});
  for (double v = 0; v <= 480; v += 120)
    features.push_back({{"type", "Feature"}, {"properties", {{"road", "local"}}},
                        {"geometry", {{"type", "LineString"}, {"coordinates", {{v, -10}, {v, 370}}}}}});
  for (double v = 0; v <= 360; v += 120)
    features.push_back({{"type", "Feature"}, {"properties", {{"road", "local"}}},
                        {"geometry", {{"type", "LineString"}, {"coordinates", {{-10, v}, {490, v}}}}}});
  return {{"type", "FeatureCollection"},
          {"exacity", {{"zones", {{"residential", {{"layout", "streets"}}}}}}},
          {"features", features}};
}

ordered_json report_of(const fs::path& out) { return ordered_json::parse(cli_util::read(out / "report.json")); }

// A residential zone 200 m by 60 m along a local street on y = 0, its zone type's settings
// `zone`.
ordered_json one_street(const ordered_json& zone) {
  ordered_json sketch{{"type", "FeatureCollection"}, {"exacity", {{"zones", {{"residential", zone}}}}},
                      {"features", ordered_json::array()}};
  sketch["features"].push_back({{"type", "Feature"}, {"properties", {{"zone", "residential"}}},
                                {"geometry", {{"type", "Polygon"}, {"coordinates", rectangle(0, 0, 200, 60)}}}});
  sketch["features"].push_back({{"type", "Feature"}, {"properties", {{"road", "local"}}},
                                {"geometry", {{"type", "LineString"}, {"coordinates", {{-20, 0}, {220, 0}}}}}});
  return sketch;
}

// Lots 40 m wide and 60 m deep taking 10 m square footprints 3 m behind the street and 4 m
// apart, with `coverage` as lot_coverage (none when 0).
ordered_json square_footprints_zone(double coverage) {
  ordered_json zone{{"layout", "streets"}, {"lot_width", {40, 40}}, {"lot_depth", 60}, {"setback", 3},
                    {"building_gap", 4}, {"footprint_width", {10, 10}}, {"footprint_depth", {10, 10}}};
  if (coverage > 0) zone["lot_coverage"] = coverage;
  return zone;
}

// The zone generated along `length` m of street, the zone `depth` m deep: its generated
// footprints' figures in report.json.
ordered_json generated_along_a_street(const std::string& name, const ordered_json& zone, double length, double depth) {
  const fs::path dir = testing_util::temp_dir(name);
  ordered_json sketch = one_street(zone);
  sketch["features"][0]["geometry"]["coordinates"] = rectangle(0, 0, length, depth);
  sketch["features"][1]["geometry"]["coordinates"] = {{-20, 0}, {length + 20, 0}};
  write(dir / "sketch.geojson", sketch.dump());
  const auto r = cli_util::run("generate " + (dir / "sketch.geojson").string() + " -q -o " + (dir / "out").string());
  EXPECT_EQ(r.code, 0) << r.out;
  return report_of(dir / "out")["footprints_by_zone"]["residential"]["generated"];
}

}  // namespace

// The twelve footprints' figures come out exactly, and the settings from them: setback and
// gap as measured, the areas' distribution at every twentieth; the sketch copy holds them
// (and no "like"), so validate rebuilds the same city.
TEST(Like, MeasuresKnownFootprintsExactly) {
  const fs::path dir = testing_util::temp_dir("like_known");
  write(dir / "place.geojson", measured_place().dump());
  const auto r = cli_util::run("generate " + (dir / "place.geojson").string() + " --like " +
                               (dir / "place.geojson").string() + " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const ordered_json like = report_of(dir / "out")["like"];
  EXPECT_EQ(like["footprints"], 12);
  EXPECT_EQ(like["zones_from"], "the file's land use");
  const ordered_json z = like["zones"]["residential"];
  EXPECT_EQ(z["buildings"], 12);
  const ordered_json& m = z["measured"];
  EXPECT_EQ(m["area_m2"], ordered_json::parse(R"({"count": 12, "p10": 120.0, "median": 200.0, "p90": 300.0})"));
  EXPECT_EQ(m["long_side_m"]["median"], 20.0);
  EXPECT_EQ(m["short_side_m"]["median"], 10.0);
  EXPECT_EQ(m["setback_m"], ordered_json::parse(R"({"count": 12, "p10": 5.0, "median": 5.0, "p90": 5.0})"));
  EXPECT_EQ(m["gap_m"], ordered_json::parse(R"({"count": 12, "p10": 4.0, "median": 4.0, "p90": 4.0})"));
  EXPECT_EQ(m["height_m"]["median"], 11.0);
  EXPECT_EQ(m["coverage_of_land_use"], std::round(2520.0 / 33000 * 1e4) / 1e4);
  const ordered_json& set = z["set"];
  EXPECT_EQ(set["setback"], 5.0);
  EXPECT_EQ(set["building_gap"], 4.0);
  EXPECT_EQ(set["min_footprint_area"], 100.0);  // the smallest: drawn areas do not shrink
  EXPECT_EQ(set["min_footprint_width"], 10.0);  // the short sides' 40th percentile
  EXPECT_GE(set["max_footprint_area"].get<double>(), 320.0);
  EXPECT_EQ(set["heights"], ordered_json::parse("[7.0, 16.0]"));
  // The road's half inside the land use, 350 m by 5 m, is no block's land: 2,520 m² of
  // footprints on the 31,250 m² left.
  ASSERT_TRUE(m.contains("street_surface_m2")) << m.dump();
  EXPECT_EQ(m["street_surface_m2"], 1750.0);
  EXPECT_EQ(m["coverage_of_blocks"], std::round(2520.0 / 31250 * 1e4) / 1e4);
  EXPECT_EQ(set["lot_coverage"], 0.081);
  const ordered_json areas = set["footprint_areas"];
  ASSERT_EQ(areas.size(), 21u);
  EXPECT_EQ(areas[0], 100.0);
  EXPECT_EQ(areas[10], 200.0);
  EXPECT_EQ(areas[20], 320.0);
  // Commercial and industrial land have no buildings: their defaults stay, and say so.
  EXPECT_EQ(like["zones"]["commercial"]["kept_defaults"], "fewer than 10 mapped buildings in commercial land");
  EXPECT_NE(r.out.find("exacity: like " + (dir / "place.geojson").string() + ": residential: 12 mapped buildings, "
                       "footprint median 200 m2, p90 300 m2; set "),
            std::string::npos)
      << r.out;
  const ordered_json copy = ordered_json::parse(cli_util::read(dir / "out" / "sketch.geojson"));
  EXPECT_FALSE(copy["exacity"].contains("like"));
  EXPECT_EQ(copy["exacity"]["zones"]["residential"]["setback"], 5.0);
  EXPECT_EQ(cli_util::run("validate " + (dir / "out").string()).code, 0);
}

// A key the sketch sets itself is kept, and named as kept; the sketch's own "like" is read
// relative to it, as --like would be.
TEST(Like, TheSketchsOwnSettingsWinAndLikeIsASetting) {
  const fs::path dir = testing_util::temp_dir("like_setting");
  ordered_json place = measured_place();
  place["exacity"] = {{"like", "place.geojson"}, {"zones", {{"residential", {{"setback", 2}}}}}};
  write(dir / "place.geojson", place.dump());
  const auto r = cli_util::run("generate " + (dir / "place.geojson").string() + " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const ordered_json z = report_of(dir / "out")["like"]["zones"]["residential"];
  EXPECT_EQ(z["kept_as_the_sketch_sets"], ordered_json::array({"setback"}));
  EXPECT_FALSE(z["set"].contains("setback"));
  EXPECT_EQ(z["set"]["building_gap"], 4.0);
  const ordered_json copy = ordered_json::parse(cli_util::read(dir / "out" / "sketch.geojson"));
  EXPECT_EQ(copy["exacity"]["zones"]["residential"]["setback"], 2);
}

// Generating empty land like the place moves the generated footprints' median from the
// defaults' toward the place's 200 m², to within a quarter of it.
TEST(Like, GeneratedMedianMovesTowardThePlace) {
  const fs::path dir = testing_util::temp_dir("like_median");
  write(dir / "place.geojson", measured_place().dump());
  write(dir / "empty.geojson", empty_place().dump());
  auto median = [&](const std::string& like, const char* out) {
    const auto r = cli_util::run("generate " + (dir / "empty.geojson").string() + like + " -q -o " + (dir / out).string());
    EXPECT_EQ(r.code, 0) << r.out;
    return report_of(dir / out)["footprints_by_zone"]["residential"]["generated"]["median_m2"].get<double>();
  };
  const double before = median("", "before");
  const double after = median(" --like " + (dir / "place.geojson").string(), "after");
  EXPECT_LT(std::abs(after - 200), std::abs(before - 200)) << before << " -> " << after;
  EXPECT_LT(std::abs(after - 200), 0.25 * 200) << before << " -> " << after;
}

// "lot_coverage" fills each lot with rows behind the first (10 m deep footprints 4 m
// apart) until they cover that share of it: lots 40 m wide and 56 m deep hold one row of
// three without it (0.11 of the lot), three rows with 0.25, the last one footprint.
TEST(Like, LotCoverageFillsLotsRowBehindRow) {
  const fs::path dir = testing_util::temp_dir("like_lot_coverage");
  auto run = [&](double coverage, const char* out) {
    write(dir / (std::string(out) + ".geojson"), one_street(square_footprints_zone(coverage)).dump());
    const auto r = cli_util::run("generate " + (dir / (std::string(out) + ".geojson")).string() + " -q -o " + (dir / out).string());
    EXPECT_EQ(r.code, 0) << r.out;
    std::set<double> fronts;  // each footprint's least y, to the centimetre: one per row
    const ordered_json buildings = ordered_json::parse(cli_util::read(dir / out / "vector" / "buildings.geojson"));
    for (const ordered_json& b : buildings["features"]) {
      if (b["properties"]["kind"] != "building") continue;  // not a garden tree
      double least = INFINITY;
      for (const ordered_json& p : b["geometry"]["coordinates"][0]) least = std::min(least, p[1].get<double>());
      fronts.insert(std::round(least * 100) / 100);
    }
    EXPECT_EQ(cli_util::run("validate " + (dir / out).string()).code, 0);
    return std::pair{fronts.size(), report_of(dir / out)["footprints_by_zone"]["residential"]["generated"]["coverage_of_lots"].get<double>()};
  };
  const auto [rows_before, before] = run(0, "one_row");
  const auto [rows_after, after] = run(0.25, "filled");
  EXPECT_EQ(rows_before, 1u);
  EXPECT_EQ(rows_after, 3u);
  EXPECT_LT(before, 0.12);
  EXPECT_GE(after, 0.25) << before;
  EXPECT_LT(after, 0.25 + 100.0 / 2000) << "filled past one footprint more than asked";
}

// A drawn area that does not fit its lot as drawn keeps its area in another shape: 900 m²
// drawn 45 m wide stands 28.1 m wide and 32 m deep on each of five lots 40 m wide (shrunk,
// it fell under min_footprint_area, and the lots left empty merged in pairs: 2 buildings).
TEST(Like, ADrawnAreaThatDoesNotFitKeepsItsAreaInAnotherShape) {
  const fs::path dir = testing_util::temp_dir("like_whole_areas");
  ordered_json zone{{"layout", "streets"}, {"lot_width", {40, 40}}, {"lot_depth", 60}, {"setback", 3},
                    {"building_gap", 4}, {"footprint_width", {45, 45}}, {"footprint_depth", {20, 20}},
                    {"footprint_areas", {900, 900}}, {"min_footprint_area", 800}};
  write(dir / "sketch.geojson", one_street(zone).dump());
  const auto r = cli_util::run("generate " + (dir / "sketch.geojson").string() + " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const ordered_json g = report_of(dir / "out")["footprints_by_zone"]["residential"]["generated"];
  EXPECT_EQ(g["footprints"], 5);  // one on each lot
  EXPECT_NEAR(g["median_m2"].get<double>(), 900, 0.1);
  EXPECT_NEAR(g["footprint_m2"].get<double>(), 4500, 0.5);
}

// A zone type with lot_coverage fills its blocks: lots 20 m deep on a zone 60 m deep leave
// its back two thirds open, which the lots beside it take; an industrial zone keeps every
// lot (none left out as yard, whose share the place's coverage holds).
TEST(Like, LotCoverageGivesTheBlocksOpenLandToTheirLots) {
  const fs::path dir = testing_util::temp_dir("like_fill_blocks");
  auto no_lot = [&](const char* type, double coverage, const char* out) {
    ordered_json zone{{"layout", "streets"}, {"lot_width", {20, 20}}, {"lot_depth", 20}};
    if (coverage > 0) zone["lot_coverage"] = coverage;
    ordered_json sketch = one_street(zone);
    sketch["features"][0]["properties"]["zone"] = type;
    sketch["exacity"]["zones"] = {{type, zone}};
    write(dir / (std::string(out) + ".geojson"), sketch.dump());
    const auto r = cli_util::run("generate " + (dir / (std::string(out) + ".geojson")).string() + " -q -o " + (dir / out).string());
    EXPECT_EQ(r.code, 0) << r.out;
    if (coverage > 0 && std::string(type) == "residential") {
      EXPECT_EQ(cli_util::run("validate " + (dir / out).string()).code, 0);
    }
    return report_of(dir / out)["lot_land"][type]["no_lot"]["share"].get<double>();
  };
  EXPECT_GT(no_lot("residential", 0, "residential_open"), 0.5);
  EXPECT_LT(no_lot("residential", 0.2, "residential_filled"), 0.01);
  EXPECT_LT(no_lot("industrial", 0.2, "industrial_filled"), 0.01);
}

// A lot a mapped building stands on is built around it up to lot_coverage, the mapped
// footprint counted as covered: lots 40 m wide and 56 m deep with 10 m square footprints
// 4 m apart; the house mapped 12 m square on one of them keeps its lot's generated ones 4 m
// away, and they and it cover 0.25 of the lot (one footprint past it at most). Without
// lot_coverage (nothing says how much more it takes) the lot gets nothing, as before; so
// it did with it too (the lot was not built again, and Kotka's completion built 35% less land).
TEST(Like, ALotAMappedBuildingStandsOnIsBuiltAroundItToItsCoverage) {
  const fs::path dir = testing_util::temp_dir("like_built_around_mapped");
  auto run = [&](double coverage, const char* out) {
    ordered_json sketch = one_street(square_footprints_zone(coverage));
    sketch["features"].push_back({{"type", "Feature"}, {"properties", {{"building", "house"}}},
                                  {"geometry", {{"type", "Polygon"}, {"coordinates", rectangle(54, 20, 66, 32)}}}});
    write(dir / (std::string(out) + ".geojson"), sketch.dump());
    const auto r = cli_util::run("generate " + (dir / (std::string(out) + ".geojson")).string() + " -q -o " + (dir / out).string());
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(cli_util::run("validate " + (dir / out).string()).code, 0);
    return ordered_json::parse(cli_util::read(dir / out / "vector" / "buildings.geojson"))["features"];
  };
  auto box = [](const ordered_json& feature) {
    std::array<double, 4> b{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const ordered_json& p : feature["geometry"]["coordinates"][0]) {
      b[0] = std::min(b[0], p[0].get<double>()), b[1] = std::min(b[1], p[1].get<double>());
      b[2] = std::max(b[2], p[0].get<double>()), b[3] = std::max(b[3], p[1].get<double>());
    }
    return b;
  };
  for (double coverage : {0.0, 0.25}) {
    const ordered_json features = run(coverage, coverage > 0 ? "covered" : "not_covered");
    const auto mapped = std::find_if(features.begin(), features.end(), [](const ordered_json& f) { return f["properties"].value("mapped", false); });
    ASSERT_NE(mapped, features.end());
    const int lot = (*mapped)["properties"]["lot"].get<int>();
    const std::array<double, 4> house = box(*mapped);
    double covered = 144;
    int around = 0;
    for (const ordered_json& f : features) {
      if (f["properties"]["kind"] != "building" || f["properties"]["lot"] != lot || f["properties"].value("mapped", false)) continue;
      const std::array<double, 4> b = box(f);
      EXPECT_GE(std::max({house[0] - b[2], b[0] - house[2], house[1] - b[3], b[1] - house[3]}), 4 - 1e-6);
      covered += (b[2] - b[0]) * (b[3] - b[1]);
      ++around;
    }
    const ordered_json report = report_of(dir / (coverage > 0 ? "covered" : "not_covered"))["mapped_buildings"];
    if (coverage == 0) {
      EXPECT_EQ(around, 0);
      EXPECT_EQ(report["lots_not_built_again"], 1);
      EXPECT_EQ(report["lots_built_around_them"], 0);
      continue;
    }
    const double lot_area = 40.0 * 56;
    EXPECT_GT(around, 0);
    EXPECT_GE(covered, 0.25 * lot_area);
    EXPECT_LT(covered, 0.25 * lot_area + 100);
    EXPECT_EQ(report["lots_not_built_again"], 0);
    EXPECT_EQ(report["lots_built_around_them"], 1);
  }
}

// With footprint_areas, a drawn area that fits nowhere in a lot 30 m deep (20 by 20 m, or
// the same area in other shapes, past the first on a lot 40 m wide) waits for a place
// instead of shrinking: every footprint has the drawn 400 m² (shrunk, 100 m² ones filled
// each lot's end).
TEST(Like, ADrawnAreaThatFitsNowhereWaitsInsteadOfShrinking) {
  const fs::path dir = testing_util::temp_dir("like_waiting_areas");
  ordered_json zone{{"layout", "streets"}, {"lot_width", {40, 40}}, {"lot_depth", 30}, {"setback", 3},
                    {"building_gap", 4}, {"footprint_width", {20, 20}}, {"footprint_depth", {20, 20}},
                    {"footprint_areas", {400, 400}}, {"min_footprint_width", 6}};
  write(dir / "sketch.geojson", one_street(zone).dump());
  const auto r = cli_util::run("generate " + (dir / "sketch.geojson").string() + " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const ordered_json buildings = ordered_json::parse(cli_util::read(dir / "out" / "vector" / "buildings.geojson"));
  int count = 0;
  for (const ordered_json& b : buildings["features"]) {
    if (b["properties"]["kind"] != "building") continue;  // not a garden tree
    const ordered_json& ring = b["geometry"]["coordinates"][0];
    double twice = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
      twice += ring[i][0].get<double>() * ring[i + 1][1].get<double>() - ring[i + 1][0].get<double>() * ring[i][1].get<double>();
    EXPECT_NEAR(std::abs(twice) / 2, 400, 0.01);
    ++count;
  }
  EXPECT_GE(count, 5);
}

// A lot keeps the areas drawn for it: one that fits nowhere on the lot ends its footprints
// rather than a fresh draw taking its place. A third of the areas drawn are 100 m², nearly
// all the rest far larger than any lot (up to 20,000 m², in a zone 60 m deep): lots 40 m
// wide along a street 1 km long get about as many 100 m² footprints as a third of their
// draws, lots left empty merging with their neighbours. Replaced, every lot drew until a
// 100 m² one came (17 footprints of 100 m²): lots filtered the place's sizes
// down to what their room held (Kotka's completion, 27% under the mapped median).
TEST(Like, ALotKeepsTheAreasDrawnForIt) {
  ordered_json zone{{"layout", "streets"}, {"lot_width", {40, 40}}, {"lot_depth", 60}, {"setback", 3},
                    {"building_gap", 4}, {"footprint_width", {10, 10}}, {"footprint_depth", {10, 10}},
                    {"footprint_areas", {100, 100, 20000, 20000}}, {"max_footprint_area", 20000}, {"min_footprint_width", 6}};
  const ordered_json g = generated_along_a_street("like_lot_keeps_draws", zone, 1000, 60);
  EXPECT_GE(g["footprints"].get<int>(), 1);
  EXPECT_LT(g["footprints"].get<int>(), 13) << "half the lots built with 100 m²: each redrew until it came";
  EXPECT_NEAR(g["median_m2"].get<double>(), 100, 0.01);
}

// With lot_coverage, a lot's footprints are drawn at once, as many as cover its share on
// average: a third of the areas 100 m², a third 1,600 and a third between, on lots 50 m
// wide that hold one 1,600 m² footprint and seldom one after a small one. Drawn one at a
// time until the lot was covered, a lot ended at the first large one that did not fit and
// kept the small ones before it: the median came out 286 m² for the areas' 850.
TEST(Like, ALotDrawsItsFootprintsAtOnce) {
  ordered_json zone{{"layout", "streets"}, {"lot_width", {50, 50}}, {"lot_depth", 60}, {"setback", 3},
                    {"building_gap", 4}, {"footprint_width", {10, 10}}, {"footprint_depth", {10, 10}},
                    {"footprint_areas", {100, 100, 1600, 1600}}, {"max_footprint_area", 1600}, {"min_footprint_width", 10},
                    {"lot_coverage", 0.4}};
  const ordered_json g = generated_along_a_street("like_lot_draws_at_once", zone, 6000, 60);
  EXPECT_GT(g["footprints"].get<int>(), 100) << g.dump();
  EXPECT_LT(std::abs(g["median_m2"].get<double>() - 850), 0.25 * 850) << g.dump();
  EXPECT_LT(std::abs(g["coverage_of_lots"].get<double>() - 0.4), 0.25 * 0.4) << g.dump();
}

// With footprint_areas, a perimeter band larger than max_footprint_area is not built: the
// lot, 100 m of street 30 m deep, would hold one band of about 1,000 m², and is built in
// rows of the zone's footprints instead, none over 400 m².
TEST(Like, APerimeterBandLargerThanThePlacesFootprintsIsBuiltInRows) {
  ordered_json zone{{"layout", "streets"}, {"lot_width", {100, 100}}, {"lot_depth", 30}, {"setback", 3},
                    {"building_gap", 2}, {"perimeter_depth", 10}, {"footprint_width", {10, 10}},
                    {"footprint_depth", {10, 10}}, {"footprint_areas", {100, 400}}, {"max_footprint_area", 400},
                    {"min_footprint_width", 5}, {"lot_coverage", 0.3}};
  const ordered_json g = generated_along_a_street("like_band_too_large", zone, 400, 30);
  EXPECT_GT(g["footprints"].get<int>(), 4) << g.dump();
  EXPECT_LE(g["p90_m2"].get<double>(), 400) << g.dump();
}

// A file with too few buildings to measure is one line, exit 2, nothing written.
TEST(Like, TooFewBuildingsIsOneLine) {
  const fs::path dir = testing_util::temp_dir("like_few");
  ordered_json few = measured_place();
  few["features"].erase(few["features"].begin() + 5, few["features"].end());  // three buildings left
  write(dir / "few.geojson", few.dump());
  write(dir / "empty.geojson", empty_place().dump());
  const auto r = cli_util::run("generate " + (dir / "empty.geojson").string() + " --like " + (dir / "few.geojson").string() +
                               " -q -o " + (dir / "out").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out, "exacity: error: " + (dir / "few.geojson").string() +
                       ": maps 3 building footprints, too few to measure a place by (at least 10); give an extract "
                       "or a file with more of its buildings, or leave out --like\n");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Eleven footprints 30 m wide and 12 m deep side by side 5 m behind the road's surface,
// on 350 m of street fronting the zone on one side (the road's 350 m); the like report of
// generating it like itself.
ordered_json touching_place_report(const std::string& name) {
  const fs::path dir = testing_util::temp_dir(name);
  ordered_json place = measured_place();
  place["features"].erase(place["features"].begin() + 2, place["features"].end());
  for (int i = 0; i < 11; ++i)
    place["features"].push_back({{"type", "Feature"}, {"properties", {{"building", "yes"}}},
                                 {"geometry", {{"type", "Polygon"}, {"coordinates", rectangle(30 * i, 10, 30 * i + 30, 22)}}}});
  write(dir / "place.geojson", place.dump());
  const auto r = cli_util::run("generate " + (dir / "place.geojson").string() + " --like " + (dir / "place.geojson").string() +
                               " -q -o " + (dir / "out").string());
  EXPECT_EQ(r.code, 0) << r.out;
  return report_of(dir / "out")["like"]["zones"]["residential"];
}

// What a perimeter block's depth is read from (docs/gis.md): the street frontage its
// land use fronts and each footprint's wing depth, twice its area over its perimeter.
TEST(Like, MeasuresStreetFrontageAndWingDepths) {
  const ordered_json m = touching_place_report("like_frontage")["measured"];
  EXPECT_EQ(m["gap_m"]["median"], 0.0);
  EXPECT_EQ(m["street_frontage_m"], 350.0);
  EXPECT_EQ(m["wing_depth_m"]["median"], 8.6);  // 720 / 84
}

// The frontage rule (docs/gis.md): the 350 m of street shared by the eleven footprints'
// 3,960 m² (no gap beside them) gives each a depth of 11.3 m, and each lot the frontage
// of its 360 m² at that depth; lots 17 m deep (5 m setback and 11.3 m, over half the
// widest frontage). The footprints touch (median gap 0), so it is set, not only reported;
// where they stand apart (the measured place's 4 m) it is only reported.
TEST(Like, ReportsTheFrontageRuleAndSetsItWhereBuildingsTouch) {
  const ordered_json z = touching_place_report("like_frontage_rule");
  ASSERT_TRUE(z.contains("frontage_rule")) << z.dump();
  const ordered_json& rule = z["frontage_rule"];
  EXPECT_EQ(rule["perimeter_depth"], 11.3);
  EXPECT_EQ(rule["lot_frontages"], ordered_json(std::vector<double>(21, 31.9)));
  EXPECT_EQ(rule["lot_depth"], 17.0);
  EXPECT_EQ(z["set"].value("perimeter_depth", ordered_json()), 11.3);
  EXPECT_EQ(z["set"].value("lot_frontages", ordered_json()), rule["lot_frontages"]);
  EXPECT_EQ(z["set"].value("lot_depth", ordered_json()), 17.0);
  // Perimeter footprints from the place's tenth to its 95th percentile area (all 360 m²
  // here), or the largest rectangle of its sides' ranges if that is larger.
  EXPECT_EQ(rule["min_footprint_area"], 360.0);
  EXPECT_GE(rule["max_footprint_area"].get<double>(), 360.0);
  EXPECT_EQ(z["set"].value("min_footprint_area", ordered_json()), 360.0);
  EXPECT_EQ(z["set"].value("max_footprint_area", ordered_json()), rule["max_footprint_area"]);

  const fs::path dir = testing_util::temp_dir("like_frontage_rule_apart");
  write(dir / "place.geojson", measured_place().dump());
  const auto r = cli_util::run("generate " + (dir / "place.geojson").string() + " --like " + (dir / "place.geojson").string() +
                               " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const ordered_json apart = report_of(dir / "out")["like"]["zones"]["residential"];
  EXPECT_TRUE(apart.contains("frontage_rule"));
  EXPECT_FALSE(apart["set"].contains("perimeter_depth"));
  EXPECT_FALSE(apart["set"].contains("lot_frontages"));
}

// "lot_frontages" draws each allocated lot's frontage from its distribution: 25 m every
// time along the 200 m of street a zone 200 m by 60 m fronts makes eight lots.
TEST(Like, LotFrontagesDrawEachLotFromTheirDistribution) {
  const fs::path dir = testing_util::temp_dir("like_lot_frontages");
  write(dir / "sketch.geojson", one_street({{"layout", "streets"}, {"lot_frontages", {25, 25}}}).dump());
  const auto r = cli_util::run("generate " + (dir / "sketch.geojson").string() + " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::vector<std::pair<double, double>> spans;  // each lot's least and greatest x
  const ordered_json lots = ordered_json::parse(cli_util::read(dir / "out" / "vector" / "lots.geojson"));
  for (const ordered_json& lot : lots["features"]) {
    std::pair<double, double> span{INFINITY, -INFINITY};
    for (const ordered_json& p : lot["geometry"]["coordinates"][0])
      span = {std::min(span.first, p[0].get<double>()), std::max(span.second, p[0].get<double>())};
    spans.push_back(span);
  }
  std::sort(spans.begin(), spans.end());
  ASSERT_EQ(spans.size(), 8u);
  for (std::size_t k = 0; k < spans.size(); ++k) {
    EXPECT_NEAR(spans[k].first, 25.0 * static_cast<double>(k), 1e-6);
    EXPECT_NEAR(spans[k].second, 25.0 * static_cast<double>(k + 1), 1e-6);
  }
}

namespace {

// A residential zone 330 m by 100 m along a road on y = 0 (as the measured place) mapping
// `footprints`, each {width along the road, depth}, 4 m apart and 5 m behind its surface.
ordered_json place_of(const std::vector<std::pair<double, double>>& footprints) {
  ordered_json place = measured_place(0);
  double x = 10;
  for (auto [w, d] : footprints) {
    place["features"].push_back({{"type", "Feature"}, {"properties", {{"building", "yes"}}},
                                 {"geometry", {{"type", "Polygon"}, {"coordinates", rectangle(x, 10, x + w, 10 + d)}}}});
    x += w + 4;
  }
  return place;
}

// The generated footprints' areas in OUT, sorted.
std::vector<double> generated_areas(const fs::path& out) {
  std::vector<double> areas;
  const ordered_json buildings = ordered_json::parse(cli_util::read(out / "vector" / "buildings.geojson"));
  for (const ordered_json& b : buildings["features"]) {
    if (b["properties"]["kind"] != "building" || b["properties"].value("mapped", false)) continue;
    const ordered_json& ring = b["geometry"]["coordinates"][0];
    double twice = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
      twice += ring[i][0].get<double>() * ring[i + 1][1].get<double>() - ring[i + 1][0].get<double>() * ring[i][1].get<double>();
    areas.push_back(std::abs(twice) / 2);
  }
  std::sort(areas.begin(), areas.end());
  return areas;
}

}  // namespace

// A place whose five sheds (5 m by 8 m) stand among seven houses 20 m square has its sheds
// generated at their size: min_footprint_width is the short sides' 40th percentile (5 m),
// min_footprint_area the smallest area. It was 0.8 of the middle width (16 m), which made
// every shed drawn a footprint of 256 m² or more.
TEST(Like, ThePlacesSmallFootprintsAreGeneratedAtTheirSize) {
  const fs::path dir = testing_util::temp_dir("like_small_footprints");
  std::vector<std::pair<double, double>> footprints(5, {8, 5});
  footprints.insert(footprints.end(), 7, {20, 20});
  write(dir / "place.geojson", place_of(footprints).dump());
  write(dir / "empty.geojson", empty_place().dump());
  const auto r = cli_util::run("generate " + (dir / "empty.geojson").string() + " --like " + (dir / "place.geojson").string() +
                               " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const ordered_json set = report_of(dir / "out")["like"]["zones"]["residential"]["set"];
  EXPECT_EQ(set["min_footprint_width"], 5.0);
  EXPECT_EQ(set["min_footprint_area"], 40.0);
  const std::vector<double> areas = generated_areas(dir / "out");
  ASSERT_FALSE(areas.empty());
  // Two fifths of the draws are sheds (the areas between the place's steps are drawn
  // linearly, so some lie between 40 and 400 m²).
  EXPECT_NEAR(areas.front(), 40, 0.01);
  EXPECT_GE(std::count_if(areas.begin(), areas.end(), [](double a) { return a < 40.01; }), static_cast<long>(areas.size() / 5));
}

// Lots are sized from the upper part of the place's distribution, so they hold its large
// footprints: a place of eight houses 10 m square and four halls 50 m by 16 m (p90 800
// m²) generated on a zone 40 m deep along a street gets lots wide enough for two halls
// with their gaps (108 to 162 m, at most twice the zone's depth), and its p90 within a
// quarter of the mapped one (800 m²). Sized for the middle (16 to 26 m wide), no lot held
// a hall in any of its shapes (p90 240.9 m²).
TEST(Like, LotsHoldThePlacesLargeFootprints) {
  const fs::path dir = testing_util::temp_dir("like_lots_hold_large");
  std::vector<std::pair<double, double>> footprints(8, {10, 10});
  footprints.insert(footprints.end(), 4, {50, 16});
  write(dir / "place.geojson", place_of(footprints).dump());
  ordered_json sketch = one_street({{"layout", "streets"}});
  sketch["features"][0]["geometry"]["coordinates"] = rectangle(0, 0, 400, 40);
  sketch["features"][1]["geometry"]["coordinates"] = {{-20, 0}, {420, 0}};
  write(dir / "street.geojson", sketch.dump());
  const auto r = cli_util::run("generate " + (dir / "street.geojson").string() + " --like " + (dir / "place.geojson").string() +
                               " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const ordered_json report = report_of(dir / "out");
  EXPECT_EQ(report["like"]["zones"]["residential"]["measured"]["area_m2"]["p90"], 800.0);
  const ordered_json g = report["footprints_by_zone"]["residential"]["generated"];
  EXPECT_LT(std::abs(g["p90_m2"].get<double>() - 800), 0.25 * 800) << g.dump();
}
