// Terrain, water and bridges as the renderer draws them: small cities on small
// heightmaps written here, rendered straight down through an orthographic camera, read back
// from the image's depth and id layers (each from the ray through its pixel's centre).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "generate/mesh/bridges.h"
#include "generate/pipeline.h"
#include "geom/measure.h"
#include "render/camera.h"
#include "render/path_tracer.h"
#include "render/scene.h"
#include "render/sky.h"
#include "tests/river_sketch.h"
#include "tests/test_util.h"

using namespace render;
using river_sketch::kPark;
using river_sketch::straight_river;

namespace {

// A city of `features` on a heightmap of value(col, row) (tests/river_sketch.h).
exacity::City city_on(const std::string& name, double (*value)(int, int), const std::string& features) {
  const auto dir = testing_util::temp_dir("ground-" + name);
  const std::string text = river_sketch::write(dir, value, features);
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  return exacity::build_city(exacity::parse_sketch(text, dir / "sketch.geojson"), clock);
}

// A city of `features` on flat land (no heightmap).
exacity::City flat_city_of(const std::string& name, const std::string& features) {
  const auto dir = testing_util::temp_dir("ground-" + name);
  const std::string text = R"({"type": "FeatureCollection", "exacity": {"seed": 5, "builtin_models": []},
    "features": [)" + features + "]}";
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  return exacity::build_city(exacity::parse_sketch(text, dir / "sketch.geojson"), clock);
}

// What the ray through each pixel's centre met, straight down from 1 km over the box.
struct TopView {
  int width = 0, height = 0;
  std::vector<geom::Vec2> at;  // city coordinates of the pixel's centre
  std::vector<double> z;       // NAN where the ray met nothing
  std::vector<std::uint32_t> id;
};

TopView look_down(const RenderScene& scene, const geom::Box& box, int width, int height) {
  Camera c = Camera::look({static_cast<float>((box.min_x + box.max_x) / 2), static_cast<float>((box.min_y + box.max_y) / 2), 1000},
                          {static_cast<float>((box.min_x + box.max_x) / 2), static_cast<float>((box.min_y + box.max_y) / 2), 0});
  c.orthographic = true;
  c.ortho_height = static_cast<float>(box.height());
  const Camera view = scene.to_scene(c);
  Sky sky(200, 40);
  const Image img = trace(scene, sky, view, TraceSettings{width, height, 1, 1});
  TopView t;
  t.width = width, t.height = height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      V3 o, d;
      view.ray(x + 0.5f, y + 0.5f, width, height, o, d);
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      t.at.push_back({o.x + scene.origin_x, o.y + scene.origin_y});
      t.z.push_back(std::isfinite(img.depth[i]) ? o.z + d.z * img.depth[i] : NAN);
      t.id.push_back(img.id[i]);
    }
  return t;
}

Entity kind(std::uint32_t id) { return static_cast<Entity>(id >> 24); }

bool in_water(const exacity::City& city, geom::Vec2 p) {
  for (const geom::Polygon& w : city.ground.water) {
    bool in = geom::odd_crossings(w.outer, p);
    for (const auto& h : w.holes) in ^= geom::odd_crossings(h, p);
    if (in) return true;
  }
  return false;
}

double distance_to_water_outline(const exacity::City& city, geom::Vec2 p) {
  double d = INFINITY;
  for (const geom::Polygon& w : city.ground.water)
    for (const geom::Ring* r : {&w.outer})
      for (std::size_t i = 0, j = r->size() - 1; i < r->size(); j = i++)
        d = std::min(d, geom::distance_to_segment(p, (*r)[j], (*r)[i]));
  return d;
}

// Hills rising east, with ridges and grooves a pixel apart running east-west: carried on
// past the map's east edge, they made walls to the horizon.
double ridged_ramp(int col, int row) { return 0.2 + 0.6 * col / 19.0 + (row % 2 ? 0.15 : 0.0); }

// A river two to three pixels wide running south-west to north-east in pixel steps, in
// land rising steeply from it.
double river_value(int col, int row) {
  const double off = std::abs(col - (19 - row) * 0.5 - 4.0);
  return off < 1.5 ? 0.0 : std::min(1.0, 0.4 + 0.08 * off);
}

// Traces a size × size view and hands each pixel's coordinates, what it sees and where:
// the point's y and height in the city's frame.
template <class F>
void for_each_pixel_seen(const RenderScene& scene, const Sky& sky, const Camera& view, int size, F&& f) {
  const Image img = trace(scene, sky, view, TraceSettings{size, size, 1, 1});
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * size + x;
      ASSERT_TRUE(std::isfinite(img.depth[i]));
      V3 o, d;
      view.ray(x + 0.5f, y + 0.5f, size, size, o, d);
      f(x, y, img.id[i], o.y + d.y * img.depth[i] + scene.origin_y, o.z + d.z * img.depth[i]);
    }
}

}  // namespace

