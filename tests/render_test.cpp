// The renderer against analytic answers: a white furnace, energy conservation, a sun-lit
// plane; cameras, the overview height and the minimap's ground footprint by hand; images
// independent of the thread count; packets of rays as single rays; the EXR's data layers read back exactly; what the
// overview and the minimap show.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include <OpenImageIO/imageio.h>
#include <tbb/global_control.h>

#include "generate/city/palette.h"
#include "generate/errors.h"
#include "generate/pipeline.h"
#include "geom/measure.h"
#include "render/camera.h"
#include "render/embree_device.h"
#include "render/image_io.h"
#include "render/material.h"
#include "render/night.h"
#include "render/path_tracer.h"
#include "render/render.h"
#include "render/sampling.h"
#include "render/scene.h"
#include "render/sky.h"
#include "tests/test_util.h"

using namespace render;

namespace {

// A closed box, [-s, s]^3, as twelve triangles.
TriangleSoup box(float s, Material m) {
  TriangleSoup b;
  for (int i = 0; i < 8; ++i) b.vertices.push_back({i & 1 ? s : -s, i & 2 ? s : -s, i & 4 ? s : -s});
  b.triangles = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                 {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  b.material = m;
  return b;
}

// The ground, z = 0, from -s to s each way.
TriangleSoup ground_plane(float s, Material m) {
  TriangleSoup plane;
  plane.vertices = {{-s, -s, 0}, {s, -s, 0}, {s, s, 0}, {-s, s, 0}};
  plane.triangles = {{0, 1, 2}, {0, 2, 3}};
  plane.material = m;
  return plane;
}

double mean_luminance(const Image& img) {
  double sum = 0;
  for (V3 c : img.beauty) sum += (c.x + c.y + c.z) / 3;
  return sum / static_cast<double>(img.beauty.size());
}

// The mean radiance seen inside a closed box whose every wall emits 1 and reflects 80%,
// the sun and sky off: L = 1 / (1 - 0.8) = 5.
double furnace(Haze haze) {
  Material white{Material::Diffuse, {0.8f, 0.8f, 0.8f}};
  white.emission = {1, 1, 1};
  RenderScene scene({box(10, white)});
  Sky off(0, 45, 3, 0, 0);
  Camera c = Camera::look({0, 0, 0}, {1, 0.3f, 0.2f}, 90);
  return mean_luminance(trace(scene, off, c, TraceSettings{16, 16, 256, 100000, haze}));
}

// A city of one zone: a width x height rectangle at the origin.
exacity::City one_zone_city(const std::string& zone, int width, int height, int seed) {
  const std::string text = R"({"type": "FeatureCollection", "exacity": {"seed": )" + std::to_string(seed) +
                           R"(}, "features": [{"type": "Feature", "properties": {"zone": ")" + zone +
                           R"("}, "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [)" + std::to_string(width) +
                           ", 0], [" + std::to_string(width) + ", " + std::to_string(height) + "], [0, " +
                           std::to_string(height) + "], [0, 0]]]}}]}";
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  return exacity::build_city(exacity::parse_sketch(text, zone + ".geojson"), clock);
}

}  // namespace

TEST(Render, WhiteFurnaceGivesEmissionOverOneMinusAlbedo) { EXPECT_NEAR(furnace({}), 5.0, 5.0 * 0.02); }

TEST(Render, HazeInTheFurnaceChangesNothing) {
  // A medium that scatters and absorbs nothing leaves a uniform radiance field as it is;
  // five metres between scatterings on average.
  EXPECT_NEAR(furnace({0.2f, 100, 0.7f}), 5.0, 5.0 * 0.02);
}

// Haze of 1500 m visibility over a sunlit plane, the sky seen through it at 16 samples,
// across the sun's direction: each sky pixel's mean is nearer its truth. The sun reached
// the haze only at the points where rays scattered (with weight one, drawn nearest the
// ground, where it is dimmest), and a ray either saw the sky or scattered: a grain of
// pixels that did and pixels that did not (a mean relative error of 0.236 here; 0.195
// with the sun sought along every ray and the sky seen through the haze as well as
// scattered; the light scattered many times is what is left).
TEST(Render, HazySkyIsLessGrainyAtAFewSamples) {
  RenderScene scene({ground_plane(20000, {Material::Diffuse, {0.3f, 0.3f, 0.3f}})});
  const Sky sky(200, 30);
  const Haze haze{Haze::density_for_visibility(1500), 500, 0.7f};
  // At right angles to the sun, from the horizon up to 40 degrees.
  const Camera c = Camera::look({0, 0, 2}, {-34, 94, 40}, 40);
  const Image img = trace(scene, sky, c, TraceSettings{32, 16, 16, 8, haze});
  double spread = 0;
  int sky_pixels = 0;
  for (std::size_t i = 0; i < img.beauty.size() / 2; ++i) {  // the upper half, clear of the horizon
    if (std::isfinite(img.depth[i])) continue;
    spread += std::sqrt(img.variance[i]) / luminance(img.beauty[i]);
    ++sky_pixels;
  }
  ASSERT_EQ(sky_pixels, 32 * 8);
  EXPECT_LT(spread / sky_pixels, 0.215) << "the sky pixels' mean relative standard deviation";
}

TEST(Render, HenyeyGreensteinSamplesItsOwnDensity) {
  for (float g : {0.0f, 0.7f, -0.4f}) {
    // Its mean cosine is g, and the density integrates to one.
    Sampler rng(3, 4);
    double mean = 0, integral = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      mean += dot(sample_henyey_greenstein({0, 0, 1}, g, rng.next(), rng.next()), V3{0, 0, 1});
      integral += henyey_greenstein(1 - 2 * rng.next(), g) * 4 * kPi;
    }
    EXPECT_NEAR(mean / n, g, 0.01) << g;
    EXPECT_NEAR(integral / n, 1.0, 0.03) << g;
  }
}

TEST(Render, EveryMaterialConservesEnergyAndSamplesWhatItEvaluates) {
  const std::vector<Material> materials{{Material::Diffuse, {1, 1, 1}},
                                        {Material::Glossy, {1, 1, 1}, 0.05f, 1.5f},
                                        {Material::Glossy, {1, 1, 1}, 0.3f, 1.5f},
                                        {Material::Glossy, {0.5f, 0.5f, 0.5f}, 0.6f, 1.33f},
                                        {Material::Glossy, {0.02f, 0.06f, 0.08f}, 0.02f, 1.33f}};
  for (const Material& m : materials)
    for (float cos_o : {0.95f, 0.6f, 0.2f}) {
      const V3 wo{std::sqrt(1 - cos_o * cos_o), 0, cos_o};
      // The reflected fraction two ways: uniform directions (eval alone), and the
      // material's own sampling (its weights).
      double uniform = 0, sampled = 0;
      const int n = 400000;
      Sampler rng(7, static_cast<std::uint64_t>(cos_o * 100));
      for (int i = 0; i < n; ++i) {
        float u1 = rng.next(), u2 = rng.next();
        float z = u1, r = std::sqrt(1 - z * z), phi = 2 * kPi * u2;
        uniform += eval(m, wo, {r * std::cos(phi), r * std::sin(phi), z}).x * 2 * kPi;
        BsdfSample s;
        if (sample(m, wo, rng.next(), rng.next(), rng.next(), s)) sampled += s.weight.x;
      }
      uniform /= n, sampled /= n;
      EXPECT_LE(sampled, 1.0 + 0.01) << m.kind << " roughness " << m.roughness << " cos " << cos_o;
      // Uniform directions rarely find a sharp lobe: compare where the lobe is wide.
      if (m.kind == Material::Diffuse || m.roughness >= 0.3f) {
        EXPECT_NEAR(sampled, uniform, 0.03 * std::max(uniform, 0.05)) << m.kind << " roughness " << m.roughness;
      }
    }
}

