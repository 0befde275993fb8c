// Depth of field (a thin lens, its plane in focus tilted or not) and the cameras
// that stand on the city's ground (render/README.md, Cameras): a pedestrian walking a road
// at eye height over a heightmap, a flyer at a height over it, and their bad specs.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <fstream>

#include "generate/pipeline.h"
#include "render/camera_path.h"
#include "render/camera_spec.h"
#include "render/path_tracer.h"
#include "render/scene.h"
#include "render/sky.h"
#include "tests/test_util.h"

using namespace render;
namespace fs = std::filesystem;

namespace {

// Where the ray (o, d) crosses the plane dot(n, p) = offset.
V3 crossing(V3 o, V3 d, V3 n, float offset) { return o + d * ((offset - dot(n, o)) / dot(n, d)); }

// A rectangle in the plane y = depth, x from x0 to x1, z from z0 to z1.
TriangleSoup wall(float depth, float x0, float x1, float z0, float z1, float albedo) {
  TriangleSoup w;
  w.vertices = {{x0, depth, z0}, {x1, depth, z0}, {x1, depth, z1}, {x0, depth, z1}};
  w.triangles = {{0, 1, 2}, {0, 2, 3}};
  w.material = {Material::Diffuse, {albedo, albedo, albedo}};
  return w;
}

// A small city on a heightmap: a 32 x 24 slope with a bump, 20 to 70 m, a residential zone
// grown over it and a highway across.
exacity::City hill_city() {
  const fs::path dir = testing_util::temp_dir("camera-hill");
  const int w = 32, h = 24;
  std::vector<std::uint16_t> pixels;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double bump = std::exp(-((x - 20.0) * (x - 20.0) + (y - 10.0) * (y - 10.0)) / 40.0);
      pixels.push_back(static_cast<std::uint16_t>(65535 * (0.1 + 0.5 * x / w + 0.4 * bump)));
    }
  auto out = OIIO::ImageOutput::create((dir / "hill.png").string());
  out->open((dir / "hill.png").string(), OIIO::ImageSpec(w, h, 1, OIIO::TypeDesc::UINT16));
  out->write_image(OIIO::TypeDesc::UINT16, pixels.data());
  out->close();
  const std::string text = R"({"type": "FeatureCollection", "exacity": {"seed": 11,
      "terrain": {"heightmap": "hill.png", "bounds": [0, 0, 480, 360], "height": [0, 100]}}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [480, 0], [480, 360], [0, 360], [0, 0]]]}},
    {"type": "Feature", "properties": {"road": "highway", "width": 16},
     "geometry": {"type": "LineString", "coordinates": [[-20, 40], [200, 170], [500, 230]]}}]})";
  std::ofstream(dir / "hill.geojson") << text;
  exacity::Sketch sketch = exacity::parse_sketch(text, dir / "hill.geojson");
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  return exacity::build_city(sketch, clock);
}

// The distance from p to the polyline, in plan.
double distance_to_line(const geom::Polyline& line, double x, double y) {
  double best = INFINITY;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const double ax = line[i].x, ay = line[i].y, dx = line[i + 1].x - ax, dy = line[i + 1].y - ay;
    const double len2 = dx * dx + dy * dy;
    const double s = len2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(x - ax - s * dx, y - ay - s * dy));
  }
  return best;
}

double length_of(const geom::Polyline& line) {
  double len = 0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    len += std::hypot(line[i + 1].x - line[i].x, line[i + 1].y - line[i].y);
  return len;
}

}  // namespace

TEST(DepthOfField, APixelsRaysMeetOnThePlaneInFocusAndSpreadByTheCircleOfConfusion) {
  Camera c = Camera::look({0, 0, 0}, {0, 10, 0}, 40);
  c.depth_of_field.aperture = 0.6f;  // focus: 10 m, the target
  const Lens lens(c, 64, 48);
  const V3 f = c.forward();
  for (auto [px, py] : {std::pair{32.0f, 24.0f}, std::pair{5.5f, 40.25f}}) {
    V3 o0, d0;
    lens.ray(px, py, o0, d0);
    const V3 sharp = crossing(o0, d0, f, 10);
    double spread_at_focus = 0, spread_far = 0;
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j) {
        V3 o, d;
        lens.ray(px, py, i / 16.0f, j / 16.0f, o, d);
        EXPECT_LE(length(o - o0), 0.3f + 1e-5f);  // on the lens, 0.6 m across
        spread_at_focus = std::max<double>(spread_at_focus, length(crossing(o, d, f, 10) - sharp));
        // 20 m away, twice the focus: the circle of confusion's radius is the lens's
        // radius times |1 - 20 / 10| = 0.3 m about the centre's ray.
        spread_far = std::max<double>(spread_far, length(crossing(o, d, f, 20) - crossing(o0, d0, f, 20)));
      }
    EXPECT_LT(spread_at_focus, 1e-4) << px;
    EXPECT_NEAR(spread_far, 0.3, 1e-3) << px;  // the grid reaches the lens's rim (u = 0)
  }
  // No aperture: every lens point gives the pinhole's ray.
  const Lens pinhole(Camera::look({0, 0, 0}, {0, 10, 0}, 40), 64, 48);
  V3 o, d, o1, d1;
  pinhole.ray(7, 9, o, d);
  pinhole.ray(7, 9, 0.9f, 0.1f, o1, d1);
  EXPECT_EQ(length(o1 - o), 0);
  EXPECT_EQ(length(d1 - d), 0);
}

