// The lot library on hand-made blocks: street edges lined with the entries' lots,
// corner lots first, and the entries steered by a two-valued channel.
#include <gtest/gtest.h>

#include "generate/sketch/sketch.h"
#include "generate/errors.h"
#include "generate/parcels/lots.h"
#include "generate/parcels/parcel_settings.h"
#include "geom/measure.h"
#include "geom/planar_map.h"

using namespace exacity;
using geom::Vec2;

namespace {

// A block with a road on every side (every edge kind 0, BlockEdge::is_road).
Block street_block(const geom::Ring& ring) {
  geom::PlanarMap map;
  map.add_ring(ring, 0);
  map.insert_batch();
  map.label_faces([](const geom::Windings& w) { return geom::winding_of(w, 0) ? 1 : 0; });
  Block b;
  b.cell = map.cells({-1, 0}, {0, 0})[0];
  return b;
}

Model lot_model(double lot_width, double lot_depth, ChannelValues channels = {}) {
  Model m;
  m.name = "m" + std::to_string(lot_width);
  m.zones = {ZoneType::Residential};
  m.width = lot_width / 2, m.depth = lot_depth / 2, m.height = 5;
  m.lot_width = lot_width, m.lot_depth = lot_depth;
  m.channels = std::move(channels);
  return m;
}

// The box of a planned lot's ring without the front overhang reaching into the street.
geom::Box box_of(const geom::Ring& ring) {
  geom::Box b = geom::Box::none();
  for (Vec2 v : ring) b.add(v);
  return b;
}

}  // namespace

TEST(LibraryLots, AStreetEdgeIsLinedWithTheEntriesLotsCornersFirst) {
  // 100 x 60, roads all round; one entry asking for a 20 x 25 lot.
  const Block block = street_block({{0, 0}, {100, 0}, {100, 60}, {0, 60}});
  ModelLibrary lib;
  lib.models = {lot_model(20, 25)};
  const Channels none;
  Random rng(1);
  const std::vector<PlannedLot> lots = make_library_lots(lib, ZoneType::Residential, none)->plan(block, 7, rng);
  ASSERT_FALSE(lots.empty());
  std::vector<geom::Box> boxes;
  for (const PlannedLot& lot : lots) {
    EXPECT_EQ(lot.model, 0);
    EXPECT_EQ(lot.block, 7);
    ASSERT_EQ(lot.ring.size(), 4u);
    EXPECT_GT(geom::signed_area(lot.ring), 0);
    const geom::Box b = box_of(lot.ring);
    // 20 along its street, 25 deep plus the half metre it reaches past the block's edge.
    EXPECT_TRUE((b.width() == 20 && b.height() == 25.5) || (b.width() == 25.5 && b.height() == 20)) << b.width() << " x " << b.height();
    boxes.push_back(b);
  }
  // Apart from each other (their insides), and inside the block but for the overhang.
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    EXPECT_GE(boxes[i].min_x, -0.5);
    EXPECT_LE(boxes[i].max_x, 100.5);
    EXPECT_GE(boxes[i].min_y, -0.5);
    EXPECT_LE(boxes[i].max_y, 60.5);
    for (std::size_t k = i + 1; k < boxes.size(); ++k) {
      const double wide = std::min(boxes[i].max_x, boxes[k].max_x) - std::max(boxes[i].min_x, boxes[k].min_x);
      const double high = std::min(boxes[i].max_y, boxes[k].max_y) - std::max(boxes[i].min_y, boxes[k].min_y);
      EXPECT_FALSE(wide > 0.5 && high > 0.5) << "lots " << i << " and " << k << " overlap";
    }
  }
  // Every corner of the block is a corner lot's.
  for (Vec2 corner : {Vec2{0, 0}, Vec2{100, 0}, Vec2{100, 60}, Vec2{0, 60}})
    EXPECT_TRUE(std::any_of(boxes.begin(), boxes.end(), [&](const geom::Box& b) {
      return b.min_x <= corner.x && corner.x <= b.max_x && b.min_y <= corner.y && corner.y <= b.max_y;
    })) << corner.x << "," << corner.y;
  // The south side is used up: from corner to corner, no gap along it holds another lot.
  std::vector<std::pair<double, double>> south;
  for (const geom::Box& b : boxes)
    if (b.min_y <= 0) south.push_back({b.min_x, b.max_x});
  std::sort(south.begin(), south.end());
  ASSERT_GE(south.size(), 4u);
  EXPECT_LE(south.front().first, 0);
  EXPECT_GE(south.back().second, 100);
  for (std::size_t i = 1; i < south.size(); ++i) EXPECT_LT(south[i].first - south[i - 1].second, 20);
  // The middle stays open space.
  for (const geom::Box& b : boxes) EXPECT_FALSE(b.min_x < 50 && 50 < b.max_x && b.min_y < 30 && 30 < b.max_y);
}