TEST(Render, SunLitPlaneMatchesItsIrradiance) {
  // A white-ish plane under the sun alone: L = albedo / pi * E_sun * sin(elevation).
  RenderScene scene({ground_plane(5000, {Material::Diffuse, {0.5f, 0.5f, 0.5f}})});
  for (float elevation : {30.0f, 60.0f}) {
    Sky sun_only(100, elevation, 3, 0, 1);
    Camera c = Camera::look({0, 0, 50}, {0, 20, 0}, 40);
    Image img = trace(scene, sun_only, c, TraceSettings{16, 16, 16, 4});
    const V3 e = sun_only.sun_irradiance();
    const float sin_el = std::sin(elevation * kPi / 180);
    for (const V3& px : img.beauty) {
      EXPECT_NEAR(px.x, 0.5f / kPi * e.x * sin_el, 0.01f * 0.5f / kPi * e.x * sin_el);
      EXPECT_NEAR(px.z, 0.5f / kPi * e.z * sin_el, 0.01f * 0.5f / kPi * e.z * sin_el);
    }
  }
}

TEST(Render, SkyTableFollowsThePreethamModel) {
  Sky sky(200, 35, 3);
  Sampler rng(1, 2);
  for (int i = 0; i < 2000; ++i) {
    V3 d = cosine_hemisphere(rng.next(), rng.next());
    if (d.z < 0.02f) continue;
    V3 a = sky.radiance(d), b = sky.model_radiance(d);
    EXPECT_NEAR(a.y, b.y, 0.03f * b.y + 1e-3f) << d.x << " " << d.y << " " << d.z;
  }
  // Brighter towards the sun than away from it, bluer at the zenith than near the horizon.
  const V3 s = sky.sun_direction();
  EXPECT_GT(luminance(sky.model_radiance(normalize(s + V3{0, 0, 0.2f}))), luminance(sky.model_radiance(normalize(V3{-s.x, -s.y, 0.3f}))));
  const V3 zenith = sky.model_radiance({0, 0, 1});
  EXPECT_GT(zenith.z / zenith.x, 1.0f);
}

TEST(Camera, OverviewHeightSeesTheWholeMap) {
  geom::Box city{0, 0, 1000, 600};
  EXPECT_NEAR(overview_height(city, 60, 1), 1000 / (2 * std::tan(kPi / 6)), 1e-3);  // the width decides
  EXPECT_NEAR(overview_height(city, 60, 2), 600 / (2 * std::tan(kPi / 6)), 1e-3);   // the height decides
  Camera c = overview_camera(city, 20, 60, 1, false);
  EXPECT_NEAR(c.from.z, 20 + 866.0254f, 1e-2);
  // Its corner rays land on the map's corners (the width fills the image).
  auto quad = ground_footprint(c, 100, 100, 20, {-1e4, -1e4, 1e4, 1e4});
  EXPECT_NEAR(quad[0].x, 0, 1e-2);
  EXPECT_NEAR(quad[1].x, 1000, 1e-2);
}

TEST(Camera, GroundFootprintByHand) {
  // Straight down from 100 m with a 90 degree view: a 200 m square, north up.
  Camera down = Camera::look({0, 0, 100}, {0, 0, 0}, 90);
  auto q = ground_footprint(down, 100, 100, 0, {-1e4, -1e4, 1e4, 1e4});
  const std::vector<geom::Vec2> expect{{-100, -100}, {100, -100}, {100, 100}, {-100, 100}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(q[i].x, expect[i].x, 1e-3) << i;
    EXPECT_NEAR(q[i].y, expect[i].y, 1e-3) << i;
  }
  // Level, 10 m up, looking north with 60 degrees: the upper rays never reach the ground,
  // so the lower rays are followed on to the bounds' north edge.
  Camera level = Camera::look({0, 0, 10}, {0, 100, 10}, 60);
  q = ground_footprint(level, 100, 100, 0, {-1000, -1000, 1000, 1000});
  const double t = std::tan(kPi / 6), near_y = 10 / t;
  EXPECT_NEAR(q[0].x, -10, 1e-3);
  EXPECT_NEAR(q[0].y, near_y, 1e-3);
  EXPECT_NEAR(q[1].x, 10, 1e-3);
  EXPECT_NEAR(q[3].y, 1000, 1e-3);
  EXPECT_NEAR(q[3].x, -10 - t * (1000 - near_y), 1e-2);
  EXPECT_NEAR(q[2].x, 10 + t * (1000 - near_y), 1e-2);
}

TEST(Camera, OrbitStaysAboveTheGroundAndSpecsParse) {
  Camera c = Camera::parse("orbit:target=10,20,0,azimuth=90,elevation=-30,distance=100", 50);
  EXPECT_GT(c.from.z, 0);  // elevation kept to the upper hemisphere
  EXPECT_NEAR(c.to.x, 10, 1e-6);
  c = Camera::parse("orbit:target=0,0,0,azimuth=0,elevation=90,distance=100", 50);
  EXPECT_NEAR(c.from.z, 100, 1e-3);
  EXPECT_NEAR(c.right().x, 1, 1e-6);  // straight down: east to the right
  c = Camera::parse("look:from=0,-10,5,to=0,0,0", 40);
  EXPECT_NEAR(c.forward().y, 10 / std::sqrt(125.0f), 1e-6);
  for (const char* bad : {"orbit:target=0,0,azimuth=1,elevation=2,distance=3", "look:from=1,2,3", "pan:x=1",
                          "look:from=0,0,0,to=0,0,0", "orbit:target=a,0,0,azimuth=0,elevation=1,distance=2"})
    EXPECT_THROW(Camera::parse(bad, 50), std::invalid_argument) << bad;
}

// Embree reports an error through the device's error function and carries on; the device
// turns it into one InternalError with Embree's own text.
TEST(Render, EmbreeErrorsBecomeOneInternalErrorWithEmbreesText) {
  render::EmbreeDevice device;
  EXPECT_NO_THROW(device.check("nothing yet"));
  RTCGeometry wrong = rtcNewGeometry(device.get(), static_cast<RTCGeometryType>(999));
  EXPECT_EQ(wrong, nullptr);
  try {
    device.check("a mesh");
    ADD_FAILURE() << "no error";
  } catch (const exacity::InternalError& e) {
    EXPECT_EQ(std::string(e.what()), "Embree: a mesh: unknown error, invalid geometry type");
  }
}

