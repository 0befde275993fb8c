// Heightmaps: loading every supported kind, heights, and the exact water outline.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include <fstream>

#include "generate/errors.h"
#include "generate/city/terrain.h"
#include "generate/pipeline.h"
#include "geom/grid.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"
#include "tests/test_util.h"

using namespace exacity;
namespace fs = std::filesystem;

namespace {

TerrainSpec spec(double size_x, double size_y, fs::path file = {}) {
  TerrainSpec s;
  s.heightmap = std::move(file);
  s.bounds = {0, 0, size_x, size_y};
  s.low = 0;
  s.high = 100;
  return s;
}

// The water polygons of a terrain, through the planar map as the zone map builds them,
// checking the outline's rules on the way: corners on the grid; each ring simple and none
// meeting another (the map holds their corners and edges and nothing more); water on their
// left, winding once; with `centres`, every pixel's centre on its own side (water in water).
std::vector<geom::Polygon> water_polygons(const Terrain& t, bool centres = true) {
  geom::PlanarMap map;
  std::size_t corners = 0;
  for (const geom::Ring& r : t.water_boundary()) {
    map.add_ring(r, 0);
    corners += r.size();
    for (geom::Vec2 p : r) {
      EXPECT_EQ(p.x, geom::snap(p.x));
      EXPECT_EQ(p.y, geom::snap(p.y));
    }
  }
  map.insert_batch();
  EXPECT_EQ(map.counts().vertices, corners);
  EXPECT_EQ(map.counts().edges, corners);
  map.label_faces([](const geom::Windings& w) {
    int n = geom::winding_of(w, 0);
    EXPECT_TRUE(n == 0 || n == 1);
    return n;
  });
  const geom::Box& b = t.bounds();
  for (int row = 0; centres && row < t.height(); ++row)
    for (int col = 0; col < t.width(); ++col) {
      const geom::Vec2 c{b.min_x + (col + 0.5) * b.width() / t.width(),
                         b.max_y - (row + 0.5) * b.height() / t.height()};
      EXPECT_EQ(map.label_at(c), t.is_water(col, row) ? 1 : 0) << "pixel " << col << ", " << row;
    }
  return testing_util::polygons(map.dissolve({-1, 0}, 1)[0]);
}

double water_area(const std::vector<geom::Polygon>& polys) {
  double a = 0;
  for (const auto& p : polys) a += testing_util::area(p);
  return a;
}

// Every edge of the polygons' rings.
template <typename F>
void for_each_edge(const std::vector<geom::Polygon>& polys, F f) {
  for (const auto& p : polys)
    for (const geom::Ring* r : {&p.outer})
      for (std::size_t i = 0, j = r->size() - 1; i < r->size(); j = i++) f((*r)[j], (*r)[i]);
  for (const auto& p : polys)
    for (const auto& r : p.holes)
      for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) f(r[j], r[i]);
}

template <typename T>
fs::path write_image(const std::string& name, int w, int h, int channels, OIIO::TypeDesc type, const std::vector<T>& px) {
  fs::path file = testing_util::temp_dir("img-" + name) / name;
  auto out = OIIO::ImageOutput::create(file.string());
  OIIO::ImageSpec s(w, h, channels, type);
  EXPECT_TRUE(out->open(file.string(), s));
  EXPECT_TRUE(out->write_image(type, px.data()));
  out->close();
  return file;
}

}  // namespace

TEST(Water, RingOfWaterIsOnePolygonWithAHole) {
  // Row 0 is north. Water (0) surrounds the land pixel at column 1, row 1.
  Terrain t(spec(4, 4), 4, 4,
            {0, 0, 0, 1,  //
             0, 1, 0, 1,  //
             0, 0, 0, 1,  //
             1, 1, 1, 1});
  auto polys = water_polygons(t);
  ASSERT_EQ(polys.size(), 1u);
  ASSERT_EQ(polys[0].holes.size(), 1u);
  // Along the map's west and north edges the water runs on the bounds, corner included;
  // along its east and south it stays within a third of a pixel of the pixel edges (x 3,
  // y 1), which it meets where the filter sees a straight edge (east of the top row).
  const geom::Ring& outer = polys[0].outer;
  EXPECT_NE(std::find(outer.begin(), outer.end(), geom::Vec2{0, 4}), outer.end());
  EXPECT_NE(std::find(outer.begin(), outer.end(), geom::Vec2{3, 1.5}), outer.end());
  for (geom::Vec2 p : outer) {
    EXPECT_TRUE(p.x <= 2.5 || std::abs(p.x - 3) < 1.0 / 3) << p.x << "," << p.y;
    EXPECT_TRUE(p.y >= 1.5 || std::abs(p.y - 1) < 1.0 / 3) << p.x << "," << p.y;
  }
  // The land pixel is an island: clockwise, a diamond on its pixel's edges.
  const geom::Ring& hole = polys[0].holes[0];
  EXPECT_LT(testing_util::signed_area(hole), 0);
  EXPECT_EQ(hole.size(), 4u);
  for (auto p : hole) EXPECT_EQ(std::abs(p.x - 1.5) + std::abs(p.y - 2.5), 0.5) << p.x << "," << p.y;
  EXPECT_NEAR(testing_util::area(polys[0]), 8, 1);
}

