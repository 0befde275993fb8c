// Lots: allocation from the street on hand-made blocks, blocks too small to cut, heights,
// and whole cities whose lots the exact validator accepts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include "generate/placement/building_settings.h"
#include "generate/placement/buildings.h"
#include "generate/parcels/allocation.h"
#include "generate/parcels/lots.h"
#include "generate/pipeline.h"
#include "generate/export/validate.h"
#include "geom/cell.h"
#include "geom/measure.h"
#include "tests/test_util.h"

using namespace exacity;
using geom::Vec2;

namespace {

// A residential square cut by three streets, one steep across the other two.
std::string three_streets() {
  std::string features = R"({"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon",
      "coordinates": [[[0,0],[240,0],[240,200],[0,200],[0,0]]]}})";
  for (const char* line : {"[[-20,70],[260,70]]", "[[150,-20],[150,220]]", "[[38,-93],[142,293]]"})
    features += R"(, {"type": "Feature", "properties": {"road": "local"}, "geometry": {"type": "LineString", "coordinates": )" +
                std::string(line) + "}}";
  return R"({"type": "FeatureCollection", "exacity": {"seed": 2, "zones":
      {"residential": {"layout": "streets"}}}, "features": [)" + features + "]}";
}

Validation generate_and_validate(const std::string& name, const std::string& text, nlohmann::ordered_json* report = nullptr) {
  auto dir = testing_util::temp_dir("lots-" + name);
  std::ofstream(dir / "in.geojson") << text;
  std::filesystem::create_directories(dir / "out");
  auto result = generate_city(load_sketch(dir / "in.geojson"), dir / "out", nullptr);
  if (report) *report = result.report;
  return validate_output(dir / "out");
}

// A w x h block at the origin with a road on every side.
geom::Cell block_with_roads_round(double w, double h) {
  geom::PlanarMap map;
  map.add_ring({{0, 0}, {w, 0}, {w, h}, {0, h}}, 0);
  map.insert_batch();
  map.label_faces([](const geom::Windings& wn) { return geom::winding_of(wn, 0) ? 1 : 0; });
  return map.cells({-1, 0}, {0, 0})[0];
}

// The points of a 1 m grid over the block [0, w] x [0, h] (off its edges) that lie in no lot.
int uncut(const std::vector<geom::Ring>& lots, int w, int h) {
  int n = 0;
  for (double x = 0.5; x < w; x += 1)
    for (double y = 0.5; y < h; y += 1)
      n += std::none_of(lots.begin(), lots.end(), [&](const geom::Ring& l) { return geom::odd_crossings(l, {x, y}); });
  return n;
}

}  // namespace

TEST(Lots, StreetLotsLineEveryRoadEdgeAndLeaveTheMiddleOpen) {
  // A 120 x 100 block with a road on every side; lots 20 m wide and 30 m deep.
  const geom::Cell block = block_with_roads_round(120, 100);
  AllocationSettings p;
  p.lot_width = {20, 20}, p.lot_depth = 30;
  Random rng(1);
  std::vector<geom::Ring> lots = street_lots(block, p, rng);
  // Each side leaves its first 30 m to the corner lot before it: (120 - 30) / 20 rounds to
  // 5 lots along two sides, (100 - 30) / 20 to 4 along the others.
  EXPECT_EQ(lots.size(), 2 * 5 + 2 * 4u);
  for (const geom::Ring& lot : lots) {
    EXPECT_GT(geom::signed_area(lot), 0);
    EXPECT_FALSE(geom::odd_crossings(lot, {60, 50}));  // the middle stays open
    bool reaches_past_edge = false;  // so the map cuts it back exactly at the road
    for (Vec2 v : lot) reaches_past_edge |= v.x < 0 || v.x > 120 || v.y < 0 || v.y > 100;
    EXPECT_TRUE(reaches_past_edge);
    for (Vec2 v : lot) EXPECT_LE(std::min({v.x + 0.5, 120.5 - v.x, v.y + 0.5, 100.5 - v.y}), 30 * std::sqrt(2.0) + 1e-9);
  }
  // Neighbours along a side share their cut exactly.
  EXPECT_EQ(lots[1][0], lots[0][lots[0].size() - 3]);
}