// A buffer Embree cannot make is an InternalError, not a null pointer written to.
TEST(Render, AnEmbreeBufferTooLargeIsAnInternalError) {
  render::EmbreeDevice device;
  RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  try {
    device.new_buffer(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, 3 * sizeof(float), std::size_t(1) << 58);
    ADD_FAILURE() << "no error";
  } catch (const exacity::InternalError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("Embree: a geometry's buffer: invalid argument, buffer too large", 0), 0u) << e.what();
  }
  rtcReleaseGeometry(g);
}

TEST(Render, CityImagesAreTheSameWhateverTheThreadCountAndHitsNameTheirEntity) {
  const exacity::City city = one_zone_city("residential", 400, 300, 3);
  ASSERT_FALSE(city.buildings.empty());
  Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  Camera c = Camera::orbit({0, 0, 0}, 235, 35, 400, 45);
  std::vector<Image> images;
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    images.push_back(trace(scene, sky, c, TraceSettings{48, 32, 4}));
  }
  ASSERT_EQ(images[0].beauty.size(), images[1].beauty.size());
  for (std::size_t i = 0; i < images[0].beauty.size(); ++i) {
    EXPECT_EQ(images[0].beauty[i].x, images[1].beauty[i].x);
    EXPECT_EQ(images[0].id[i], images[1].id[i]);
  }
  // Straight down onto the centre of a building's rectangle (on its ridge): its entity.
  const auto& b = city.buildings[0];
  ASSERT_EQ(b.polygon.outer.size(), 4u);
  geom::Vec2 inside{0, 0};
  for (geom::Vec2 v : b.polygon.outer) inside.x += v.x / 4, inside.y += v.y / 4;
  Surface hit;
  ASSERT_TRUE(scene.intersect(scene.to_scene(inside.x, inside.y, 500), {0, 0, -1}, INFINITY, hit));
  EXPECT_EQ(hit.entity, entity_id(Entity::Building, 0));
  EXPECT_NEAR(hit.position.z, b.floor + b.height, 1e-3);  // flat or the ridge's height at most
}

// A street between offices at eye height, rendered as exacity render does: it reads as
// daylight, not half black. The windows were flat near-black glass and the shaded
// asphalt nearly so at the aerial views' exposure: 32% of the town's street view
// (pedestrian:road=3,along=560) was under 40/255.
TEST(Render, AStreetBetweenOfficesReadsAsDaylight) {
  const int width = 400, height = 300;
  const exacity::City city = one_zone_city("commercial", width, height, 5);
  // The segment of a laid-out street whose middle lies deepest inside the zone.
  geom::Vec2 at{0, 0}, along{1, 0};
  double deepest = 0;
  for (const auto& r : city.ground.roads)
    for (std::size_t i = 0; i + 1 < r.line.size(); ++i) {
      const geom::Vec2 a = r.line[i], b = r.line[i + 1], m = geom::lerp(a, b, 0.5);
      const double depth = std::min({m.x, width - m.x, m.y, height - m.y});
      if (geom::distance(a, b) > 40 && depth > deepest) deepest = depth, at = m, along = geom::unit_along(a, b);
    }
  ASSERT_GT(deepest, 40);
  RenderRequest request;
  request.camera = Camera::look({static_cast<float>(at.x), static_cast<float>(at.y), 1.7f},
                                {static_cast<float>(at.x + along.x * 30), static_cast<float>(at.y + along.y * 30), 1.7f});
  request.width = 160, request.height = 90, request.spp = 4;
  const auto dir = testing_util::temp_dir("street-daylight");
  request.still = dir / "still.png";
  render_city(city, request);
  auto in = OIIO::ImageInput::open(request.still.string());
  ASSERT_TRUE(in);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(request.width) * request.height * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
  int dark = 0;
  for (std::size_t i = 0; i < rgb.size(); i += 3)
    dark += 0.2126 * rgb[i] + 0.7152 * rgb[i + 1] + 0.0722 * rgb[i + 2] < 40;
  EXPECT_LT(dark, request.width * request.height / 10) << "pixels under 40/255";
}

TEST(Render, PacketsFindWhatSingleRaysFind) {
  // Camera rays over a city and past it onto the ground plane, in packets of every size
  // from 1 to 16: each finds the surface intersect() finds, and each shadow ray from those
  // surfaces is blocked exactly when occluded() says so.
  const exacity::City city = one_zone_city("commercial", 300, 200, 5);
  Sky sky(150, 25);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  const Camera c = scene.to_scene(Camera::orbit({150, 100, 0}, 200, 35, 350, 60));
  const Lens lens(c, 64, 48);
  Sampler rng(1, 1);
  int hits = 0, blocked_rays = 0, plane = 0;
  for (int count = 1; count <= RenderScene::kPacket; ++count)
    for (int round = 0; round < 20; ++round) {
      V3 o[RenderScene::kPacket], d[RenderScene::kPacket];
      for (int j = 0; j < count; ++j) {
        const auto [u, v] = rng.next2();
        lens.ray(64 * u, 48 * v, 0.5f, 0.5f, o[j], d[j]);
      }
      Surface found[RenderScene::kPacket];
      bool hit[RenderScene::kPacket];
      scene.intersect_packet(o, d, count, found, hit);
      V3 from[RenderScene::kPacket], towards[RenderScene::kPacket];
      int shadow_rays = 0;
      for (int j = 0; j < count; ++j) {
        Surface one;
        ASSERT_EQ(hit[j], scene.intersect(o[j], d[j], INFINITY, one)) << count << " " << j;
        if (!hit[j]) continue;
        ++hits;
        if (found[j].entity == entity_id(Entity::Terrain, 0)) ++plane;
        EXPECT_EQ(found[j].entity, one.entity);
        EXPECT_NEAR(found[j].distance, one.distance, 1e-4f * one.distance);
        EXPECT_NEAR(dot(found[j].normal, one.normal), 1.0f, 1e-5f);
        EXPECT_EQ(found[j].material.albedo.x, one.material.albedo.x);
        // Towards the sun, or down through the ground (blocked by the plane or the city).
        from[shadow_rays] = found[j].position + found[j].normal * 1e-3f;
        towards[shadow_rays++] = j % 3 == 2 ? normalize(V3{0.3f, -0.2f, -1}) : sky.sun_direction();
      }
      bool blocked[RenderScene::kPacket];
      scene.occluded_packet(from, towards, shadow_rays, blocked);
      for (int q = 0; q < shadow_rays; ++q) {
        EXPECT_EQ(blocked[q], scene.occluded(from[q], towards[q], INFINITY)) << count << " " << q;
        blocked_rays += blocked[q];
      }
    }
  // The rays met the city and the plane, and some shadow rays were blocked, some not.
  EXPECT_GT(hits - plane, 200);
  EXPECT_GT(plane, 20);
  EXPECT_GT(blocked_rays, 50);
  EXPECT_LT(blocked_rays, hits);
}