// Two water pixels meeting at a corner join there (a saddle whose centre is water), and the
// two land pixels are cut off.
TEST(Water, DiagonalPixelsJoinAtTheirCorner) {
  Terrain t(spec(2, 2), 2, 2, {0, 1, 1, 0});
  auto polys = water_polygons(t);
  ASSERT_EQ(polys.size(), 1u);
  EXPECT_TRUE(polys[0].holes.empty());
  EXPECT_NEAR(testing_util::area(polys[0]), 2, 0.5);
}

TEST(Water, WaterEverywhereIsTheBoundsAndNoWaterIsNothing) {
  Terrain t(spec(1000, 700), 3, 7, std::vector<float>(21, 0.f));
  auto polys = water_polygons(t);
  ASSERT_EQ(polys.size(), 1u);
  EXPECT_EQ(polys[0].outer.size(), 4u);
  EXPECT_EQ(testing_util::area(polys[0]), 700000);
  EXPECT_TRUE(Terrain(spec(1000, 700), 3, 7, std::vector<float>(21, 0.5f)).water_boundary().empty());
  for (float v : {0.f, 1.f}) {
    Terrain one(spec(1, 1), 1, 1, {v});
    EXPECT_EQ(water_area(water_polygons(one)), v == 0 ? 1 : 0);
  }
}

// Every 3 x 3 map and a thousand random 9 x 7 ones, over bounds off the grid, huge and
// tiny: the rules water_polygons checks hold, whatever the pixels.
TEST(Water, EveryMaskKeepsTheRules) {
  for (int mask = 0; mask < 512; ++mask) {
    std::vector<float> v;
    for (int i = 0; i < 9; ++i) v.push_back(mask >> i & 1 ? 1.f : 0.f);
    water_polygons(Terrain(spec(3, 3), 3, 3, v));
    SCOPED_TRACE(mask);
  }
  std::uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  for (int n = 0; n < 1000; ++n) {
    std::vector<float> v;
    const std::uint32_t density = next() % 100;
    for (int i = 0; i < 63; ++i) v.push_back(next() % 100 < density ? 0.f : 1.f);
    TerrainSpec s = spec(1, 1);
    const double sizes[] = {1, 1e6, 9.3, 0.1};
    s.bounds = {-0.3, 1.7, -0.3 + sizes[n % 4], 1.7 + sizes[n % 4] * 0.8};
    SCOPED_TRACE(n);
    water_polygons(Terrain(s, 9, 7, v));
  }
}

// A lone water pixel stays water: a small diamond round its centre.
TEST(Water, ALoneWaterPixelIsKept) {
  std::vector<float> v(25, 1.f);
  v[12] = 0;
  auto polys = water_polygons(Terrain(spec(50, 50), 5, 5, v));
  ASSERT_EQ(polys.size(), 1u);
  EXPECT_EQ(polys[0].outer.size(), 4u);
  EXPECT_GT(testing_util::area(polys[0]), 0.25 * 100);
}

// Pixels finer than a few grid steps (here 1 m over 1000 of them, about one step each) are
// taken in blocks: a block with any water is water, so no water is lost.
TEST(Water, PixelsFinerThanTheGridAreTakenInBlocks) {
  const int n = 1000;
  std::vector<float> v(static_cast<std::size_t>(n) * 3, 1.f);
  v[n + 500] = 0;  // one pixel in the middle row
  auto polys = water_polygons(Terrain(spec(1, 0.003), n, 3, v), false);
  ASSERT_EQ(polys.size(), 1u);
  geom::Box box = geom::Box::none();
  for (geom::Vec2 p : polys[0].outer) box.add(p);
  EXPECT_LE(box.min_x, 0.5005);
  EXPECT_GE(box.max_x, 0.5);
  EXPECT_LT(box.width(), 0.01);
}