TEST(LibraryLots, AnEntryWhoseLotFitsNoEdgeLaysNothing) {
  const Block block = street_block({{0, 0}, {30, 0}, {30, 30}, {0, 30}});
  ModelLibrary lib;
  lib.models = {lot_model(40, 40)};
  const Channels none;
  Random rng(1);
  EXPECT_TRUE(make_library_lots(lib, ZoneType::Residential, none)->plan(block, 0, rng).empty());
}

TEST(LibraryLots, ASharpChannelSendsEachEntryToItsHalf) {
  // A 400 m street; the channel is 0 on the west half and 1 on the east (two pixels).
  const Block block = street_block({{0, 0}, {400, 0}, {400, 60}, {0, 60}});
  ModelLibrary lib;
  lib.models = {lot_model(16, 25, {{"downtown", 0.0}}), lot_model(18, 25, {{"downtown", 1.0}})};
  const Channels channels({{"downtown", "", {0, 0, 400, 60}}}, {GreyImage{2, 1, {0.0f, 1.0f}}}, 16);
  Random rng(3);
  int west = 0, east = 0;
  for (const PlannedLot& lot : make_library_lots(lib, ZoneType::Residential, channels)->plan(block, 0, rng)) {
    const geom::Box b = box_of(lot.ring);
    const double x = (b.min_x + b.max_x) / 2;
    // Pixel centres at 100 and 300: the value is 0 west of 100 and 1 east of 300.
    if (x < 100) {
      EXPECT_EQ(lot.model, 0) << x;
      ++west;
    }
    if (x > 300) {
      EXPECT_EQ(lot.model, 1) << x;
      ++east;
    }
  }
  EXPECT_GE(west, 4);
  EXPECT_GE(east, 4);
}

TEST(LibraryLots, AZoneAskingForLibraryLotsNeedsEntriesWithLotsOfAGoodShape) {
  Sketch sketch;
  sketch.path = "town.geojson";
  const nlohmann::json library_lots{{"lots", "library"}};
  sketch.zone_settings[ZoneType::Residential] =
      read_zone_settings(SettingsReader(library_lots, "", ""), ZoneType::Residential, false);
  auto message = [&](const ModelLibrary* lib) {
    try {
      check_lot_library(sketch, lib);
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(nullptr).find("names no model library"), std::string::npos) << message(nullptr);
  ModelLibrary lib;
  lib.file = "lib.json";
  lib.models = {lot_model(20, 25)};
  lib.models[0].lot_width = 0;  // an entry without a lot
  EXPECT_NE(message(&lib).find("has no building entry with a \"lot\" for residential"), std::string::npos) << message(&lib);
  lib.models[0] = lot_model(10, 80);
  EXPECT_NE(message(&lib).find("models[0]: \"lot\" [10, 80] is 8 times as deep as wide"), std::string::npos) << message(&lib);
  lib.models[0] = lot_model(4, 4);
  EXPECT_NE(message(&lib).find("models[0]: \"lot\" [4, 4] is under residential zones' min_lot_area (20 m²)"),
            std::string::npos) << message(&lib);
  lib.models[0] = lot_model(20, 25);
  EXPECT_EQ(message(&lib), "");
}