// Past the map's east edge (x 200) the ground sinks smoothly to the map's lowest height
// (the plane's) within half the map's side (100 m) and stays there: no ridge carried on,
// and no step where the drawn ground gives way to the plane (it ended at 400 m, the city's
// size past it, at the map's edge heights, 30 to 37.5 m over the plane).
TEST(GroundRender, PastTheMapTheGroundSinksToThePlaneWithoutWallsOrAStep) {
  const exacity::City city = city_on("edge", ridged_ramp, kPark);
  ASSERT_TRUE(city.heightmap());
  const double lowest = city.heightmap()->lowest();
  EXPECT_NEAR(lowest, 0.2 * 50, 1e-3);
  Sky sky(200, 40);
  SceneOptions bare_ground;  // the ground itself, without the landscape's hedgerows on it
  bare_ground.landscape_trees = false;
  RenderScene scene(city, sky.sun_direction(), bare_ground);
  // x 150 to 750 m (the ground drawn before reached 400), y 25 to 175 m; 1.5625 m a pixel.
  const TopView t = look_down(scene, {150, 25, 750, 175}, 384, 96);
  double steepest = 0;
  int flat = 0;
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * t.width + x;
      ASSERT_TRUE(std::isfinite(t.z[i])) << "sky straight down at " << t.at[i].x;
      if (x > 0) steepest = std::max(steepest, std::abs(t.z[i] - t.z[i - 1]));
      if (t.at[i].x > 200 + 100 + 10) {  // past the fade and the ground's last 10 m cell across it
        EXPECT_NEAR(t.z[i], lowest, 1e-3) << "at " << t.at[i].x << ", " << t.at[i].y;
        ++flat;
      }
    }
  EXPECT_GT(flat, t.width * t.height / 2);
  // The map's own slope rises under 0.3 m over a pixel; its fall past the edge, at most
  // 37.5 m over 100 m smoothstepped, 1.5 times its mean slope at steepest: 0.9 m a pixel.
  // A step would be tens of metres.
  EXPECT_LT(steepest, 2.0);
}

// Seen from above, water covers its outline (the smooth contour of its pixels, exact in the
// city map) but for its banks sloping under it, and the water is level: the ground no
// longer pokes through it along the banks in pixel-sized teeth.
TEST(GroundRender, BanksFollowTheWaterOutlineAndWaterIsLevel) {
  const exacity::City city = city_on("river", river_value, kPark);
  ASSERT_FALSE(city.ground.water.empty());
  Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  const TopView t = look_down(scene, {0, 0, 200, 200}, 128, 128);  // 1.5625 m a pixel
  double low = INFINITY, high = -INFINITY;
  int water = 0, wrong = 0;
  for (std::size_t i = 0; i < t.id.size(); ++i) {
    const bool wet = in_water(city, t.at[i]);
    // Pixels on the outline, and in the water along it, where its bank slopes under it
    // (kBankSlope, at most a quarter of the water's width out).
    if (distance_to_water_outline(city, t.at[i]) < (wet ? 8.0 : 1.0)) continue;
    if (wet != (kind(t.id[i]) == Entity::Water)) ++wrong;
    if (wet && kind(t.id[i]) == Entity::Water) {
      ++water;
      low = std::min(low, t.z[i]), high = std::max(high, t.z[i]);
    }
  }
  EXPECT_GT(water, 400);  // of 1.5625 m, the river 20 to 30 m wide less 8 m along each bank
  EXPECT_EQ(wrong, 0) << "pixels whose water or land disagrees with the outline";
  EXPECT_LT(high - low, 1e-3) << "the water's surface is not level";
}

