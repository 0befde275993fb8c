// Lots: seed 000's three residential cases on hand-made corners, the weighted centre,
// and whole cities whose lots the exact validator accepts.
#include <gtest/gtest.h>

#include <fstream>

#include "generate/buildings.h"
#include "generate/lots.h"
#include "generate/pipeline.h"
#include "generate/validate.h"
#include "geom/cell.h"
#include "tests/test_util.h"

using namespace exacity;
using geom::Vec2;

namespace {

void expect_ring(const geom::Ring& got, const geom::Ring& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i].x, want[i].x, 1e-9) << "vertex " << i;
    EXPECT_NEAR(got[i].y, want[i].y, 1e-9) << "vertex " << i;
  }
}

Validation generate_and_validate(const std::string& name, const std::string& text, nlohmann::ordered_json* report = nullptr) {
  auto dir = testing_util::temp_dir("lots-" + name);
  std::ofstream(dir / "in.geojson") << text;
  std::filesystem::create_directories(dir / "out");
  auto result = generate_city(load_sketch(dir / "in.geojson"), dir / "out", nullptr);
  if (report) *report = result.report;
  return validate_output(dir / "out");
}

}  // namespace

TEST(Lots, RegularCornerGivesACornerLotAndAnInsideLot) {
  // Corner (100, 0) of the square (0,0)-(100,100), centre (50, 50).
  auto lots = corner_lots({0, 0}, {100, 0}, {100, 100}, {50, 50});
  ASSERT_EQ(lots.size(), 2u);
  expect_ring(lots[0], {{60, 5}, {95, 5}, {95, 40}, {60, 40}});   // p4 on p0p1, p1, p4 on p1p2, p4
  expect_ring(lots[1], {{95, 40}, {95, 60}, {60, 60}, {60, 40}});  // p4 on p1p2, p3 on p1p2, p3, p4
}

TEST(Lots, CornerThatCannotBeProjectedGivesTwoInsideLots) {
  // p4 = (30, 28) falls beyond p0p1 = (93,3)-(30,21): seed 000's first special case.
  auto lots = corner_lots({100, 0}, {30, 20}, {0, 100}, {30, 30});
  ASSERT_EQ(lots.size(), 2u);
  expect_ring(lots[0], {{27.698630136986303, 27.136986301369863}, {42.15094339622642, 17.528301886792452}, {44, 24}, {30, 28}});
  expect_ring(lots[1], {{27.698630136986303, 27.136986301369863}, {21.698630136986303, 43.13698630136986}, {24, 44}, {30, 28}});
}

TEST(Lots, InsideThatCannotBeProjectedMovesP3OntoTheOtherEdge) {
  // p4 = (54, 20) falls beyond p1p2 = (33,20)-(6,92): seed 000's second special case.
  auto lots = corner_lots({100, 0}, {30, 20}, {0, 100}, {60, 20});
  ASSERT_EQ(lots.size(), 2u);
  expect_ring(lots[0], {{52.41509433962264, 14.452830188679245}, {42.64150943396226, 17.245283018867923}, {48, 36}, {54, 20}});
  expect_ring(lots[1], {{42.64150943396226, 17.245283018867923}, {33, 20}, {6, 92}, {48, 36}});
}

TEST(Lots, NeighbouringCornersShareTheirLotEdges) {
  std::vector<Vec2> square{{0, 0}, {100, 0}, {100, 100}, {0, 100}};
  auto lots = residential_lots(square, weighted_centre(square));
  ASSERT_EQ(lots.size(), 8u);
  // The inside lot of one corner ends where the next corner lot begins.
  EXPECT_EQ(lots[1][1], lots[2][0]);
  EXPECT_EQ(lots[1][2], lots[2][3]);
}

TEST(Lots, WeightedCentreIgnoresVerticesInLine) {
  // A 100 x 100 square with four extra vertices along its top edge (seed 000's figure 8):
  // the plain mean is pulled up, the weighted centre of the corners is not.
  geom::PlanarMap map;
  map.add_ring({{0, 0}, {100, 0}, {100, 100}, {80, 100}, {60, 100}, {40, 100}, {20, 100}, {0, 100}}, 0);
  map.insert_batch();
  map.label_faces([](const geom::Windings& w) { return geom::winding_of(w, 0) ? 1 : 0; });
  geom::Cell block = map.cells({-1, 0}, {0, 0})[0];
  auto corners = block.corners();
  ASSERT_EQ(corners.size(), 4u);
  EXPECT_EQ(weighted_centre(corners), (Vec2{50, 50}));
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

TEST(Buildings, HeightsFallWithDistanceFromTheCentre) {
  ZoneParams p = default_params(ZoneType::Commercial);  // 12 to 48 m
  Random rng(3);
  double tallest_centre = 0, tallest_edge = 0;
  for (int i = 0; i < 2000; ++i) {
    double at_centre = building_height(p, 0, 1000, rng), at_edge = building_height(p, 1500, 1000, rng);
    EXPECT_GE(at_centre, p.min_height);
    EXPECT_LE(at_centre, 2 * p.max_height);
    EXPECT_GE(at_edge, p.min_height / 2);
    EXPECT_LE(at_edge, p.max_height / 2);  // no towers at the edge
    tallest_centre = std::max(tallest_centre, at_centre), tallest_edge = std::max(tallest_edge, at_edge);
  }
  EXPECT_GT(tallest_centre, p.max_height);  // the rare doubled towers
}
