// The items a build keeps, as text and back (generate/plan/memo_text.h): every road plan,
// lot plan and lot's structures of a small city read back to the value written, field for
// field, exact coordinates included.
#include "generate/plan/memo_text.h"

#include <gtest/gtest.h>

#include <memory>

#include "generate/pipeline.h"
#include "generate/regenerate.h"
#include "generate/sketch/sketch.h"
#include "geom/cell.h"

using namespace exacity;

namespace {

// examples/town.geojson built once with a cache, which then holds its every item.
const RegionCache& town_items() {
  static const std::shared_ptr<RegionCache> cache = [] {
    auto c = std::make_shared<RegionCache>();
    StageClock clock(nullptr, kCityStages);
    build_city(load_sketch(std::filesystem::path(EXACITY_SOURCE_DIR) / "examples" / "town.geojson"), clock, c);
    return c;
  }();
  return *cache;
}

// Each value of the memo: written, read back, written again, the same text; and the memo's
// text read into a new memo gives the same text. Returns the memo's text.
template <typename Value>
std::string expect_round_trip(const Memo<Value>& memo, const char* what) {
  int values = 0;
  memo.for_each([&](const std::string&, const Value& value) {
    const std::string text = value_text(value);
    EXPECT_EQ(value_text(value_from_text<Value>(text)), text) << what;
    ++values;
  });
  EXPECT_GT(values, 0) << what;
  const std::string text = memo_text(memo);
  Memo<Value> read;
  read_memo_text(text, read);
  EXPECT_EQ(memo_text(read), text) << what;
  return text;
}

}  // namespace

TEST(MemoText, RoadPlansReadBackExactly) {
  const std::string text = expect_round_trip(town_items().road_plans, "road plans");
  // The growth's roads end where they met others: exact points that are not doubles.
  EXPECT_NE(text.find(" q"), std::string::npos);
  town_items().road_plans.for_each([](const std::string&, const RoadPlan& plan) {
    const RoadPlan read = value_from_text<RoadPlan>(value_text(plan));
    ASSERT_EQ(read.roads.size(), plan.roads.size());
    for (std::size_t i = 0; i < plan.roads.size(); ++i) {
      EXPECT_EQ(geom::exact_text(read.roads[i].path), geom::exact_text(plan.roads[i].path));
      EXPECT_EQ(read.roads[i].path.to_plain(), plan.roads[i].path.to_plain());
      EXPECT_EQ(read.roads[i].width, plan.roads[i].width);
      EXPECT_EQ(read.roads[i].road_class, plan.roads[i].road_class);
    }
    EXPECT_EQ(read.piece_reaches_sketch, plan.piece_reaches_sketch);
    EXPECT_EQ(read.junctions.size(), plan.junctions.size());
    EXPECT_EQ(read.levels, plan.levels);
  });
}

TEST(MemoText, LotPlansReadBackExactly) {
  const std::string text = expect_round_trip(town_items().lot_plans, "lot plans");
  EXPECT_NE(text.find(" q"), std::string::npos);
  town_items().lot_plans.for_each([](const std::string&, const std::vector<PlannedLot>& lots) {
    const auto read = value_from_text<std::vector<PlannedLot>>(value_text(lots));
    ASSERT_EQ(read.size(), lots.size());
    for (std::size_t i = 0; i < lots.size(); ++i) {
      EXPECT_EQ(read[i].block, lots[i].block);
      EXPECT_EQ(read[i].ring, lots[i].ring);
      EXPECT_EQ(geom::exact_text(read[i].cell), geom::exact_text(lots[i].cell));
      if (lots[i].cell.has_value()) {
        EXPECT_EQ(read[i].cell.area(), lots[i].cell.area());
      }
      EXPECT_EQ(read[i].model, lots[i].model);
    }
  });
}

TEST(MemoText, StructuresReadBackExactly) {
  expect_round_trip(town_items().placements, "lot placements");
  int buildings = 0, models = 0;
  town_items().placements.for_each([&](const std::string&, const Structures& s) {
    const Structures read = value_from_text<Structures>(value_text(s));
    ASSERT_EQ(read.buildings.size(), s.buildings.size());
    ASSERT_EQ(read.models.size(), s.models.size());
    for (std::size_t i = 0; i < s.buildings.size(); ++i, ++buildings) {
      EXPECT_EQ(read.buildings[i].polygon.outer, s.buildings[i].polygon.outer);
      EXPECT_EQ(read.buildings[i].height, s.buildings[i].height);
      EXPECT_EQ(read.buildings[i].roof, s.buildings[i].roof);
      EXPECT_EQ(read.buildings[i].roof_faces, s.buildings[i].roof_faces);
    }
    for (std::size_t i = 0; i < s.models.size(); ++i, ++models) {
      EXPECT_EQ(read.models[i].placed.position, s.models[i].placed.position);
      EXPECT_EQ(read.models[i].placed.angle, s.models[i].placed.angle);
      EXPECT_EQ(read.models[i].kind, s.models[i].kind);
    }
  });
  EXPECT_GT(buildings, 0);
  EXPECT_GT(models, 0);
}

TEST(MemoText, RefusesTextItDidNotWrite) {
  for (const char* text : {"", "3 ", "1 x", "0x1p+0 ", "1 4:ring 0 "})
    EXPECT_THROW(value_from_text<RoadPlan>(text), std::invalid_argument) << text;
  EXPECT_THROW(geom::cell_from_exact_text("ring 1 qx 0x0p+0 0 "), std::invalid_argument);
  EXPECT_THROW(geom::path_from_exact_text("path 0x1p+0 "), std::invalid_argument);
}