TEST(Lots, StreetLotsCoverABlockThinnerThanTwiceTheirDepth) {
  // A 200 x 60 block with a road on every side and lots 56 m deep, as --like sets them on
  // Helsinki's centre: every lot reaches half way across, 30 m, so the corner lot of a long
  // side ends 30 m along the short side, where the short side's lots begin (not 56 m along
  // it, which left the land between uncut: 26 x 56 m at each corner).
  const geom::Cell block = block_with_roads_round(200, 60);
  AllocationSettings p;
  p.lot_width = {20, 20}, p.lot_depth = 56;
  Random rng(1);
  const std::vector<geom::Ring> lots = street_lots(block, p, rng);
  // Every point of the block, on a 1 m grid off its edges, lies in a lot.
  EXPECT_EQ(uncut(lots, 200, 60), 0);
}

TEST(Lots, StreetLotsReachAcrossABlockWithNoRoadBehind) {
  // A 200 x 16 block, a road along its foot only, lots 30 m deep: no lots come from the
  // other side, so they reach all the way across (half way, 8 m deep and near 16 m wide,
  // made them shallower than half their width, all refused).
  geom::PlanarMap map;
  map.add_ring({{0, 0}, {200, 0}, {200, 16}, {0, 16}}, 0);
  map.add_ring({{-10, -10}, {210, -10}, {210, 0}, {-10, 0}}, 1);
  map.insert_batch();
  map.label_faces([](const geom::Windings& w) { return geom::winding_of(w, 0) ? 1 : geom::winding_of(w, 1) ? 2 : 0; });
  geom::Cell block = map.cells({-1, 0, -1}, {BlockEdge::kNoRoad, 0, 0})[0];
  AllocationSettings p;
  p.lot_width = {20, 20}, p.lot_depth = 30;
  Random rng(1);
  const std::vector<geom::Ring> lots = street_lots(block, p, rng);
  EXPECT_EQ(uncut(lots, 200, 16), 0);
  for (const geom::Ring& lot : lots) {
    double depth = 0;
    for (Vec2 v : lot) depth = std::max(depth, v.y);
    EXPECT_NEAR(depth, 16, 1e-9);
  }
}

TEST(Lots, StreetLotsSkipEdgesWithoutARoad) {
  // Every edge faces a zone edge (kind -1), none a road.
  geom::PlanarMap map;
  map.add_ring({{0, 0}, {100, 0}, {100, 100}, {0, 100}}, 0);
  map.insert_batch();
  map.label_faces([](const geom::Windings& w) { return geom::winding_of(w, 0) ? 1 : 0; });
  geom::Cell block = map.cells({-1, 0}, {-1, -1})[0];
  AllocationSettings p;
  p.lot_width = {25, 25};
  Random rng(1);
  EXPECT_TRUE(street_lots(block, p, rng).empty());
}

TEST(Lots, CitiesWithEveryStrategyValidate) {
  auto zone = [](const std::string& type, double x0, double x1) {
    return R"({"type": "Feature", "properties": {"zone": ")" + type +
           R"("}, "geometry": {"type": "Polygon", "coordinates": [[[)" + std::to_string(x0) + ",0],[" +
           std::to_string(x1) + ",0],[" + std::to_string(x1) + ",500],[" + std::to_string(x0) + ",500],[" +
           std::to_string(x0) + ",0]]]}}";
  };
  std::string features = zone("residential", 0, 600) + "," + zone("commercial", 600, 1100) + "," + zone("industrial", 1100, 1700);
  for (const char* strategy : {"allocation", "split"}) {
    std::string settings = std::string(R"({"seed": 5, "zones": {"residential": {"lots": ")") + strategy +
                           R"("}, "commercial": {"lots": ")" + strategy + R"("}, "industrial": {"lots": ")" + strategy + R"("}}})";
    nlohmann::ordered_json report;
    Validation v = generate_and_validate(strategy, R"({"type": "FeatureCollection", "exacity": )" + settings +
                                                       R"(, "features": [)" + features + "]}",
                                         &report);
    EXPECT_TRUE(v.ok()) << strategy << ": " << (v.problems.empty() ? "" : v.problems[0]);
    EXPECT_GT(v.features["lots"], 20) << strategy;
    EXPECT_GT(report["counts"]["lots"].get<int>(), 20);
  }
}