TEST(DepthOfField, ATiltOfNinetyLessTheViewsAngleDownPutsTheGroundInFocus) {
  // 100 m up looking 30 degrees down: tilted by 60 degrees, the plane in focus is z = 0,
  // so every ray of a pixel meets the ground where its centre's ray does, near or far.
  Camera c = Camera::look({0, 0, 100}, {0, 100 / std::tan(30 * kPi / 180), 0}, 40);
  c.depth_of_field = {4, 0, 60};
  const Lens lens(c, 64, 48);
  for (auto [px, py] : {std::pair{32.0f, 47.5f}, std::pair{3.0f, 30.0f}, std::pair{60.0f, 2.0f}}) {
    V3 o0, d0;
    lens.ray(px, py, o0, d0);
    const V3 ground = crossing(o0, d0, {0, 0, 1}, 0);
    for (float u : {0.0f, 0.3f, 0.99f})
      for (float v : {0.0f, 0.5f, 0.8f}) {
        V3 o, d;
        lens.ray(px, py, u, v, o, d);
        EXPECT_LT(length(crossing(o, d, {0, 0, 1}, 0) - ground), 2e-5f * length(ground - o0)) << px << " " << py;
      }
  }
  // Untilted, the far ground is out of focus: the rays part there.
  c.depth_of_field.focus_tilt = 0;
  const Lens flat(c, 64, 48);
  V3 o0, d0, o, d;
  flat.ray(32, 2, o0, d0);
  flat.ray(32, 2, 0, 0.5f, o, d);
  EXPECT_GT(length(crossing(o, d, {0, 0, 1}, 0) - crossing(o0, d0, {0, 0, 1}, 0)), 1.0f);
}

TEST(DepthOfField, AnEdgeInFocusStaysSharpWhileOneNearerBlursAsTheLensPredicts) {
  // White walls left of x = 0: the upper one at the focus distance (10 m), the lower one
  // at 5 m; black far behind. The albedo each pixel's samples saw: at the focus every
  // sample of a pixel lands in its own footprint, so only the edge's pixels may be grey; at
  // 5 m the blur's diameter is 0.6 m x |1 - 5/10| = 0.3 m, 4 pixels of the 3.64 m the
  // image spans there.
  const RenderScene scene(
      {wall(10, -100, 0, 0, 100, 1), wall(5, -100, 0, -100, -0.01f, 1), wall(1000, -4000, 4000, -4000, 4000, 0)});
  const Sky sky(200, 40, 3);
  const int w = 64, h = 48;
  Camera c = Camera::look({0, 0, 0}, {0, 10, 0}, 40);
  auto albedo_at = [&](const Image& img, int x, int y) {
    return img.mean_albedo[static_cast<std::size_t>(y) * w + x].x;
  };
  for (float aperture : {0.0f, 0.6f}) {
    c.depth_of_field.aperture = aperture;
    const Image img = trace(scene, sky, c, TraceSettings{w, h, 64, 1});
    for (int y : {4, 12}) {  // the wall in focus
      for (int x = 0; x <= 30; ++x) EXPECT_EQ(albedo_at(img, x, y), 1) << aperture << " " << x << " " << y;
      for (int x = 33; x < w; ++x) EXPECT_EQ(albedo_at(img, x, y), 0) << aperture << " " << x << " " << y;
    }
    for (int y : {36, 44}) {  // the nearer wall
      for (int x = 0; x <= 27; ++x) EXPECT_EQ(albedo_at(img, x, y), 1) << aperture << " " << x << " " << y;
      for (int x = 36; x < w; ++x) EXPECT_EQ(albedo_at(img, x, y), 0) << aperture << " " << x << " " << y;
      if (aperture == 0) {
        EXPECT_EQ(albedo_at(img, 30, y), 1);
        EXPECT_EQ(albedo_at(img, 33, y), 0);
      } else {
        // Within a pixel of the edge the lens mixes both sides, about a third of the other.
        for (int x : {31, 32}) {
          EXPECT_GT(albedo_at(img, x, y), 0.15) << x << " " << y;
          EXPECT_LT(albedo_at(img, x, y), 0.85) << x << " " << y;
        }
      }
    }
  }
}