TEST(Render, PassesAddUpToOneTraceOnACityWithInstances) {
  // As Film.PassesOfSamplesAddUpToOneTraceBitForBit, through Embree's instances (the
  // residential zone's trees and lamps) with packets cut differently by the passes.
  const exacity::City city = one_zone_city("residential", 250, 200, 2);
  Sky sky(200, 35);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  ASSERT_GT(scene.instances, 10u);
  const Camera c = scene.to_scene(Camera::orbit({125, 100, 0}, 210, 30, 120, 50));
  const Image whole = trace(scene, sky, c, TraceSettings{48, 32, 37});
  Film film(48, 32);
  for (int spp : {16, 5, 16}) add_samples(film, scene, sky, c, TraceSettings{48, 32, spp});
  const Image passes = film.image();
  std::size_t models = 0;
  for (std::size_t i = 0; i < whole.beauty.size(); ++i) {
    ASSERT_EQ(whole.beauty[i].x, passes.beauty[i].x) << i;
    ASSERT_EQ(whole.beauty[i].y, passes.beauty[i].y) << i;
    ASSERT_EQ(whole.beauty[i].z, passes.beauty[i].z) << i;
    ASSERT_EQ(whole.variance[i], passes.variance[i]) << i;
    ASSERT_EQ(whole.first_sun[i].x, passes.first_sun[i].x) << i;
    ASSERT_EQ(whole.halves[1].beauty[i].y, passes.halves[1].beauty[i].y) << i;
    const std::uint32_t kind = whole.id[i] >> 24;
    models += kind == static_cast<std::uint32_t>(Entity::Model) || kind == static_cast<std::uint32_t>(Entity::Clutter);
  }
  EXPECT_GT(models, 30u);  // the view sees the instances (trees, lamps, clutter)
}

TEST(Render, ExrKeepsItsDataLayersExactly) {
  Image img;
  img.width = 3, img.height = 2;
  for (int i = 0; i < 6; ++i) {
    img.beauty.push_back({0.5f * i, 1, 2});
    img.depth.push_back(i == 5 ? INFINITY : 10.25f + i);
    img.normal.push_back({0, 0, 1});
    img.albedo.push_back({0.25f, 0.5f, 0.75f});
    img.id.push_back(entity_id(Entity::Building, 1000000 + i));
  }
  auto dir = testing_util::temp_dir("exr");
  write_exr(img, dir / "still.exr");
  auto in = OIIO::ImageInput::open((dir / "still.exr").string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  auto channel = [&](const std::string& name) {
    for (int c = 0; c < spec.nchannels; ++c)
      if (spec.channelnames[c] == name) return c;
    return -1;
  };
  const int id = channel("id"), z = channel("Z"), r = channel("R"), albedo = channel("albedo.G");
  ASSERT_GE(id, 0);
  ASSERT_GE(z, 0);
  EXPECT_EQ(spec.channelformat(id), OIIO::TypeDesc::UINT);
  EXPECT_EQ(spec.channelformat(r), OIIO::TypeDesc::HALF);
  EXPECT_EQ(spec.channelformat(albedo), OIIO::TypeDesc::FLOAT);
  std::vector<std::uint32_t> ids(6);
  std::vector<float> depth(6);
  ASSERT_TRUE(in->read_image(0, 0, id, id + 1, OIIO::TypeDesc::UINT, ids.data()));
  ASSERT_TRUE(in->read_image(0, 0, z, z + 1, OIIO::TypeDesc::FLOAT, depth.data()));
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(ids[i], img.id[i]);
    EXPECT_EQ(depth[i], img.depth[i]);
  }
}

namespace {

struct Png {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  std::array<int, 3> at(int x, int y) const {
    const std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
  // The mean colour of the square of side 2r + 1 around (x, y).
  std::array<double, 3> mean(int x, int y, int r) const {
    std::array<double, 3> sum{0, 0, 0};
    for (int j = y - r; j <= y + r; ++j)
      for (int i = x - r; i <= x + r; ++i)
        for (int c = 0; c < 3; ++c) sum[c] += at(i, j)[c];
    for (double& s : sum) s /= (2 * r + 1) * (2 * r + 1);
    return sum;
  }
};

Png read_png(const std::filesystem::path& file) {
  Png png;
  auto in = OIIO::ImageInput::open(file.string());
  EXPECT_TRUE(in) << file;
  if (!in) return png;
  png.width = in->spec().width, png.height = in->spec().height;
  png.rgb.resize(static_cast<std::size_t>(png.width) * png.height * 3);
  EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, png.rgb.data())) << file;
  return png;
}

}  // namespace

