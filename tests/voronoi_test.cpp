// The Voronoi layout's streets: the diagram, junctions along its edges, the inner-road
// heuristic on a hand-made cell, and cells clipped at a concave zone edge.
#include <gtest/gtest.h>

#include <fstream>

#include "generate/export/geojson.h"
#include "generate/layout/voronoi.h"
#include "generate/pipeline.h"
#include "generate/export/validate.h"
#include "tests/test_util.h"

using namespace exacity;
using geom::Vec2;

TEST(Voronoi, FourSitesOnASquareCutTheBoxIntoQuarters) {
  const std::vector<Vec2> sites{{25, 25}, {75, 25}, {75, 75}, {25, 75}};
  auto cells = voronoi_cells(sites, {0, 0, 100, 100}, 50);
  ASSERT_EQ(cells.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(geom::signed_area(cells[i].ring), 2500) << i;
    // Two edges on the box, one towards each neighbouring site, none towards the opposite one.
    std::vector<int> across = cells[i].across;
    std::sort(across.begin(), across.end());
    std::vector<int> expected{-1, -1, static_cast<int>((i + 1) % 4), static_cast<int>((i + 3) % 4)};
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(across, expected) << i;
  }
}

TEST(Voronoi, JunctionsAtEqualStepsStrictlyBetweenTheEnds) {
  EXPECT_EQ(junctions_along({0, 0}, {200, 0}, 50), (std::vector<Vec2>{{50, 0}, {100, 0}, {150, 0}}));
  EXPECT_EQ(junctions_along({0, 0}, {0, 130}, 60), (std::vector<Vec2>{{0, 65}}));  // two steps of 65
  EXPECT_TRUE(junctions_along({0, 0}, {70, 0}, 60).empty());
}

TEST(Voronoi, InnerRoadsStartPerpendicularToTheLongestRoadThenRunParallel) {
  // A 200 x 100 cell, its roads counter-clockwise from the bottom, junctions every 50 m.
  const std::vector<CellRoad> roads{{{0, 0}, {50, 0}, {100, 0}, {150, 0}, {200, 0}},
                                    {{200, 0}, {200, 50}, {200, 100}},
                                    {{200, 100}, {150, 100}, {100, 100}, {50, 100}, {0, 100}},
                                    {{0, 100}, {0, 50}, {0, 0}}};
  auto made = inner_roads(roads);
  // From (50, 0) straight across, then the bottom's other junctions parallel to it; the
  // side junctions would cross those, so they stay unjoined.
  const std::vector<std::pair<Vec2, Vec2>> expected{{{50, 0}, {50, 100}}, {{100, 0}, {100, 100}}, {{150, 0}, {150, 100}}};
  EXPECT_EQ(made, expected);
  // A skewed cell: the first inner road is the one nearest square to the long bottom road.
  const std::vector<CellRoad> skewed{{{0, 0}, {60, 0}, {120, 0}, {180, 0}, {240, 0}, {330, 0}},
                                     {{330, 0}, {300, 100}},
                                     {{300, 100}, {220, 100}, {140, 100}, {60, 100}, {-20, 100}},
                                     {{-20, 100}, {0, 0}}};
  made = inner_roads(skewed);
  ASSERT_GE(made.size(), 2u);
  EXPECT_EQ(made[0], (std::pair<Vec2, Vec2>{{60, 0}, {60, 100}}));
  // Then (120, 0) to the junction whose road is within 15 degrees of parallel to it; (180,
  // 0)'s best, (220, 100), is 22 degrees off.
  EXPECT_EQ(made[1], (std::pair<Vec2, Vec2>{{120, 0}, {140, 100}}));
  for (const auto& [a, b] : made) EXPECT_TRUE(a.y == 0 || b.y == 0);
}

TEST(VoronoiLayout, CellsAreClippedAtAConcaveZoneEdgeNotDropped) {
  auto dir = testing_util::temp_dir("voronoi-u");
  std::ofstream(dir / "in.geojson")
      << R"({"type": "FeatureCollection", "exacity": {"seed": 2, "zones": {"residential": {"layout": "voronoi", "cell_size": 150}}},
  "features": [{"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon", "coordinates":
  [[[0,0],[900,0],[900,900],[650,900],[650,250],[250,250],[250,900],[0,900],[0,0]]]}}]})";
  std::filesystem::create_directories(dir / "out");
  generate_city(load_sketch(dir / "in.geojson"), dir / "out", nullptr);
  Validation v = validate_output(dir / "out");
  ASSERT_TRUE(v.ok()) << v.problems[0];
  // Blocks (green ones included) and road areas inside the zone cover it: no cell dropped.
  std::vector<std::string> problems;
  double covered = 0;
  for (const char* layer : {"blocks", "road_areas"})
    for (const auto& f : read_geojson(dir / "out" / "vector" / (std::string(layer) + ".geojson"), problems).features)
      covered += testing_util::area(f.polygon);
  const double zone = 900 * 900 - 400 * 650;
  EXPECT_NEAR(covered, zone, 1e-6 * zone);
  // And the roads reach into both arms of the U.
  int in_arms = 0;
  for (const auto& f : read_geojson(dir / "out" / "vector" / "roads.geojson", problems).features)
    for (Vec2 p : f.line) in_arms += p.y > 400 && (p.x < 250 || p.x > 650);
  EXPECT_GT(in_arms, 4);
}