TEST(DepthOfField, ImagesAreTheSameBytesWhateverTheThreadCount) {
  const RenderScene scene({wall(10, -100, 0, -100, 100, 0.8f), wall(30, -400, 400, -400, 400, 0.3f)});
  const Sky sky(200, 40, 3);
  Camera c = Camera::look({0, 0, 0}, {0, 10, 0}, 40);
  c.depth_of_field = {0.5f, 0, 15};
  auto bytes = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const Image img = trace(scene, sky, c, TraceSettings{40, 30, 8});
    return std::string(reinterpret_cast<const char*>(img.beauty.data()), img.beauty.size() * sizeof(V3));
  };
  EXPECT_TRUE(bytes(1) == bytes(2));
}

TEST(GroundCameras, APedestrianWalksItsRoadAtEyeHeightOverTheTerrainEveryFrame) {
  const exacity::City city = hill_city();
  ASSERT_NE(city.heightmap(), nullptr);
  // The longest centre line, walked end to end, then off to a point by the bump.
  const auto& roads = city.ground.roads;
  std::size_t road = 0;
  for (std::size_t i = 0; i < roads.size(); ++i)
    if (length_of(roads[i].line) > length_of(roads[road].line)) road = i;
  const double length = length_of(roads[road].line);
  ASSERT_GT(length, 100);
  const std::string r = std::to_string(road), end = std::to_string(length);
  CameraPath path = parse_camera_path(R"({"fps": 4, "keys": [
      {"t": 0, "camera": "pedestrian:road=)" +
                                          r + R"(,along=0"},
      {"t": 3, "camera": "pedestrian:road=)" +
                                          r + R"(,along=)" + end + R"(,ahead=15,eye=1.75"},
      {"t": 5, "camera": "pedestrian:at=240,120,heading=30"}]})",
                                      "walk.json", 50);
  path.place(city, "walk.json");
  const SceneOptions whole;
  const RenderScene scene(city, Sky(200, 40, 3).sun_direction(), whole);
  const exacity::Terrain& terrain = *city.heightmap();
  double lowest = INFINITY, highest = -INFINITY;
  ASSERT_EQ(path.frame_count(), 21);
  for (int n = 0; n < path.frame_count(); ++n) {
    const Camera c = path.frame(n);
    const double over = c.from.z - terrain.height_at({c.from.x, c.from.y});
    EXPECT_GE(over, 1.6) << n;
    EXPECT_LE(over, 1.8) << n;
    lowest = std::min<double>(lowest, c.from.z), highest = std::max<double>(highest, c.from.z);
    // It looks ahead, level with the ground it walks.
    EXPECT_LT(std::abs(c.forward().z), 0.5) << n;
    if (n > 12) continue;  // past the road's end (3 s), towards the point
    EXPECT_LT(distance_to_line(roads[road].line, c.from.x, c.from.y), 1e-3) << n;
    // Straight down from the eye: the road's surface, an eye's height under it.
    Surface hit;
    ASSERT_TRUE(scene.intersect(scene.to_scene(c.from.x, c.from.y, c.from.z), {0, 0, -1}, INFINITY, hit)) << n;
    EXPECT_EQ(hit.entity >> 24, static_cast<std::uint32_t>(Entity::Road)) << n;
    EXPECT_NEAR(hit.distance, over - 0.1, 0.05) << n;  // road surfaces lie 0.1 m over the terrain
  }
  EXPECT_GT(highest - lowest, 10) << "the walk goes up and down the hill";
  const Camera last = path.frame(20);
  EXPECT_NEAR(last.from.x, 240, 1e-3);
  EXPECT_NEAR(last.from.z - terrain.height_at({240, 120}), 1.7, 1e-3);
}