// A highway over a river on a heightmap: its bridge's deck is level from bank to bank,
// at the banks' height, and a pier under its middle stands on the riverbed.
TEST(GroundRender, BridgeDeckIsLevelFromAbutmentToAbutmentOnPiers) {
  const exacity::City city =
      city_on("bridge", straight_river, kPark + ", " + river_sketch::highway("[-20, 100], [220, 100]"));
  bool bridge = false;
  for (const auto& r : city.ground.road_areas) bridge |= r.bridge;
  ASSERT_TRUE(bridge);
  Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  // Along the centre line from bank to bank: x 70 to 130 m, one metre a pixel.
  const TopView t = look_down(scene, {70, 99, 130, 101}, 60, 2);
  double low = INFINITY, high = -INFINITY;
  for (int x = 0; x < t.width; ++x) {
    const std::size_t i = x;  // the top row, y 100.5
    EXPECT_EQ(kind(t.id[i]), Entity::Road) << t.at[i].x;
    if (t.at[i].x > 81 && t.at[i].x < 119) low = std::min(low, t.z[i]), high = std::max(high, t.z[i]);
  }
  const double bank = city.heightmap()->height_at({80, 100});
  EXPECT_LT(high - low, 0.01) << "the deck is not level";
  EXPECT_GE(low, bank) << "the deck sinks below its bank";
  // A level ray from the south, under the deck and over the water, meets the pier at x 100.
  Surface hit;
  const exacity::BridgeDecks decks = exacity::bridge_decks(city.ground, city.heightmap());
  const double underside = low - decks.thickness[decks.area_at(city.ground, {100, 100})];
  const double under = (underside + exacity::water_level(city.ground.water[0], city.heightmap())) / 2;
  ASSERT_TRUE(scene.intersect(scene.to_scene(100, 50, under), {0, 1, 0}, 100, hit));
  int road = -1;
  for (const auto& r : city.ground.road_areas)
    if (r.bridge) road = r.road;
  ASSERT_GE(road, 0);
  EXPECT_EQ(hit.entity, entity_id(Entity::Road, static_cast<std::size_t>(road)));  // the pier is its bridge's
  EXPECT_NEAR(hit.position.y + scene.origin_y, 100 - exacity::kPierWidth / 2, 0.01);
}

// A highway across a flat park, seen from the grass at eye height 15 m south of its edge
// through a narrow lens (a pixel is 8 mm there): every pixel sees the grass before the
// edge, or the road (its top or its side), never the ground under the road. The road lies
// 10 cm over the ground and the grass 3 cm; through the gap under the road's edge the
// camera saw the ground beneath it, in the road's shadow: a black sliver along every road
// edge seen from the grass.
TEST(GroundRender, ARoadsEdgeSeenFromTheGrassHidesTheGroundUnderIt) {
  const exacity::City city = flat_city_of("road-edge", kPark + ", " + river_sketch::highway("[-20, 100], [220, 100]"));
  // The road's southern edge where x = 100.
  double edge = INFINITY;
  for (const auto& a : city.ground.road_areas)
    for (std::size_t i = 0, j = a.polygon.outer.size() - 1; i < a.polygon.outer.size(); j = i++) {
      const geom::Vec2 p = a.polygon.outer[j], q = a.polygon.outer[i];
      if ((p.x < 100) != (q.x < 100)) edge = std::min(edge, p.y + (q.y - p.y) * (100 - p.x) / (q.x - p.x));
    }
  ASSERT_LT(edge, 100);
  Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  const Camera view = scene.to_scene(Camera::look({100, static_cast<float>(edge - 15), 1.7f},
                                                  {100, static_cast<float>(edge), 0.06f}, 1));
  const int size = 32;
  int road = 0, grass = 0;
  for_each_pixel_seen(scene, sky, view, size, [&](int x, int y, std::uint32_t id, double at, double) {
    if (kind(id) == Entity::Road) {
      ++road;
      return;
    }
    ++grass;
    EXPECT_LT(at, edge + 1e-3) << "pixel " << x << ", " << y << " sees entity kind " << (id >> 24) << " "
                               << at - edge << " m under the road";
  });
  EXPECT_GT(road, size * 4);
  EXPECT_GT(grass, size * 4);
}

// The same highway's centre line (0.15 m, 2 cm over the road), seen across from 15 m at
// eye height through a narrow lens: every pixel sees the line (its top or its side) or the
// road beside it, never the road under it. Without sides the camera saw, through the gap
// under the line's near edge, the road beneath it in its shadow: a black line a pixel high
// under every zebra stripe and lane line of a street view.
TEST(GroundRender, ARoadMarkingSeenAcrossTheRoadHidesTheRoadUnderIt) {
  const exacity::City city = flat_city_of("marking-edge", kPark + ", " + river_sketch::highway("[-20, 100], [220, 100]"));
  const double line = 100, half = 0.075;  // the centre line's middle and half width
  Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  const Camera view = scene.to_scene(Camera::look({100, static_cast<float>(line - 15), 1.7f},
                                                  {100, static_cast<float>(line), 0.12f}, 1));
  const int size = 32;
  int marking = 0, beside = 0;
  for_each_pixel_seen(scene, sky, view, size, [&](int x, int y, std::uint32_t, double at, double z) {
    if (z > exacity::kRoadOverTerrain + 0.005) {
      ++marking;
      return;
    }
    ++beside;
    EXPECT_GE(std::abs(at - line), half - 1e-3) << "pixel " << x << ", " << y << " sees the road "
                                                << std::abs(at - line) << " m from the line's middle";
  });
  EXPECT_GT(marking, size * 2);
  EXPECT_GT(beside, size * 4);
}