// A park 400 m square with water in its north-east quarter, its still seen straight down
// from 60 m over (150, 150) with a 90 degree view: by hand, the still (96 x 64) sees
// x 60..240 m, y 90..210 m. The overview and the minimap show the whole city north up (the
// water top right); the minimap (256 px over the 400 m) outlines that ground in yellow,
// marks the camera in red, and sits in the still's top-right corner.
TEST(Render, OverviewAndMinimapShowTheCityNorthUpWithTheStillsGroundAndCamera) {
  const std::string text = R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"zone": "park"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [400, 0], [400, 400], [0, 400], [0, 0]]]}},
    {"type": "Feature", "properties": {"zone": "water"},
     "geometry": {"type": "Polygon", "coordinates": [[[200, 200], [400, 200], [400, 400], [200, 400], [200, 200]]]}}]})";
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  const exacity::City city = exacity::build_city(exacity::parse_sketch(text, "quarters.geojson"), clock);
  auto dir = testing_util::temp_dir("render-minimap");
  RenderRequest request;
  request.camera = Camera::look({150, 150, 60}, {150, 150, 0}, 90);
  request.width = 96, request.height = 64, request.spp = 4;
  request.overview = request.minimap = true;
  request.still = dir / "still.png", request.overview_file = dir / "overview.png", request.minimap_file = dir / "minimap.png";
  const nlohmann::ordered_json report = render_city(city, request);

  const std::vector<std::array<double, 2>> seen{{60, 90}, {240, 90}, {240, 210}, {60, 210}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(report["minimap"]["visible_ground"][i][0].get<double>(), seen[i][0], 1e-3) << i;
    EXPECT_NEAR(report["minimap"]["visible_ground"][i][1].get<double>(), seen[i][1], 1e-3) << i;
  }

  // Water blue, park green: quarter by quarter, north up and east right.
  auto water = [](std::array<double, 3> c) { return c[2] > c[1]; };
  const Png overview = read_png(dir / "overview.png"), minimap = read_png(dir / "minimap.png");
  for (const auto& [image, size] : {std::pair{&overview, 96}, std::pair{&minimap, 256}}) {
    ASSERT_EQ(image->width, size);
    ASSERT_EQ(image->height, size);
    const int q = size / 4;  // a quarter's centre is q or 3q in
    EXPECT_TRUE(water(image->mean(3 * q, q, 6))) << size;
    EXPECT_FALSE(water(image->mean(q, q, 6))) << size;
    EXPECT_FALSE(water(image->mean(q, 3 * q, 6))) << size;
    EXPECT_FALSE(water(image->mean(3 * q, 3 * q, 6))) << size;
  }

  // The visible ground at 0.64 px a metre from the centre (128, 128): rows 121.6 and 198.4,
  // columns 38.4 and 153.6; lines 3 px wide.
  const std::array<int, 3> yellow{255, 237, 89}, red{243, 89, 89};  // (1, 0.85, 0.1) and (0.9, 0.1, 0.1) in sRGB
  for (int x = 42; x <= 150; ++x) {
    EXPECT_EQ(minimap.at(x, 122), yellow) << x;
    EXPECT_EQ(minimap.at(x, 198), yellow) << x;
    EXPECT_NE(minimap.at(x, 112), yellow) << x;
    EXPECT_NE(minimap.at(x, 208), yellow) << x;
  }
  for (int y = 126; y <= 194; ++y) {
    EXPECT_EQ(minimap.at(38, y), yellow) << y;
    EXPECT_EQ(minimap.at(154, y), yellow) << y;
    EXPECT_NE(minimap.at(28, y), yellow) << y;
    EXPECT_NE(minimap.at(164, y), yellow) << y;
  }
  // The camera, straight down over (150, 150): a red disc of radius 4 at (96, 160), no heading.
  EXPECT_EQ(minimap.at(96, 160), red);
  EXPECT_EQ(minimap.at(99, 160), red);
  EXPECT_NE(minimap.at(96, 166), red);

  // In the still's top-right corner: 32 px (a third of its height, at least 32), 8 px in,
  // framed in white.
  const Png still = read_png(dir / "still.png");
  ASSERT_EQ(still.width, 96);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) ASSERT_EQ(still.at(56 + x, 8 + y), minimap.at(x * 8, y * 8)) << x << ", " << y;
  for (int k = -2; k < 34; ++k) {
    EXPECT_EQ(still.at(56 + k, 7), (std::array<int, 3>{255, 255, 255})) << k;
    EXPECT_EQ(still.at(55, 8 + k), (std::array<int, 3>{255, 255, 255})) << k;
  }
}