TEST(Lots, ShallowStripsBetweenRoadsAreBuiltOn) {
  // Blocks 28 m deep between main roads: lots from both sides would be 14 m deep, too
  // shallow for a house behind its setback; joined back to back they hold one.
  std::string features = R"({"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon",
      "coordinates": [[[0,-30],[600,-30],[600,110],[0,110],[0,-30]]]}})";
  for (int y : {0, 40, 80})
    features += R"(, {"type": "Feature", "properties": {"road": "main"}, "geometry": {"type": "LineString",
        "coordinates": [[-20,)" + std::to_string(y) + "],[620," + std::to_string(y) + "]]}}";
  nlohmann::ordered_json report;
  Validation v = generate_and_validate("strips", R"({"type": "FeatureCollection", "exacity": {"seed": 2, "zones":
      {"residential": {"layout": "streets"}}}, "features": [)" + features + "]}",
                                       &report);
  ASSERT_TRUE(v.ok()) << v.problems[0];
  const auto& lots = report["statistics"]["zones"]["residential"]["lots"];
  EXPECT_GT(lots["area_m2"]["count"].get<int>(), 20);
  EXPECT_LE(lots["share_without_building"].get<double>(), 0.03);
  // The outer strips, a road on one side only, take lots all the way across (they were
  // cut half way, and those lots merged after placing); the strips between roads take two
  // rows back to back: every m2 of the blocks is in a lot.
  EXPECT_EQ(report["lot_land"]["residential"]["lots"]["share"].get<double>(), 1.0);
}

TEST(Lots, RefusedPiecesJoinTheLotBesideThemAndTheLandIsAccountedFor) {
  // Three streets, one steep across the others: where its lots meet a cross street's,
  // pieces shallower than half their width (two, 787 m2) were left open; each joins the lot
  // it shares the longest edge with, and report.json's lot_land accounts for every m2 of
  // the blocks. (One, 357 m2, while a zero could round to -0: a block's text, which seeds its
  // lots, was another then.)
  nlohmann::ordered_json report;
  Validation v = generate_and_validate("joined", three_streets(), &report);
  ASSERT_TRUE(v.ok()) << v.problems[0];
  const auto& land = report["lot_land"]["residential"];
  ASSERT_TRUE(land.contains("pieces_joined_to_a_lot"));
  EXPECT_EQ(land["pieces_joined_to_a_lot"]["count"].get<int>(), 2);
  EXPECT_TRUE(land["refused"].empty()) << land["refused"].dump();
  double m2 = land["lots"]["area_m2"].get<double>() + land["no_lot"]["area_m2"].get<double>();
  for (const auto& [why, piece] : land["refused"].items()) m2 += piece["area_m2"].get<double>();
  EXPECT_NEAR(m2, land["blocks_m2"].get<double>(), 2);  // each figure rounded to the m2
}

TEST(Lots, LotLandTalliesTheLotsAsTheyEnd) {
  // lot_land is tallied by the tracing that made each block's last lots, not by tracing a
  // map again: its lots must be the city's as they end (after joined pieces, whole blocks
  // and merged unbuilt lots), their land the lots' as written.
  auto dir = testing_util::temp_dir("lots-land-tally");
  std::ofstream(dir / "in.geojson") << three_streets();
  StageClock clock(nullptr, kCityStages);
  const City city = build_city(load_sketch(dir / "in.geojson"), clock, {}, ExactWork::Kept);
  int lots = 0;
  double m2 = 0, written_m2 = 0;
  for (const auto& [zone, land] : city.lot_land) lots += land.lots.count, m2 += land.lots.area_m2;
  for (const Lot& lot : city.lots) written_m2 += geom::area(lot.polygon);
  ASSERT_GT(lots, 0);
  EXPECT_EQ(lots, static_cast<int>(city.lots.size()));
  EXPECT_NEAR(m2, written_m2, 1e-6 * written_m2);  // exact pieces against their rounding
  // The lots are made in their blocks' maps alone: the city's map holds none of them.
  for (const FaceLabel& label : city.network.map.labels) EXPECT_EQ(label.lot, -1);
}