TEST(GroundCameras, AFlyerKeepsItsHeightOverTheTerrainAndItsHeading) {
  const exacity::City city = hill_city();
  const exacity::Terrain& terrain = *city.heightmap();
  const Camera c = place_camera(parse_camera_spec("flyer:at=300,150,height=40,heading=90,pitch=-20", 45), city);
  EXPECT_NEAR(c.from.z - terrain.height_at({300, 150}), 40, 1e-3);
  EXPECT_NEAR(c.forward().x, 0, 1e-5);
  EXPECT_NEAR(c.forward().y, std::cos(20 * kPi / 180), 1e-5);
  EXPECT_NEAR(c.forward().z, -std::sin(20 * kPi / 180), 1e-5);
  // Flown between two flyer keys over the hill, it stays 40 m up all the way.
  CameraPath path = parse_camera_path(R"({"fps": 10, "keys": [
      {"t": 0, "camera": "flyer:at=20,180,height=40,heading=0"},
      {"t": 2, "camera": "flyer:at=460,180,height=40,heading=0"}]})",
                                      "fly.json", 45);
  path.place(city, "fly.json");
  for (int n = 0; n < path.frame_count(); ++n) {
    const Camera f = path.frame(n);
    EXPECT_NEAR(f.from.z - terrain.height_at({f.from.x, f.from.y}), 40, 1e-3) << n;
  }
}

TEST(GroundCameras, BetweenAnAirKeyAndAGroundKeyTheEyeKeepsOverTheTerrain) {
  // From low in the air west of the hill, straight up its slope to a pedestrian by the
  // bump: a line between the two eyes runs through the hill. The eye's height over the
  // terrain goes from the one key's to the other's instead, never under either.
  const exacity::City city = hill_city();
  const exacity::Terrain& terrain = *city.heightmap();
  CameraPath path = parse_camera_path(R"({"fps": 10, "keys": [
      {"t": 0, "camera": "look:from=0,150,30,to=300,150,60"},
      {"t": 4, "camera": "pedestrian:at=300,150,heading=0"},
      {"t": 6, "camera": "look:from=470,150,120,to=300,150,60"}]})",
                                      "descend.json", 45);
  path.place(city, "descend.json");
  auto over = [&](const Camera& c) { return c.from.z - terrain.height_at({c.from.x, c.from.y}); };
  const double first = over(path.frame(0)), last = over(path.frame(60));
  ASSERT_GT(first, 1.7);
  ASSERT_GT(last, 1.7);
  double before = first;
  for (int n = 1; n <= 40; ++n) {  // down to the pedestrian: ever lower over the ground
    const double h = over(path.frame(n));
    EXPECT_LE(h, before + 1e-3) << n;
    EXPECT_GE(h, 1.7 - 1e-3) << n;
    before = h;
  }
  EXPECT_NEAR(before, 1.7, 1e-3);
  for (int n = 41; n <= 60; ++n) {  // and up again
    const double h = over(path.frame(n));
    EXPECT_GE(h, before - 1e-3) << n;
    EXPECT_LE(h, last + 1e-3) << n;
    before = h;
  }
}

TEST(GroundCameras, BadSpecsSayWhatIsWrong) {
  const std::pair<const char*, const char*> cases[] = {
      {"pedestrian:road=-1,along=0", "road=-1"},
      {"pedestrian:road=1.5,along=0", "is not a road id"},
      {"pedestrian:road=2", "missing along="},
      {"pedestrian:road=2,along=5,ahead=0", "ahead="},
      {"pedestrian:road=2,along=5,speed=3", "unknown key speed="},
      {"pedestrian:at=0,0,heading=0,eye=0", "eye="},
      {"pedestrian:at=0,heading=0", "at needs 2 numbers"},
      {"flyer:at=0,0,height=10", "missing heading="},
      {"flyer:at=0,0,height=10,heading=0,pitch=95", "pitch="},
      {"flyer:at=0,0,height=-5,heading=0", "height="},
      {"orbit:target=nan,0,0,azimuth=0,elevation=30,distance=10", "\"nan\" is not a number"},
      // Each made a ray Embree aborts on (exit 134).
      {"orbit:target=0,0,0,azimuth=0,elevation=30,distance=1e30", "distance=1e30 is outside -1e9 to 1e9"},
      {"orbit:target=0,0,0,azimuth=0,elevation=30,distance=1e-30", "distance= must be at least 0.01"},
      {"look:from=0,0,1e-30,to=0,0,0", "under 0.01 m apart"},
      {"walker:at=0,0", "unknown camera \"walker\""},
      {"pedestrian", "expected KIND:KEY=VALUE"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      parse_camera_spec(text, 45);
      ADD_FAILURE() << text << " parsed";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << text << ": " << e.what();
    }
  }
  // The bounds themselves are in range, though the spec's numbers are floats.
  for (const char* text : {"pedestrian:at=0,0,heading=0,pitch=89.9,eye=0.1", "flyer:at=0,0,height=0.1,heading=0,pitch=-89.9"})
    EXPECT_NO_THROW(parse_camera_spec(text, 45)) << text;
  const exacity::City city = hill_city();
  try {
    place_camera(parse_camera_spec("pedestrian:road=99999,along=0", 45), city);
    ADD_FAILURE() << "road 99999 placed";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the city has no road 99999"), std::string::npos) << e.what();
  }
}