// Zone land no lot covers (gardens, verges, a zone with no street yet) is grass from
// straight above, not paving.
TEST(Render, ZoneLandWithoutLotsIsGreenFromAbove) {
  const std::string text = R"({"type": "FeatureCollection", "exacity": {"zones": {"residential": {"layout": "streets"}}},
    "features": [{"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [400, 0], [400, 400], [0, 400], [0, 0]]]}}]})";
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  const exacity::City city = exacity::build_city(exacity::parse_sketch(text, "garden.geojson"), clock);
  ASSERT_TRUE(city.ground.lots.empty());
  auto dir = testing_util::temp_dir("render-garden");
  RenderRequest request;
  request.camera = Camera::look({200, 200, 300}, {200, 200, 0}, 60);
  request.width = 64, request.height = 64, request.spp = 4;
  request.overview = true;
  request.still = dir / "still.png", request.overview_file = dir / "overview.png";
  render_city(city, request);
  for (const Png& image : {read_png(dir / "still.png"), read_png(dir / "overview.png")}) {
    const std::array<double, 3> c = image.mean(image.width / 2, image.height / 2, 6);
    EXPECT_GT(c[1], c[0]);
    EXPECT_GT(c[1], c[2]);
  }
}

TEST(Texture, SamplesLinearTexelsBilinearlyRepeatingOrClamped) {
  // A 2 x 2 image: red, blue on the top row; black, white below (sRGB 8-bit).
  exacity::TextureImage image;
  image.width = image.height = 2;
  image.rgb = {255, 0, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255};
  const Texture t(image);
  EXPECT_EQ(srgb_to_linear(255), 1.0f);
  EXPECT_EQ(srgb_to_linear(0), 0.0f);
  EXPECT_NEAR(srgb_to_linear(128), 0.2158605f, 1e-6);  // sRGB's curve, not value / 255
  auto expect = [&](float u, float v, bool clamp, V3 want) {
    const V3 got = t.sample(u, v, clamp);
    EXPECT_NEAR(got.x, want.x, 1e-6) << u << "," << v;
    EXPECT_NEAR(got.y, want.y, 1e-6) << u << "," << v;
    EXPECT_NEAR(got.z, want.z, 1e-6) << u << "," << v;
  };
  // Texel centres: v runs up, so the top row is at v = 0.75.
  expect(0.25f, 0.75f, false, {1, 0, 0});
  expect(0.75f, 0.75f, false, {0, 0, 1});
  expect(0.25f, 0.25f, false, {0, 0, 0});
  expect(0.75f, 0.25f, false, {1, 1, 1});
  // Halfway between red and blue: their linear mean.
  expect(0.5f, 0.75f, false, {0.5f, 0, 0.5f});
  // Outside 0..1 the image repeats; at the seam, the first column mixes with the last.
  expect(1.25f, -0.25f, false, {1, 0, 0});
  expect(0.0f, 0.75f, false, {0.5f, 0, 0.5f});
  // Clamped, the edge texel carries on.
  expect(0.0f, 0.75f, true, {1, 0, 0});
  expect(-3.0f, 7.0f, true, {1, 0, 0});
}

// The pixel samples cover the pixel evenly (render/sampling.h): sample 0 at the centre, and
// the first 256 put 4 ± 1 in each cell of an 8 x 8 grid over the pixel, where independent
// uniform jitter would leave some cells with 0 or 1 and others with 8 or more.
TEST(Render, PixelSamplesStartAtTheCentreAndCoverThePixelEvenly) {
  float x, y;
  pixel_jitter(0, x, y);
  EXPECT_EQ(x, 0.5f);
  EXPECT_EQ(y, 0.5f);
  int cells[8][8] = {};
  for (std::uint64_t k = 0; k < 256; ++k) {
    pixel_jitter(k, x, y);
    ASSERT_TRUE(x >= 0 && x < 1 && y >= 0 && y < 1) << "sample " << k << ": " << x << ", " << y;
    ++cells[static_cast<int>(y * 8)][static_cast<int>(x * 8)];
  }
  for (const auto& row : cells)
    for (int count : row) EXPECT_NEAR(count, 4, 1);
}

// Beyond the city the land is farmland, not one lawn to the horizon: straight down over the
// ring 150 to 700 m past a small city, some rays meet the trees of woods and hedgerows
// (metres over the ground, which lies at 0), and the fields between are of several crops,
// ripe cereals and bare soil among them (redder than green, which grass never is).
TEST(Render, TheLandBeyondTheCityIsFieldsHedgerowsAndWoods) {
  const exacity::City city = one_zone_city("residential", 300, 200, 4);
  Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  int rays = 0, trees = 0, ground = 0, golden = 0;
  for (int y = -700; y <= 900; y += 7)
    for (int x = -700; x <= 1000; x += 7) {
      const double past = std::max({-x, x - 300, -y, y - 200});
      if (past < 150 || past > 700) continue;
      Surface hit;
      ASSERT_TRUE(scene.intersect(scene.to_scene(x, y, 400), {0, 0, -1}, INFINITY, hit));
      ++rays;
      if (hit.position.z > 2) ++trees;
      if (hit.entity >> 24 != static_cast<std::uint32_t>(Entity::Terrain)) continue;
      ++ground;
      golden += hit.material.albedo.x > hit.material.albedo.y;
    }
  ASSERT_GT(rays, 10000);
  EXPECT_GT(trees, rays / 20) << "rays meeting trees of " << rays;
  EXPECT_LT(trees, rays * 2 / 3);
  EXPECT_GT(golden, ground / 10) << "cereal or soil of " << ground << " on the ground";
  EXPECT_LT(golden, ground * 2 / 3);
}

// Clear air fades distance towards the sky's colour: 300 m up, looking level over flat
// land, the ground just under the horizon (some 30 km off) is nearly the sky just above it.
// Without aerial perspective the far fields met the sky in a hard line.
TEST(Render, ClearAirFadesTheFarGroundTowardsTheSky) {
  const exacity::City city = one_zone_city("residential", 300, 200, 4);
  const auto dir = testing_util::temp_dir("clear-air");
  RenderRequest request;
  request.camera = Camera::look({150, 100, 300}, {150, 10100, 300}, 45);
  request.width = 96, request.height = 64, request.spp = 4;
  request.still = dir / "still.png";
  render_city(city, request);
  const Png png = read_png(request.still);
  // Rows 32 (centre) and up are sky; the ground's first rows are 33 and on.
  double apart = 0;
  for (int x = 8; x < 88; ++x) {
    const auto sky = png.at(x, 30), ground = png.at(x, 34);
    for (int c = 0; c < 3; ++c) apart += std::abs(sky[c] - ground[c]) / 3.0 / 80;
  }
  EXPECT_LT(apart, 12) << "mean 8-bit difference across the horizon";
  // And near ground keeps its own colour: green under the camera.
  const auto near = png.mean(48, 60, 3);
  EXPECT_GT(near[1], near[2]);
}

// The default camera holds the whole city in its frame, with the horizon and sky above it.
TEST(Camera, DefaultViewHoldsTheCityWithSkyAbove) {
  const exacity::City city = one_zone_city("commercial", 400, 300, 6);
  const Camera c = default_camera(city, 16.0f / 9);
  V3 o, top, bottom;
  c.ray(480, 0, 960, 540, o, top);
  c.ray(480, 540, 960, 540, o, bottom);
  EXPECT_GT(top.z, 0.02f) << "the frame's top looks above the horizon";
  EXPECT_LT(bottom.z, 0);
  const V3 f = c.forward(), r = c.right(), u = cross(r, f);
  const float tan_y = std::tan(c.fov_y * kPi / 360), tan_x = tan_y * 16 / 9;
  for (float x : {0.0f, 400.0f})
    for (float y : {0.0f, 300.0f}) {
      const V3 p = V3{x, y, 0} - c.from;
      const float depth = dot(p, f);
      ASSERT_GT(depth, 0);
      EXPECT_LE(std::abs(dot(p, r)), depth * tan_x) << x << "," << y;
      EXPECT_LE(std::abs(dot(p, u)), depth * tan_y) << x << "," << y;
    }
  // Near enough that the city fills much of the frame's width.
  float widest = 0;
  for (float x : {0.0f, 400.0f})
    for (float y : {0.0f, 300.0f}) {
      const V3 p = V3{x, y, 0} - c.from;
      widest = std::max(widest, std::abs(dot(p, r)) / (dot(p, f) * tan_x));
    }
  EXPECT_GT(widest, 0.6f);
}

// --mark-mapped: a building read from the sketch is light grey from above, a generated one
// orange. The mapped one stands in a park, whose buildings had no material (the palette
// held the built-up zones' only): Helsinki's centre, with mapped buildings in parks, was an
// internal error (map::at) in every render.
TEST(Render, MarkMappedTellsMappedBuildingsFromGeneratedOnesAndParksHoldThem) {
  const std::string text = R"({"type": "FeatureCollection", "exacity": {"seed": 3}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 200], [0, 200], [0, 0]]]}},
    {"type": "Feature", "properties": {"zone": "park"},
     "geometry": {"type": "Polygon", "coordinates": [[[300, 0], [400, 0], [400, 200], [300, 200], [300, 0]]]}},
    {"type": "Feature", "properties": {"building": "yes", "height": 12},
     "geometry": {"type": "Polygon", "coordinates": [[[340, 90], [360, 90], [360, 110], [340, 110], [340, 90]]]}}]})";
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  const exacity::City city = exacity::build_city(exacity::parse_sketch(text, "marked.geojson"), clock);
  const exacity::Building* mapped = nullptr;
  const exacity::Building* generated = nullptr;
  for (const auto& b : city.buildings) (b.mapped >= 0 ? mapped : generated) = &b;
  ASSERT_TRUE(mapped && generated);
  Sky sky(200, 40);
  SceneOptions options;
  options.mark_mapped = true;
  RenderScene scene(city, sky.sun_direction(), options);
  auto albedo_over = [&](const exacity::Building& b) {
    geom::Vec2 c{0, 0};
    for (geom::Vec2 v : b.polygon.outer) c.x += v.x / b.polygon.outer.size(), c.y += v.y / b.polygon.outer.size();
    Surface hit;
    EXPECT_TRUE(scene.intersect(scene.to_scene(c.x, c.y, 500), {0, 0, -1}, INFINITY, hit));
    EXPECT_EQ(hit.entity >> 24, static_cast<std::uint32_t>(Entity::Building));
    return hit.material.albedo;
  };
  const V3 grey = albedo_over(*mapped), orange = albedo_over(*generated);
  EXPECT_NEAR(grey.x, grey.z, 0.05f);
  EXPECT_GT(orange.x, 2 * orange.z + 0.3f);
  // Unmarked, the park's mapped building has its palette's facade and roof.
  RenderScene plain(city, sky.sun_direction(), SceneOptions{});
  Surface hit;
  EXPECT_TRUE(plain.intersect(plain.to_scene(350, 100, 500), {0, 0, -1}, INFINITY, hit));
}