TEST(Lots, ABlockOverTwoZonesOfOneTypeHasLotsAcrossTheirEdgeWhole) {
  // Two residential zones side by side (x < 100 and x > 100) make one block on each side of
  // a street, whose map (its cell alone) has no edge at x = 100; a commercial zone beside
  // them, with no road between, makes blocks that meet theirs at x = 240. Lots along the
  // street run across x = 100 whole, and those meeting the commercial lots at x = 240 take
  // their vertices there: the city validates.
  auto zone = [](const char* type, int x0, int x1) {
    return R"({"type": "Feature", "properties": {"zone": ")" + std::string(type) +
           R"("}, "geometry": {"type": "Polygon", "coordinates": [[[)" + std::to_string(x0) + ",0],[" +
           std::to_string(x1) + ",0],[" + std::to_string(x1) + ",200],[" + std::to_string(x0) + ",200],[" +
           std::to_string(x0) + ",0]]]}}";
  };
  const std::string features = zone("residential", 0, 100) + "," + zone("residential", 100, 240) + "," +
                               zone("commercial", 240, 400) +
                               R"(, {"type": "Feature", "properties": {"road": "local"}, "geometry": {"type": "LineString",
      "coordinates": [[-20,100],[420,100]]}})";
  nlohmann::ordered_json report;
  const Validation v = generate_and_validate("two-zones", R"({"type": "FeatureCollection", "exacity": {"seed": 3, "zones":
      {"residential": {"layout": "streets"}, "commercial": {"layout": "streets"}}}, "features": [)" + features + "]}",
                                             &report);
  ASSERT_TRUE(v.ok()) << v.problems[0];
  std::ifstream in(testing_util::test_dir("lots-two-zones") / "out" / "vector" / "lots.geojson");
  const nlohmann::json layer = nlohmann::json::parse(in);
  int across = 0, lots = 0;
  for (const auto& lot : layer["features"]) {
    if (lot["properties"]["zone"] != "residential") continue;
    ++lots;
    double low = INFINITY, high = -INFINITY;
    for (const auto& p : lot["geometry"]["coordinates"][0]) low = std::min(low, p[0].get<double>()), high = std::max(high, p[0].get<double>());
    across += low < 99 && high > 101;
  }
  EXPECT_GT(lots, 10);
  EXPECT_GE(across, 2);  // one on each side of the street
}

TEST(Lots, BlocksTooSmallToCutAreOneLot) {
  // A grid of streets 40 m apart: blocks about 30 m across, where lots 30 m deep from every
  // side would be corners and slivers. Each block is one lot and holds a building.
  std::string features = R"({"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon",
      "coordinates": [[[-20,-20],[180,-20],[180,180],[-20,180],[-20,-20]]]}})";
  for (int at = 0; at <= 160; at += 40)
    features += R"(, {"type": "Feature", "properties": {"road": "local"}, "geometry": {"type": "LineString", "coordinates": [[-40,)" +
                std::to_string(at) + "],[200," + std::to_string(at) + R"(]]}}, {"type": "Feature", "properties": {"road": "local"},
        "geometry": {"type": "LineString", "coordinates": [[)" + std::to_string(at) + ",-40],[" + std::to_string(at) + ",200]]}}";
  nlohmann::ordered_json report;
  Validation v = generate_and_validate("small-blocks", R"({"type": "FeatureCollection", "exacity": {"seed": 2, "zones":
      {"residential": {"layout": "streets"}}}, "features": [)" + features + "]}",
                                       &report);
  ASSERT_TRUE(v.ok()) << v.problems[0];
  const auto layer = [](const char* name) {
    std::ifstream in(testing_util::test_dir("lots-small-blocks") / "out" / "vector" / name);
    return nlohmann::json::parse(in)["features"];
  };
  std::set<int> built_blocks, blocks;
  for (const auto& lot : layer("lots.geojson")) built_blocks.insert(lot["properties"]["block"].get<int>());
  for (const auto& block : layer("blocks.geojson"))
    if (!block["properties"]["green"].get<bool>()) blocks.insert(block["properties"]["id"].get<int>());
  EXPECT_GE(blocks.size(), 16u);
  EXPECT_EQ(built_blocks, blocks);
  EXPECT_EQ(report["statistics"]["zones"]["residential"]["lots"]["share_without_building"].get<double>(), 0.0);
}

TEST(Buildings, HeightsFallWithDistanceFromTheCentre) {
  BuildingSettings p = default_building_settings(ZoneType::Commercial);  // 12 to 48 m
  Random rng(3);
  double tallest_centre = 0, tallest_edge = 0;
  for (int i = 0; i < 2000; ++i) {
    double at_centre = building_height(p, 1, rng), at_edge = building_height(p, 0, rng);
    EXPECT_GE(at_centre, p.min_height);
    EXPECT_LE(at_centre, 2 * p.max_height);
    EXPECT_GE(at_edge, p.min_height / 2);
    EXPECT_LE(at_edge, p.max_height / 2);  // no towers at the edge
    tallest_centre = std::max(tallest_centre, at_centre), tallest_edge = std::max(tallest_edge, at_edge);
  }
  EXPECT_GT(tallest_centre, p.max_height);  // the rare doubled towers
  // At the edge heights still span the halved range, up to near its top (2000 draws over
  // 6 to 24 m all miss the top 5% with a chance near 1e-60, whatever the seed).
  EXPECT_GT(tallest_edge, 0.95 * p.max_height / 2);
}