namespace {

// A map of `size` pixels over as many metres, water where water(x, y) holds at a pixel's
// centre (x east, y north, in pixels from the south-west corner).
Terrain drawn(int size, const std::function<bool(double, double)>& water) {
  std::vector<float> v;
  for (int row = 0; row < size; ++row)
    for (int col = 0; col < size; ++col) v.push_back(water(col + 0.5, size - row - 0.5) ? 0.f : 1.f);
  return Terrain(spec(size, size), size, size, std::move(v));
}

}  // namespace

// A river 4 pixels wide at 30 degrees: its pixels step, its banks do not. Away from the
// map's edges every edge of the outline runs within 15 degrees of the river (pixel edges
// ran at 30 and 60), and the banks lie within a third of a pixel of their lines.
TEST(Water, ADiagonalRiverHasStraightBanks) {
  const double angle = 30 * M_PI / 180, dx = std::cos(angle), dy = std::sin(angle);
  auto offset = [&](double x, double y) { return -(x - 4) * dy + (y - 20) * dx; };  // across the river
  auto polys = water_polygons(drawn(64, [&](double x, double y) { return std::abs(offset(x, y)) < 2; }));
  ASSERT_EQ(polys.size(), 1u);
  int edges = 0;
  double worst_angle = 0, worst_offset = 0;
  for_each_edge(polys, [&](geom::Vec2 a, geom::Vec2 b) {
    for (geom::Vec2 p : {a, b})
      if (p.x < 2 || p.y < 2 || p.x > 62 || p.y > 62) return;
    ++edges;
    const double along = std::abs(geom::cross(geom::unit(b - a), {dx, dy}));
    worst_angle = std::max(worst_angle, std::asin(std::min(1.0, along)) * 180 / M_PI);
    worst_offset = std::max(worst_offset, std::abs(std::abs(offset(a.x, a.y)) - 2));
  });
  EXPECT_GT(edges, 40);
  EXPECT_LT(worst_angle, 15);
  EXPECT_LT(worst_offset, 1.0 / 3);
}

// A disc of water of radius 12 pixels: the outline's area is within 2% of pi r^2 and every
// corner within a third of a pixel of the circle (the pixels' own staircase strays 0.69 px
// from it; a third of a pixel is what pixels a diagonal apart leave undecided).
TEST(Water, ADiscIsRound) {
  const double r = 12;
  auto polys = water_polygons(drawn(32, [&](double x, double y) { return std::hypot(x - 16, y - 16) < r; }));
  ASSERT_EQ(polys.size(), 1u);
  EXPECT_NEAR(water_area(polys) / (M_PI * r * r), 1, 0.02);
  double worst = 0;
  for (geom::Vec2 p : polys[0].outer) worst = std::max(worst, std::abs(std::hypot(p.x - 16, p.y - 16) - r));
  EXPECT_LT(worst, 1.0 / 3);
}

// A rectangle of whole pixels keeps its sides on the pixel edges; only its corners round,
// cut by about 0.6 pixel.
TEST(Water, ARectangleOfPixelsStaysARectangle) {
  auto polys = water_polygons(drawn(20, [](double x, double y) { return x > 4 && x < 16 && y > 6 && y < 12; }));
  ASSERT_EQ(polys.size(), 1u);
  const geom::Ring& outer = polys[0].outer;
  int on_sides = 0;
  for (geom::Vec2 p : outer) {
    const double d = std::min({std::abs(p.x - 4), std::abs(p.x - 16), std::abs(p.y - 6), std::abs(p.y - 12)});
    EXPECT_LT(d, 0.5) << p.x << "," << p.y;
    on_sides += d == 0;
  }
  EXPECT_EQ(on_sides, 8);  // the straight runs' ends
  for (geom::Vec2 corner : {geom::Vec2{4, 6}, geom::Vec2{16, 6}, geom::Vec2{16, 12}, geom::Vec2{4, 12}}) {
    double d = INFINITY;
    for (std::size_t i = 0, j = outer.size() - 1; i < outer.size(); j = i++)
      d = std::min(d, geom::distance_to_segment(corner, outer[j], outer[i]));
    EXPECT_LT(d, 0.65);
  }
  EXPECT_NEAR(water_area(polys) / (12 * 6), 1, 0.04);
}