// Grass has detail a few centimetres across: at eye level it was metre-wide blurred blobs
// (its finest noise 1.1 m across), neighbours 4 cm apart differing by about 1%.
TEST(Render, GrassHasTuftsAtEyeLevel) {
  const exacity::City city = one_zone_city("park", 200, 200, 2);
  Sky sky(200, 40);
  SceneOptions options;
  RenderScene scene(city, sky.sun_direction(), options);
  double change = 0, level = 0;
  int pairs = 0;
  Surface last;
  bool have_last = false;
  for (int i = 0; i < 2000; ++i) {
    const double x = 20 + i * 0.04, y = 37.3;
    Surface hit;
    const bool grass = scene.intersect(scene.to_scene(x, y, 100), {0, 0, -1}, INFINITY, hit) &&
                       hit.entity >> 24 == static_cast<std::uint32_t>(Entity::Zone) && hit.position.z < 1;
    if (grass && have_last) {
      change += std::abs(luminance(hit.material.albedo) - luminance(last.material.albedo));
      level += luminance(hit.material.albedo);
      ++pairs;
    }
    have_last = grass, last = hit;
  }
  ASSERT_GT(pairs, 500);
  EXPECT_GT(change / level, 0.04) << "mean relative change between neighbours 4 cm apart";
}

// Sidewalks (where the sketch gives its streets some) stand a kerb (12 cm) over the
// carriageway, its face their side: straight down on an office district's streets, road surfaces lie at two heights, 0.1 m (asphalt) and 0.22 m
// (sidewalks); they lay at one, the street flush from wall to wall.
TEST(Render, SidewalksStandAKerbOverTheCarriageway) {
  const std::string text = R"({"type": "FeatureCollection", "exacity": {"seed": 4,
    "zones": {"commercial": {"layout": "streets"}}, "roads": {"local": {"sidewalk": 2.5}}}, "features": [
    {"type": "Feature", "properties": {"zone": "commercial"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 200], [0, 200], [0, 0]]]}},
    {"type": "Feature", "properties": {"road": "local"},
     "geometry": {"type": "LineString", "coordinates": [[0, 100], [300, 100]]}},
    {"type": "Feature", "properties": {"road": "local"},
     "geometry": {"type": "LineString", "coordinates": [[150, 0], [150, 200]]}}]})";
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  const exacity::City city = exacity::build_city(exacity::parse_sketch(text, "kerbs.geojson"), clock);
  ASSERT_TRUE(std::any_of(city.ground.road_areas.begin(), city.ground.road_areas.end(),
                          [](const auto& a) { return a.surface == exacity::RoadSurface::Sidewalk; }));
  Sky sky(200, 40);
  SceneOptions options;
  RenderScene scene(city, sky.sun_direction(), options);
  int road = 0, kerb_high = 0;
  for (double y = 1; y < 200; y += 1.3)
    for (double x = 1; x < 300; x += 1.3) {
      Surface hit;
      if (!scene.intersect(scene.to_scene(x, y, 100), {0, 0, -1}, INFINITY, hit)) continue;
      if (hit.entity >> 24 != static_cast<std::uint32_t>(Entity::Road) || hit.position.z > 1) continue;
      ++road;
      kerb_high += std::abs(hit.position.z - 0.22f) < 0.005f;
    }
  ASSERT_GT(road, 1000);
  EXPECT_GT(kerb_high, road / 10) << "of " << road << " road hits at the sidewalk's height";
  EXPECT_LT(kerb_high, road * 9 / 10);
}

// Where a street meets another road it has a zebra crossing and a stop line: paint lies on
// the street away from its centre stripe, near its end. Before, the only paint on streets
// was the centre stripe.
TEST(Render, StreetsHaveCrossingsAndStopLinesAtJunctions) {
  const exacity::City city = one_zone_city("residential", 400, 300, 3);
  Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  const V3 paint{exacity::kPaintAlbedo[0], exacity::kPaintAlbedo[1], exacity::kPaintAlbedo[2]};
  int marked = 0;
  for (double y = 0.5; y < 300; y += 0.35)
    for (double x = 0.5; x < 400; x += 0.35) {
      Surface hit;
      if (!scene.intersect(scene.to_scene(x, y, 100), {0, 0, -1}, INFINITY, hit)) continue;
      if (hit.entity >> 24 != static_cast<std::uint32_t>(Entity::Road) || length(hit.material.albedo - paint) > 1e-3f)
        continue;
      double to_centre = INFINITY;
      for (const auto& r : city.ground.roads)
        for (std::size_t k = 0; k + 1 < r.line.size(); ++k)
          to_centre = std::min(to_centre, geom::distance_to_segment({x, y}, r.line[k], r.line[k + 1]));
      marked += to_centre > 0.6;
    }
  EXPECT_GT(marked, 200) << "painted points off the centre stripes";
}

// At night (--night) a street lamp is lit: its head bright, the sky dark; the lamps are
// point lights chosen among those that reach a point (render/night.h), the minimap is the
// day's whatever the hour.
TEST(Render, AtNightTheLampsAreLitAndTheSkyIsDark) {
  const exacity::City city = one_zone_city("residential", 400, 300, 3);
  SceneOptions lit;
  lit.lamp_intensity = 1;
  const RenderScene probe(city, {0, 0, 1}, lit);
  ASSERT_FALSE(probe.lamps.empty());
  // The lamp farthest from any tree, looked up at from 2 m beside its foot: its head at
  // the middle of the frame against the sky.
  V3 head{0, 0, 0};
  double clearest = -1;
  for (const Lamp& lamp : probe.lamps) {
    const V3 at{lamp.position.x + static_cast<float>(probe.origin_x), lamp.position.y + static_cast<float>(probe.origin_y),
                lamp.position.z};
    double nearest = INFINITY;
    auto near_tree = [&](const exacity::ModelInstance& m) {
      if (m.kind == exacity::ModelKind::Tree)
        nearest = std::min(nearest, std::hypot(m.placed.position.x - at.x, m.placed.position.y - at.y));
    };
    for (const auto& m : city.models) near_tree(m);
    for (const auto& c : city.clutter.items) near_tree(c.instance);
    if (nearest > clearest) clearest = nearest, head = at + V3{0, 0, 0.1f};
  }
  RenderRequest request;
  request.width = 96, request.height = 64, request.spp = 4;
  request.camera = Camera::look({head.x + 1.5f, head.y + 1.5f, 1.7f}, head, 60);
  request.minimap = true;
  const auto dir = testing_util::temp_dir("night-lamp");
  auto pixels = [&](const std::filesystem::path& file) {
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(spec.width) * spec.height * 3);
    EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
    return rgb;
  };
  auto grey = [](const std::vector<std::uint8_t>& rgb, std::size_t i) {
    return 0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2];
  };
  std::vector<std::vector<std::uint8_t>> minimaps;
  for (float hour : {-1.0f, 22.0f}) {
    request.time_of_day = hour;
    request.still = dir / (hour < 0 ? "day.png" : "night.png");
    request.minimap_file = dir / (hour < 0 ? "day-minimap.png" : "night-minimap.png");
    const nlohmann::ordered_json report = render_city(city, request);
    const std::vector<std::uint8_t> rgb = pixels(request.still);
    // The head, at the middle of the frame: its brightest pixel of the 5x5 there.
    double head_grey = 0;
    for (int y = request.height / 2 - 2; y <= request.height / 2 + 2; ++y)
      for (int x = request.width / 2 - 2; x <= request.width / 2 + 2; ++x)
        head_grey = std::max(head_grey, grey(rgb, static_cast<std::size_t>(y) * request.width + x));
    // The sky: the top rows, left of the minimap's inset.
    double sky = 0;
    int sky_pixels = 0;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < request.width / 3; ++x) sky += grey(rgb, static_cast<std::size_t>(y) * request.width + x), ++sky_pixels;
    sky /= sky_pixels;
    if (hour < 0) {
      EXPECT_EQ(report["lamps"], 0u);
      EXPECT_GT(sky, 90) << "a day's sky";
    } else {
      EXPECT_GT(report["lamps"].get<std::size_t>(), 0u);
      EXPECT_GT(head_grey, 230) << "the lamp's head, lit";
      EXPECT_LT(sky, 50) << "the night sky";
      EXPECT_LT(report["sun"]["elevation"].get<float>(), -20);
    }
    minimaps.push_back(pixels(request.minimap_file));
  }
  EXPECT_EQ(minimaps[0], minimaps[1]) << "the minimap is the day's at any hour";
}