// A river leaving the map runs on past its edge, where the terrain is the map mirrored and
// sinking to the plane: level water over the river's width, land beside it, no bank
// across it at the map's edge (y 200), and water on over the plane past the fade (100 m).
// It ended in a bank along the map's edge, the land going on.
TEST(GroundRender, ARiverAtTheMapsEdgeRunsOnPastIt) {
  const exacity::City city = city_on("river-on", straight_river, kPark);
  ASSERT_EQ(city.ground.water.size(), 1u);
  Sky sky(200, 40);
  SceneOptions bare_ground;
  bare_ground.landscape_trees = false;
  RenderScene scene(city, sky.sun_direction(), bare_ground);
  const TopView t = look_down(scene, {40, 190, 160, 430}, 60, 120);  // 2 m a pixel
  const double level = exacity::water_level(city.ground.water[0], city.heightmap()) + 0.05;
  int water = 0;
  for (std::size_t i = 0; i < t.id.size(); ++i) {
    const geom::Vec2 p = t.at[i];
    if (p.x > 89 && p.x < 111) {  // the river's middle, clear of its banks
      EXPECT_EQ(kind(t.id[i]), Entity::Water) << "at " << p.x << ", " << p.y;
      if (p.y < 240) {  // then rising over 50 m to the sheet over the plane
        EXPECT_NEAR(t.z[i], level, 1e-3) << "at " << p.x << ", " << p.y;
      }
      ++water;
    } else if (p.x < 70 || p.x > 130) {
      EXPECT_NE(kind(t.id[i]), Entity::Water) << "at " << p.x << ", " << p.y;
    }
  }
  EXPECT_GT(water, 10 * 120);
  // Looking down the river from a metre over it, no ray meets land where the water drawn
  // with the terrain gives way to the sheet over the plane, 0.8 m higher here (the land's
  // lowest height): under that sheet's edge the rays met the land there, a dark line.
  for (double slope : {0.005, 0.01, 0.02, 0.04}) {
    Surface hit;
    ASSERT_TRUE(scene.intersect(scene.to_scene(100, 230, level + 1), normalize(V3{0, 1, static_cast<float>(-slope)}),
                                INFINITY, hit));
    EXPECT_EQ(kind(hit.entity), Entity::Water) << "slope " << slope << " met y " << hit.position.y + scene.origin_y;
  }
}

// A highway drawn past the city's ground (a park x 0 to 200, the road to x 220) runs on
// straight into the land beyond, far into it, as a road with its lines, grass either side
// and no tree on it. It ended 20 m past the park, in a field.
TEST(GroundRender, ADrawnRoadLeavingTheCityRunsOnIntoTheLand) {
  const exacity::City city =
      flat_city_of("road-on", kPark + ", " + river_sketch::highway("[-20, 100], [220, 100]", 16));
  Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  auto down = [&](double x, double y) {
    Surface hit;
    EXPECT_TRUE(scene.intersect(scene.to_scene(x, y, 200), {0, 0, -1}, INFINITY, hit)) << x << ", " << y;
    return hit;
  };
  for (double x : {230.0, 400.0, 1000.0, 3000.0, 10000.0, 25000.0, -500.0, -20000.0}) {
    for (double y : {93.0, 100.0, 107.0}) {
      const Surface hit = down(x, y);
      EXPECT_EQ(kind(hit.entity), Entity::Road) << "at " << x << ", " << y;
      EXPECT_NEAR(hit.position.z, exacity::kRoadOverTerrain, 0.03) << "at " << x << ", " << y;
    }
    for (double y : {80.0, 120.0}) EXPECT_NE(kind(down(x, y).entity), Entity::Road) << "at " << x << ", " << y;
  }
}

// A road carried on past the city stops 20 m short of where it would come back onto the
// city's ground: a second park 300 m on along it keeps its grass, the road running up to
// it and no further.
TEST(GroundRender, ARoadRunningOnStopsShortOfTheCitysGroundAhead) {
  const std::string ahead = R"({"type": "Feature", "properties": {"zone": "park"},
    "geometry": {"type": "Polygon", "coordinates": [[[500, 0], [700, 0], [700, 200], [500, 200], [500, 0]]]}})";
  const exacity::City city =
      flat_city_of("road-back", kPark + ", " + ahead + ", " + river_sketch::highway("[-20, 100], [220, 100]", 16));
  Sky sky(200, 40);
  SceneOptions bare_ground;
  bare_ground.landscape_trees = false;
  RenderScene scene(city, sky.sun_direction(), bare_ground);
  auto down = [&](double x) {
    Surface hit;
    EXPECT_TRUE(scene.intersect(scene.to_scene(x, 100, 200), {0, 0, -1}, INFINITY, hit)) << x;
    return kind(hit.entity);
  };
  EXPECT_EQ(down(300), Entity::Road);
  EXPECT_EQ(down(470), Entity::Road);
  EXPECT_NE(down(490), Entity::Road);
  EXPECT_NE(down(600), Entity::Road);
  EXPECT_NE(down(2000), Entity::Road);
}