// Whole cities on maps of 1e6 m and of 1 m, their water crossing a park diagonally:
// validation indexed the boxes of such long diagonal edges bucket by bucket and ran out of
// memory.
TEST(Water, HugeAndTinyMapsGenerateAndValidate) {
  const fs::path png = write_image<std::uint8_t>("diagonal.png", 4, 4, 1, OIIO::TypeDesc::UINT8,
                                                 {0, 255, 255, 255, 255, 0, 255, 255, 255, 255, 0, 255, 255, 255, 255, 0});
  for (double size : {1e6, 1.0}) {
    const fs::path dir = testing_util::temp_dir("water-size-" + std::to_string(static_cast<int>(size)));
    const double lo = size * 0.4, hi = size * 0.6;
    std::ofstream(dir / "in.geojson") << R"({"type": "FeatureCollection", "exacity": {"builtin_models": [],
      "terrain": {"heightmap": ")" << png.string() << R"(", "bounds": [0, 0, )" << size << ", " << size << R"(]}},
      "features": [{"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon",
      "coordinates": [[[)" << lo << "," << lo << "],[" << hi << "," << lo << "],[" << hi << "," << hi << "],[" << lo << ","
                                        << hi << "],[" << lo << "," << lo << "]]]}}]}";
    fs::create_directories(dir / "out");
    const GenerateResult result = generate_city(load_sketch(dir / "in.geojson"), dir / "out", nullptr);
    EXPECT_TRUE(result.valid) << size << ": " << result.report["validation"].dump();
    EXPECT_EQ(result.report["counts"]["water"], 1) << size;
  }
}

TEST(Terrain, HeightsAreBicubicBetweenPixelCentresHeldWithinTheFourAround) {
  Terrain t(spec(2, 1), 2, 1, {0.5f, 1.0f});
  EXPECT_DOUBLE_EQ(t.height_at({0.5, 0.5}), 50);
  EXPECT_DOUBLE_EQ(t.height_at({1.5, 0.5}), 100);
  EXPECT_DOUBLE_EQ(t.height_at({1.0, 0.5}), 75);
  // Catmull-Rom halfway between 25 and 100 with 1 and 100 beyond: 9/16 (25 + 100) - 1/16
  // (1 + 100) = 64, where bilinear gave 62.5.
  Terrain curve(spec(4, 1), 4, 1, {0.01f, 0.25f, 1.0f, 1.0f});
  EXPECT_NEAR(curve.height_at({2.0, 0.5}), 64, 1e-6);  // 0.01 as a float
  // A groove a pixel wide between high ground: the cubic dips below 1 between the two low
  // pixels, and is held at 1.
  Terrain groove(spec(4, 1), 4, 1, {1.0f, 0.01f, 0.01f, 1.0f});
  EXPECT_DOUBLE_EQ(groove.height_at({2.0, 0.5}), groove.lowest());
  EXPECT_NEAR(groove.lowest(), 1, 1e-6);
}

// A water pixel's 0 marks water, not the ground's height: the ground under water is the
// lowest land around it, filled in from the shore, so the land does not fall into a
// pixel-wide cliff at the water's edge (nor past the map's edge, where the map is mirrored).
TEST(Terrain, WaterPixelsTakeTheLowestLandAroundThem) {
  Terrain t(spec(6, 1), 6, 1, {0.5f, 0.0f, 0.0f, 0.0f, 0.8f, 0.9f});
  EXPECT_TRUE(t.is_water(1, 0) && t.is_water(2, 0) && t.is_water(3, 0));
  EXPECT_FALSE(t.is_water(0, 0) || t.is_water(4, 0));
  EXPECT_FLOAT_EQ(t.value(1, 0), 0.5f);  // from the shore west
  EXPECT_FLOAT_EQ(t.value(3, 0), 0.8f);  // from the shore east
  EXPECT_FLOAT_EQ(t.value(2, 0), 0.5f);  // the lower of the two filled beside it
  EXPECT_DOUBLE_EQ(t.lowest(), 50);
  // The shore (pixel edges 1 and 4) at the land's height, where it fell to the water's 0.
  EXPECT_DOUBLE_EQ(t.height_at({1, 0.5}), 50);
  EXPECT_GE(t.height_at({4, 0.5}), 80);
  EXPECT_DOUBLE_EQ(t.height_at({-0.5, 0.5}), 50);  // mirrored past the west edge
  // A map all water keeps its 0.
  EXPECT_DOUBLE_EQ(Terrain(spec(2, 1), 2, 1, {0.0f, 0.0f}).height_at({1, 0.5}), 0);
}

// Past the bounds the map is mirrored at its edge and sinks smoothly (smoothstep) to its
// lowest height over half its longer side.
TEST(Terrain, PastTheBoundsTheMapIsMirroredAndSinksToItsLowest) {
  Terrain t(spec(4, 2), 4, 2, {0.25f, 0.5f, 0.75f, 1.0f, 0.25f, 0.5f, 0.75f, 1.0f});
  EXPECT_DOUBLE_EQ(t.fade(), 2);
  EXPECT_DOUBLE_EQ(t.lowest(), 25);
  EXPECT_DOUBLE_EQ(t.height_at({4, 1}), 100);  // the edge
  // 0.5 past the east edge: the mirror of x 3.5 (100), a quarter of the way down:
  // smoothstep(1/4) = 5/32 of the way to 25.
  EXPECT_DOUBLE_EQ(t.height_at({4.5, 1}), 100 - 75 * 5.0 / 32);
  // 1 past: the mirror of x 3, between the centres at 2.5 (75) and 3.5 (100), halfway down.
  EXPECT_DOUBLE_EQ(t.height_at({5, 1}), t.height_at({3, 1}) + (25 - t.height_at({3, 1})) / 2);
  EXPECT_GT(t.height_at({3, 1}), 75);
  EXPECT_DOUBLE_EQ(t.height_at({6, 1}), 25);
  EXPECT_DOUBLE_EQ(t.height_at({-100, 50}), 25);
}

TEST(Terrain, LoadsEightAndSixteenBitFloatAndGreyRgb) {
  auto png8 = write_image<std::uint8_t>("a.png", 2, 1, 1, OIIO::TypeDesc::UINT8, {0, 255});
  auto png16 = write_image<std::uint16_t>("b.png", 2, 1, 1, OIIO::TypeDesc::UINT16, {0, 65535});
  auto tif = write_image<float>("c.tif", 2, 1, 1, OIIO::TypeDesc::FLOAT, {0.f, 8340.f});
  auto rgb = write_image<std::uint8_t>("d.png", 2, 1, 3, OIIO::TypeDesc::UINT8, {0, 0, 0, 255, 255, 255});
  for (const fs::path& f : {png8, png16, tif, rgb}) {
    Terrain t = Terrain::load(spec(2, 1, f));
    EXPECT_TRUE(t.is_water(0, 0)) << f;
    EXPECT_FALSE(t.is_water(1, 0)) << f;
    EXPECT_DOUBLE_EQ(t.height_at({1.5, 0.5}), 100) << f;
  }
}

TEST(Terrain, BadHeightmapsAreUserErrors) {
  auto colour = write_image<std::uint8_t>("e.png", 1, 1, 3, OIIO::TypeDesc::UINT8, {10, 20, 30});
  try {
    Terrain::load(spec(1, 1, colour));
    FAIL() << "accepted a colour image";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("colour"), std::string::npos) << e.what();
  }
  fs::path garbage = testing_util::temp_dir("img-garbage") / "bad.png";
  std::ofstream(garbage) << "not an image";
  EXPECT_THROW(Terrain::load(spec(1, 1, garbage)), UserError);
  try {
    Terrain::load(spec(1, 1, "/nonexistent/valley.png"));
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  }
}

// Real heightmaps from ../shared/data, when this checkout has them beside it.
TEST(Terrain, RealHeightmaps) {
  fs::path data = fs::path(EXACITY_SOURCE_DIR) / ".." / "shared" / "data" / "heightmaps";
  if (!fs::exists(data)) GTEST_SKIP() << "no shared data at " << data;
  Terrain bowl = Terrain::load(spec(1290, 1290, data / "gz_heightmap_bowl_rgb8.png"));  // RGB, R = G = B
  EXPECT_EQ(bowl.width(), 129);
  Terrain volcano = Terrain::load(spec(9791, 13996, data / "gz_volcano_feet_float32.tif"));
  int water = 0;
  for (int r = 0; r < volcano.height(); ++r)
    for (int c = 0; c < volcano.width(); ++c) water += volcano.is_water(c, r);
  EXPECT_EQ(water, 372);  // its zero border (SOURCES.md)
  Terrain srtm = Terrain::load(spec(35910, 19290, data / "derived" / "bigtujunga_elev_m_u16.png"));
  EXPECT_EQ(srtm.width(), 1197);
  EXPECT_EQ(srtm.height(), 643);
}