TEST(Render, TheSunFollowsTheHour) {
  const SunPosition noon = sun_at_hour(12), morning = sun_at_hour(9), evening = sun_at_hour(18.5f);
  EXPECT_NEAR(noon.elevation, 40, 0.01);  // 90 less the latitude, on an equinox
  EXPECT_NEAR(noon.azimuth, -90, 0.01);   // due south
  EXPECT_GT(morning.elevation, 0);
  EXPECT_GT(std::cos(morning.azimuth * kPi / 180), 0);  // east of south
  EXPECT_LT(evening.elevation, 0);
  EXPECT_EQ(night_share(10), 0);
  EXPECT_EQ(night_share(-20), 1);
}

namespace {

// A 400 m square residential zone with its south-west corner at (x, y) in the CRS of
// EPSG `epsg`.
exacity::City zone_on_earth(int epsg, double x, double y) {
  const auto at = [](double v) { return std::to_string(static_cast<long long>(v)); };
  const std::string text = R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name":
    "urn:ogc:def:crs:EPSG::)" + std::to_string(epsg) + R"("}}, "exacity": {"seed": 3}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon", "coordinates": [[[)" +
                           at(x) + ", " + at(y) + "], [" + at(x + 400) + ", " + at(y) + "], [" + at(x + 400) + ", " +
                           at(y + 400) + "], [" + at(x) + ", " + at(y + 400) + "], [" + at(x) + ", " + at(y) +
                           "]]]}}]}";
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  return exacity::build_city(exacity::parse_sketch(text, "on-earth.geojson"), clock);
}

}  // namespace

// The hour's sun stands where the city is: a city in Helsinki's centre (UTM zone 35N,
// 60.17 degrees north, 2.05 degrees west of the zone's central meridian, where the map's
// north is turned 1.78 degrees west of true north: cs2cs and the meridian convergence,
// atan(tan(dlon) sin(lat))) sees the noon sun 29.8 degrees high on an equinox, in the
// south, which is 1.78 degrees clockwise of the map's south, and 53.3 degrees high on the
// June solstice; one in Sydney (zone 56S, 33.86 south) sees it in the north, 56.1 degrees
// high. A sketch without a CRS keeps 50 north. Every city stood at 50
// north (the sun 40 degrees high at noon wherever it was).
TEST(Render, TheHoursSunStandsAtTheCitysLatitude) {
  const exacity::City helsinki = zone_on_earth(32635, 385800, 6671900);
  RenderRequest request;
  request.width = 16, request.height = 9, request.spp = 1, request.denoise = false;
  request.time_of_day = 12;
  request.camera = default_camera(helsinki);
  request.still = testing_util::temp_dir("sun-latitude") / "still.png";
  const nlohmann::ordered_json report = render_city(helsinki, request);
  EXPECT_NEAR(report["latitude"].get<double>(), 60.17, 0.01);
  EXPECT_NEAR(report["sun"]["elevation"].get<double>(), 90 - 60.17, 0.02);
  EXPECT_NEAR(report["sun"]["azimuth"].get<double>(), -90 - 1.78, 0.02);

  const SolarPlace midsummer = solar_place(helsinki, day_of_year(6, 21));
  EXPECT_NEAR(midsummer.declination, 23.44, 0.1);
  EXPECT_NEAR(sun_at_hour(12, midsummer).elevation, 90 - 60.17 + 23.44, 0.1);
  // At midnight on midsummer's night the sun is under the northern horizon, but barely.
  EXPECT_NEAR(sun_at_hour(0, midsummer).elevation, 60.17 + 23.44 - 90, 0.1);

  const SolarPlace sydney = solar_place(zone_on_earth(32756, 334000, 6252000));
  EXPECT_NEAR(sydney.latitude, -33.86, 0.01);
  const SunPosition noon = sun_at_hour(12, sydney);
  EXPECT_NEAR(noon.elevation, 90 - 33.86, 0.02);
  EXPECT_NEAR(std::remainder(noon.azimuth - sydney.grid_north, 360.0), 90, 0.01);  // due north

  const SolarPlace local = solar_place(one_zone_city("residential", 100, 100, 3));
  EXPECT_EQ(local.latitude, 50);
  EXPECT_EQ(local.grid_north, 0);
  EXPECT_NEAR(sun_at_hour(12, local).elevation, 40, 0.01);
}

// Ten thousand lamps, every 30 m on a 3 km square: the light at a street point estimated
// from 64 lamps drawn by StreetLights::choose is within 5% of the sum over them all (the
// draws go where the light comes from), and no draw goes to a lamp that gives none.
TEST(Render, ManyLampsConvergeAsAFewDo) {
  std::vector<Lamp> lamps;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) lamps.push_back({{x * 30.0f, y * 30.0f, 6}, 1 + 0.5f * static_cast<float>((x + y) % 3)});
  const StreetLights lights(lamps);
  for (const V3 p : {V3{1510, 1495, 0}, V3{3, 2, 0}, V3{1000, 2980, 0}}) {
    double exact = 0;
    for (const Lamp& l : lamps) {
      const V3 d = l.position - p;
      const float r = std::sqrt(dot(d, d));
      exact += lamp_intensity(l, d * (-1 / r), r) * (d.z / r) / std::max(dot(d, d), 1.0f);
    }
    double estimate = 0;
    constexpr int kDraws = 64;
    for (int k = 0; k < kDraws; ++k) {
      float chance = 0;
      const Lamp* l = lights.choose(p, (k + 0.5f) / kDraws, chance);
      ASSERT_TRUE(l);
      const V3 d = l->position - p;
      const float r = std::sqrt(dot(d, d));
      const double light = lamp_intensity(*l, d * (-1 / r), r) * (d.z / r) / std::max(dot(d, d), 1.0f);
      EXPECT_GT(light, 0);
      estimate += light / chance / kDraws;
    }
    EXPECT_NEAR(estimate, exact, 0.05 * exact) << p.x << ", " << p.y;
  }
}
