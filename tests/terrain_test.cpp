// Heightmaps: loading every supported kind, heights, and the exact water outline.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>

#include <fstream>

#include "generate/errors.h"
#include "generate/city/terrain.h"
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

// Water polygons of a terrain, through the planar map as the zone map builds them.
std::vector<geom::Polygon> water_polygons(const Terrain& t) {
  geom::PlanarMap map;
  for (auto [a, b] : t.water_boundary()) map.add_edge(a, b, 0);
  map.insert_batch();
  map.label_faces([](const geom::Windings& w) {
    int n = geom::winding_of(w, 0);
    EXPECT_TRUE(n == 0 || n == 1);
    return n;
  });
  return testing_util::polygons(map.dissolve({-1, 0}, 1)[0]);
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
  EXPECT_EQ(t.water_boundary().size(), 8u);  // collinear pixel edges merged
  auto polys = water_polygons(t);
  ASSERT_EQ(polys.size(), 1u);
  ASSERT_EQ(polys[0].holes.size(), 1u);
  EXPECT_EQ(testing_util::area(polys[0]), 8);
  const geom::Ring& hole = polys[0].holes[0];
  EXPECT_EQ(testing_util::signed_area(hole), -1);  // clockwise, around the land pixel
  ASSERT_EQ(hole.size(), 4u);
  for (auto p : hole) EXPECT_TRUE((p.x == 1 || p.x == 2) && (p.y == 2 || p.y == 3)) << p.x << "," << p.y;
}

TEST(Water, DiagonalPixelsAreTwoPolygons) {
  Terrain t(spec(2, 2), 2, 2, {0, 1, 1, 0});
  auto polys = water_polygons(t);
  ASSERT_EQ(polys.size(), 2u);
  for (const auto& p : polys) {
    EXPECT_EQ(testing_util::area(p), 1);
    EXPECT_TRUE(geom::ring_is_simple(p.outer));
  }
}

TEST(Water, PixelCornersLieOnTheGridAndTheBounds) {
  Terrain t(spec(1000, 700), 3, 7, std::vector<float>(21, 0.f));
  EXPECT_EQ(t.corner(3, 7), (geom::Vec2{1000, 0}));
  geom::Vec2 c = t.corner(1, 0);
  EXPECT_EQ(c.x * 1024, std::nearbyint(c.x * 1024));
  auto polys = water_polygons(t);
  ASSERT_EQ(polys.size(), 1u);
  EXPECT_EQ(testing_util::area(polys[0]), 700000);
}

TEST(Terrain, HeightsAreBicubicBetweenPixelCentresHeldWithinTheFourAround) {
  Terrain t(spec(2, 1), 2, 1, {0.5f, 1.0f});
  EXPECT_DOUBLE_EQ(t.height_at({0.5, 0.5}), 50);
  EXPECT_DOUBLE_EQ(t.height_at({1.5, 0.5}), 100);
  EXPECT_DOUBLE_EQ(t.height_at({1.0, 0.5}), 75);
  // Catmull-Rom halfway between 25 and 100 with 0 and 100 beyond: 9/16 (25 + 100) - 1/16
  // (0 + 100) = 64.0625, where bilinear gave 62.5.
  Terrain curve(spec(4, 1), 4, 1, {0.0f, 0.25f, 1.0f, 1.0f});
  EXPECT_DOUBLE_EQ(curve.height_at({2.0, 0.5}), 64.0625);
  // A groove a pixel wide between high ground: the cubic dips below 0 between the two low
  // pixels, and is held at 0.
  Terrain groove(spec(4, 1), 4, 1, {1.0f, 0.0f, 0.0f, 1.0f});
  EXPECT_DOUBLE_EQ(groove.height_at({2.0, 0.5}), 0);
  EXPECT_DOUBLE_EQ(groove.lowest(), 0);
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
