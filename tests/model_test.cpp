// Placed models: OBJ files as real exporters write them, the library's normalisation, the
// exact footprint checks, and rows of models facing the road.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "generate/placement/building_settings.h"
#include "generate/placement/buildings.h"
#include "generate/errors.h"
#include "generate/placement/model_library.h"
#include "generate/placement/model_placement.h"
#include "geom/cell.h"
#include "geom/grid.h"
#include "geom/planar_map.h"
#include "geom/triangulate.h"
#include "geom/polygon_check.h"
#include "tests/test_util.h"
#include "generate/pipeline.h"

#include <OpenImageIO/imageio.h>

using namespace exacity;
namespace fs = std::filesystem;
using geom::Vec2;

namespace {

fs::path write(const fs::path& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

geom::Cell lot(const geom::Ring& ring, std::vector<int> road_edges) {
  return testing_util::fronted_cell(ring, std::move(road_edges));
}

// A unit-less box model: w x d x h in file units, Z-up, base at z0.
std::string box_obj(double w, double d, double h, double z0 = 0) {
  std::string s;
  for (double z : {z0, z0 + h})
    for (auto [x, y] : {std::pair{-w / 2, -d / 2}, {w / 2, -d / 2}, {w / 2, d / 2}, {-w / 2, d / 2}})
      s += "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
  return s + "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
}

// What load_model_library says of a manifest of `entries` (JSON objects, comma-separated)
// written into `dir`: its error, or "no error".
std::string library_error(const fs::path& dir, const std::string& entries) {
  write(dir, "library.json", R"({"models": [)" + entries + "]}");
  try {
    load_model_library(dir / "library.json");
  } catch (const UserError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ObjFile, ReadsTheQuirksOfRealFiles) {
  fs::path dir = testing_util::temp_dir("obj-quirks");
  // A concave hexagon (an L) as one n-gon with negative indices and v/vt/vn corners,
  // groups and objects, a doubled face (reversed), a stray vertex, comments, a
  // continued line and a material from the .mtl.
  write(dir, "l.mtl", "newmtl red\nKd 0.8 0.1 0.1\n");
  fs::path file = write(dir, "l.obj",
                        "# awkward\nmtllib l.mtl\no first\ng walls\nv 100 100 100\n"
                        "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nvt 0 0\nvn 0 0 1\n"
                        "usemtl red\nf -6/1/1 -5/1/1 -4//1 \\\n -3 -2/1 -1\n"
                        "g copy\nf 7 6 5 4 3 2\n");
  TriangleMesh m = read_obj(file);
  EXPECT_EQ(m.vertices.size(), 6u);  // the stray vertex is gone
  ASSERT_EQ(m.triangles.size(), 4u);  // the hexagon once: its reversed copy is a repeat
  double area = 0;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    area += ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2;
  }
  EXPECT_EQ(area, 3.0);  // counter-clockwise and not a fan across the notch
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].name, "red");
  EXPECT_EQ(m.materials[0].colour[0], 0.8);
}

TEST(ObjFile, BadIndexNamesTheFileAndLine) {
  fs::path dir = testing_util::temp_dir("obj-bad");
  fs::path file = write(dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  try {
    read_obj(file);
    FAIL() << "no error";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.obj line 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_obj(dir / "missing.obj"), UserError);
  EXPECT_THROW(read_obj(write(dir, "empty.obj", "v 0 0 0\n")), UserError);
}

TEST(ModelLibrary, YUpMillimetresAndASunkenBaseComeOutInMetresStandingOnZero) {
  fs::path dir = testing_util::temp_dir("library");
  // Y-up, millimetres: 4000 wide (x), 10000 high (y), 6000 deep (z), base at y = -500.
  std::string yup;
  for (double y : {-500.0, 9500.0})
    for (auto [x, z] : {std::pair{-2000.0, 3000.0}, {2000.0, 3000.0}, {2000.0, -3000.0}, {-2000.0, -3000.0}})
      yup += "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
  yup += "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  write(dir, "tall.obj", yup);
  write(dir, "library.json",
        R"({"models": [{"file": "tall.obj", "zones": ["commercial"], "up": "y", "unit": "mm"}]})");
  ModelLibrary lib = load_model_library(dir / "library.json");
  ASSERT_EQ(lib.models.size(), 1u);
  const Model& m = lib.models[0];
  EXPECT_EQ(m.name, "tall");
  EXPECT_EQ(m.height, 10.0);
  EXPECT_EQ(m.width, 4.0);
  EXPECT_EQ(m.depth, 6.0);
  double lowest = INFINITY;
  for (const Vec3& v : m.mesh.vertices) lowest = std::min(lowest, v[2]);
  EXPECT_EQ(lowest, 0.0);
  EXPECT_EQ(geom::signed_area(m.outline), 24.0);
  EXPECT_EQ(lib.choices(ZoneType::Commercial, ModelKind::Building), std::vector<int>{0});
  EXPECT_TRUE(lib.choices(ZoneType::Residential, ModelKind::Building).empty());
}

TEST(ModelLibrary, FrontTurnsToMinusY) {
  // A wedge whose front (+x in the file) is its tall side: after loading, the tall side faces -y.
  TriangleMesh wedge;
  wedge.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {2, 0, 3}, {2, 1, 3}};
  wedge.triangles = {{0, 3, 2}, {0, 2, 1}, {1, 2, 5}, {1, 5, 4}, {0, 1, 4}, {3, 5, 2}, {0, 4, 5}, {0, 5, 3}};
  wedge.material.assign(wedge.triangles.size(), 0);
  wedge.materials = {{"default", {0.5, 0.5, 0.5}}};
  Model m = normalise_model(wedge, "z", "+x", 1, "test");
  int tall = 0;
  for (const Vec3& v : m.mesh.vertices)
    if (v[2] == 3) {
      ++tall;
      EXPECT_EQ(v[1], -m.depth / 2);  // the tall edge is at the front
    }
  EXPECT_EQ(tall, 2);  // both ends of the tall edge, still 3 high
  EXPECT_EQ(m.width, 1.0);
  EXPECT_EQ(m.depth, 2.0);
  EXPECT_THROW(normalise_model(wedge, "z", "+z", 1, "test"), UserError);
}

TEST(ModelLibrary, OutlineIsTheExactShadowAndPiecesGetTheirHull) {
  // An L-shaped roof, raised at its inner corner: its outline is the L itself.
  TriangleMesh l;
  l.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 1}, {1, 2, 0}, {0, 2, 0}};
  l.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  l.material.assign(4, 0);
  l.materials = {{"default", {}}};
  Model m = normalise_model(l, "z", "-y", 1, "test");
  EXPECT_EQ(m.outline.size(), 6u);
  EXPECT_EQ(geom::signed_area(m.outline), 3.0);
  // Two separate squares: the hull of both.
  TriangleMesh two;
  two.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {3, 0, 0}, {4, 0, 0}, {4, 1, 1}, {3, 1, 0}};
  two.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  two.material.assign(4, 0);
  two.materials = {{"default", {}}};
  Model t = normalise_model(two, "z", "-y", 1, "test");
  EXPECT_EQ(t.outline.size(), 4u);
  EXPECT_EQ(geom::signed_area(t.outline), 4.0);
}

TEST(ModelLibrary, BadEntriesAreNamed) {
  fs::path dir = testing_util::temp_dir("library-bad");
  write(dir, "box.obj", box_obj(4, 4, 4));
  auto error = [&](const std::string& entry) { return library_error(dir, entry); };
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["park"]})").find("models[0]: \"zones\""), std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["residential"], "up": "x"})").find("\"up\""), std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["residential"], "weight": "heavy"})").find("models[0]"), std::string::npos);
  EXPECT_NE(error(R"({"file": "none.obj", "zones": ["residential"]})").find("none.obj"), std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["residential"], "colour": 1})").find("unknown key"), std::string::npos);
  // The library's newer keys: kinds, clutter rules, channel values and lots.
  EXPECT_NE(error(R"({"file": "box.obj", "kind": "kiosk"})").find("\"kind\" is \"kiosk\"; expected one of"), std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "kind": "lamp", "side": "left"})").find("\"side\""), std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "kind": "bench", "offset": -1})").find("\"offset\""), std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["residential"], "channels": {"wealth": 1.5}})").find("channels.wealth is 1.5"),
            std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["residential"], "channels": [0.5]})").find("\"channels\" must map"),
            std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "kind": "lamp", "lot": [10, 10]})").find("\"lot\" is for building models"),
            std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["residential"], "lot": [10]})").find("\"lot\" must be"), std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["residential"], "lot": [4.5, 20]})").find("does not fit its lot"),
            std::string::npos);
  EXPECT_NE(error(R"({"file": "box.obj", "zones": ["park"], "kind": "building"})").find("models[0]: \"zones\""), std::string::npos);
  // Clutter may dress park streets, and an entry without zones dresses every zone's.
  EXPECT_EQ(error(R"({"file": "box.obj", "kind": "bench", "zones": ["park"]})"), "no error");
  EXPECT_EQ(error(R"({"file": "box.obj", "kind": "hydrant"})"), "no error");
}

namespace {

// A city on a 600 x 200 residential zone with a street down its middle, its library's
// two box houses tagged for opposite ends of a "downtown" channel (0 west, 1 east).
City two_ended_city(const std::string& name, const std::string& zone_settings) {
  const fs::path dir = testing_util::temp_dir(name);
  write(dir, "small.obj", box_obj(8, 8, 6));
  write(dir, "large.obj", box_obj(10, 10, 20));
  write(dir, "library.json", R"({"models": [
      {"file": "small.obj", "zones": ["residential"], "up": "z", "channels": {"downtown": 0}, "lot": [14, 20]},
      {"file": "large.obj", "zones": ["residential"], "up": "z", "channels": {"downtown": 1}, "lot": [16, 22]}]})");
  // Two pixels, 0 and 255: pixel centres at x = 150 and 450.
  const std::vector<unsigned char> pixels{0, 255};
  auto out = OIIO::ImageOutput::create((dir / "downtown.png").string());
  out->open((dir / "downtown.png").string(), OIIO::ImageSpec(2, 1, 1, OIIO::TypeDesc::UINT8));
  out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
  out->close();
  write(dir, "sketch.geojson", R"({"type": "FeatureCollection", "exacity": {"seed": 4, "models": "library.json",
      "channels": {"downtown": {"image": "downtown.png", "bounds": [0, 0, 600, 200]}}, "channel_sharpness": 12,
      "zones": {"residential": )" + zone_settings + R"(}},
    "features": [
      {"type": "Feature", "properties": {"zone": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [600, 0], [600, 200], [0, 200], [0, 0]]]}},
      {"type": "Feature", "properties": {"road": "main"},
       "geometry": {"type": "LineString", "coordinates": [[-10, 100], [610, 100]]}}]})");
  StageClock stages(nullptr, kCityStages);
  return build_city(load_sketch(dir / "sketch.geojson"), stages, {}, ExactWork::Kept);  // the tests read the lots
}

}  // namespace

TEST(Channels, ASharpChannelKeepsEachModelToItsEndOfTheCity) {
  for (const char* settings : {R"({"block_area": 8000})", R"({"block_area": 8000, "placement": "grid"})",
                               R"({"block_area": 8000, "lots": "library"})"}) {
    const City city = two_ended_city("channels-two-ended", settings);
    int west = 0, east = 0;
    for (const ModelInstance& m : city.models) {
      if (m.kind != ModelKind::Building) continue;
      const double x = m.placed.position.x;
      if (x < 150) {
        EXPECT_EQ(m.placed.model, 0) << settings << " at x = " << x;
        ++west;
      }
      if (x > 450) {
        EXPECT_EQ(m.placed.model, 1) << settings << " at x = " << x;
        ++east;
      }
    }
    EXPECT_GE(west, 5) << settings;
    EXPECT_GE(east, 5) << settings;
  }
}

TEST(LibraryLots, EachLotHoldsItsOwnModelFacingTheStreet) {
  const City city = two_ended_city("library-lots-city", R"({"block_area": 8000, "lots": "library"})");
  ASSERT_GE(city.lots.size(), 10u);
  std::vector<int> held(city.lots.size(), 0);
  for (const ModelInstance& m : city.models) {
    if (m.kind != ModelKind::Building) continue;
    ++held[m.lot];
    EXPECT_EQ(m.placed.model, city.lots[m.lot].model);
  }
  for (std::size_t i = 0; i < city.lots.size(); ++i) {
    EXPECT_TRUE(city.lots[i].model.has_value());
    EXPECT_EQ(held[i], 1) << "lot " << i;
  }
  EXPECT_EQ(city.unbuilt_lots.merged + city.unbuilt_lots.left_open, 0);
}

TEST(FootprintChecks, TouchingCountsAndHolesAreSeen) {
  geom::Ring a{{0, 0}, {2, 0}, {2, 2}, {0, 2}}, touching{{2, 0}, {4, 0}, {4, 2}, {2, 2}},
      apart{{2.0009765625, 0}, {4, 0}, {4, 2}, {2.0009765625, 2}}, inner{{0.5, 0.5}, {1, 0.5}, {1, 1}};
  EXPECT_TRUE(geom::rings_meet(a, touching));
  EXPECT_FALSE(geom::rings_meet(a, apart));
  EXPECT_TRUE(geom::rings_meet(a, inner));  // one inside the other, no edges crossing
  EXPECT_TRUE(geom::rings_meet(inner, a));

  geom::Cell square = lot({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {});
  EXPECT_TRUE(square.holds({{1, 1}, {9, 1}, {9, 9}, {1, 9}}));
  EXPECT_FALSE(square.holds({{0, 1}, {9, 1}, {9, 9}, {1, 9}}));  // a corner on the boundary
  EXPECT_FALSE(square.holds({{-1, -1}, {11, -1}, {11, 11}, {-1, 11}}));
}

TEST(ModelRows, ModelsStandInsideTheLotApartAndFacingTheRoad) {
  fs::path dir = testing_util::temp_dir("rows");
  write(dir, "small.obj", box_obj(6, 5, 4));
  write(dir, "large.obj", box_obj(12, 8, 9));
  write(dir, "library.json", R"({"models": [
      {"file": "small.obj", "zones": ["residential"], "up": "z"},
      {"file": "large.obj", "zones": ["residential"], "up": "z"}]})");
  ModelLibrary lib = load_model_library(dir / "library.json");
  // A lot 80 m along a road on its south edge (edge 0), 40 m deep, turned by 30 degrees.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  auto turn = [&](double x, double y) { return geom::snap(Vec2{100 + c * x - s * y, 50 + s * x + c * y}); };
  geom::Ring ring{turn(0, 0), turn(80, 0), turn(80, 40), turn(0, 40)};
  geom::Cell cell = lot(ring, {0});
  const double road = std::atan2(ring[1].y - ring[0].y, ring[1].x - ring[0].x);  // on the grid, near 30 degrees
  BuildingSettings params = default_building_settings(ZoneType::Residential);
  for (const char* density : {"dense", "normal", "sparse"}) {
    params.density = density;
    Random rng(7);
    Occupancy occupancy(cell, 1);
    auto placed = place_models(occupancy, choices_at(lib.choices(ZoneType::Residential, ModelKind::Building), lib, nullptr, geom::Vec2{}), ModelKind::Building,
                               lib, params, rng);
    ASSERT_FALSE(placed.empty()) << density;
    for (std::size_t i = 0; i < placed.size(); ++i) {
      EXPECT_TRUE(cell.holds(placed[i].polygon.outer));
      EXPECT_NEAR(placed[i].placed.angle, road, 1e-12);  // x along the road, front (-y) towards it
      for (std::size_t j = 0; j < i; ++j) EXPECT_FALSE(geom::rings_meet(placed[i].polygon.outer, placed[j].polygon.outer));
    }
    // Largest first: the first placed is a large one, at the front row (its centre 3 m
    // setback + half its depth from the road).
    EXPECT_EQ(placed[0].placed.model, 1) << density;
    const Vec2 p = placed[0].placed.position;
    const double depth = -s * (p.x - 100) + c * (p.y - 50);
    EXPECT_NEAR(depth, params.setback + 4 * placed[0].placed.scale, 1e-2);
  }
}

TEST(ModelRows, DensityChangesHowManyFit) {
  fs::path dir = testing_util::temp_dir("rows-density");
  write(dir, "house.obj", box_obj(8, 8, 6));
  write(dir, "library.json", R"({"models": [{"file": "house.obj", "zones": ["residential"], "up": "z", "scale": [1, 1]}]})");
  ModelLibrary lib = load_model_library(dir / "library.json");
  geom::Cell cell = lot({{0, 0}, {200, 0}, {200, 16}, {0, 16}}, {0});
  BuildingSettings params = default_building_settings(ZoneType::Residential);
  std::map<std::string, std::size_t> count;
  for (const char* density : {"dense", "normal", "sparse"}) {
    params.density = density;
    Random rng(3);
    Occupancy occupancy(cell, 1);
    count[density] = place_models(occupancy, choices_at({0}, lib, nullptr, geom::Vec2{}), ModelKind::Building, lib, params, rng).size();
  }
  // One row of 8 m houses along 200 m: spacing 1.25–1.5, 2–3 and 4–5 widths.
  EXPECT_GE(count["dense"], 16u);
  EXPECT_LE(count["dense"], 20u);
  EXPECT_GE(count["normal"], 8u);
  EXPECT_LE(count["normal"], 13u);
  EXPECT_GE(count["sparse"], 5u);
  EXPECT_LE(count["sparse"], 7u);
}

TEST(ObjFile, MalformedFacesNameTheFileAndLine) {
  fs::path dir = testing_util::temp_dir("obj-malformed");
  const std::string corners = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
  auto error = [&](const std::string& face) {
    try {
      read_obj(write(dir, "m.obj", corners + face + "\n"));
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  for (const char* face : {"f 1.5 2 3", "f 1/1/1/1 2 3", "f 1/x 2 3", "f x 2 3", "f 1 2 3e0"})
    EXPECT_NE(error(face).find("m.obj line 6: \""), std::string::npos) << face << ": " << error(face);
  EXPECT_NE(error("f 1/2 2 3").find("texture coordinate index 2 points to none of the 1"), std::string::npos);
  EXPECT_NE(error("f 1//3 2 3").find("normal index 3"), std::string::npos);
  EXPECT_NE(error("f 1 2").find("line 6: a face needs at least 3 corners"), std::string::npos);
  EXPECT_EQ(error("f 1/1/1 2//1 -1/-1"), "no error");
  EXPECT_EQ(error("f 1// 2/ 3"), "no error");
  std::string folder = "no error";
  try {
    read_obj(dir);
  } catch (const UserError& e) {
    folder = e.what();
  }
  EXPECT_NE(folder.find("is a folder"), std::string::npos) << folder;
}

TEST(ObjFile, AFaceWhoseSidesCrossIsStillTriangulated) {
  // A bow tie: a constrained triangulation of its outline would need the crossing as a
  // vertex. The face comes out as a fan of triangles instead of an error.
  fs::path dir = testing_util::temp_dir("obj-bowtie");
  TriangleMesh m = read_obj(write(dir, "q.obj", "v 0 0 0\nv 10 6 0\nv 10 0 0\nv 0 5 0\nf 1 2 3 4\n"));
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_TRUE(geom::triangulate(geom::Polygon{{{0, 0}, {10, 6}, {10, 0}, {0, 5}}, {}}).empty());
}

TEST(ObjFile, AFaceWithEveryCornerOnOneLineHasNoArea) {
  // Found by the obj fuzz target: the triangulation of a face with no extent in two
  // directions has no faces to walk.
  fs::path dir = testing_util::temp_dir("obj-line");
  EXPECT_THROW(read_obj(write(dir, "line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3 4\n")), UserError);
  EXPECT_THROW(read_obj(write(dir, "point.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3 4\n")), UserError);
  EXPECT_TRUE(geom::triangulate(geom::Polygon{{{0, 0}, {1, 1}, {2, 2}, {3, 3}}, {}}).empty());
}

TEST(ModelLibrary, AFlatModelIsRefused) {
  fs::path dir = testing_util::temp_dir("library-flat");
  write(dir, "flat.obj", "v 0 0 0\nv 4 0 0\nv 4 0 4\nv 0 0 4\nv 9 9 9\nf 1 2 3 4\n");  // y up: a horizontal square
  write(dir, "library.json", R"({"models": [{"file": "flat.obj", "zones": ["residential"]}]})");
  try {
    load_model_library(dir / "library.json");
    FAIL() << "accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("models[0]: the model is flat"), std::string::npos) << e.what();
  }
}

TEST(ModelLibrary, AFaceOfManyCornersGetsABoundedOutlineAroundIt) {
  // One face of 2,000 corners round a star, with height: its outline is a convex polygon of
  // kOutlineCorners sides that holds every corner.
  fs::path dir = testing_util::temp_dir("library-star");
  std::string obj;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n, r = i % 2 ? 8 : 7.5;
    obj += "v " + std::to_string(r * std::cos(a)) + " " + std::to_string(r * std::sin(a)) + " " + (i % 4 < 2 ? "10" : "0") + "\n";
  }
  obj += "f";
  for (int i = 1; i <= n; ++i) obj += " " + std::to_string(i);
  write(dir, "star.obj", obj + "\n");
  write(dir, "library.json", R"({"models": [{"file": "star.obj", "zones": ["residential"], "up": "z"}]})");
  const ModelLibrary lib = load_model_library(dir / "library.json");
  const Model& m = lib.models[0];
  ASSERT_LE(m.outline.size(), kOutlineCorners);
  EXPECT_EQ(geom::ring_orientation(m.outline), 1);
  for (const Vec3& v : m.mesh.vertices) EXPECT_TRUE(geom::ring_within({geom::Vec2{v[0], v[1]}}, m.outline));
}

TEST(ModelLibrary, ExportsPastTheirTriangleBudgetStopWithTheHeaviestModel) {
  ModelLibrary lib;
  lib.file = "library.json";
  lib.models.resize(2);
  lib.models[0].name = "heavy", lib.models[0].mesh.triangles.resize(3000000);
  lib.models[1].name = "light", lib.models[1].mesh.triangles.resize(10);
  std::vector<ModelInstance> models(20);
  for (ModelInstance& m : models) m.placed.model = 0;
  EXPECT_NO_THROW(check_export_size(models, &lib));  // 60 million triangles: the budget
  models.push_back({});
  models.back().placed.model = 1;
  try {
    check_export_size(models, &lib);
    FAIL() << "accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("model \"heavy\" (3000000 triangles) is placed 20 times"), std::string::npos) << e.what();
  }
}

namespace {

// A PNG of w x h RGBA pixels (row 0 at the top).
void write_png(const fs::path& file, int w, int h, const std::vector<std::uint8_t>& rgba) {
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(w, h, 4, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgba.data()));
  out->close();
}

// A quad textured corner to corner, and a triangle of the same material without vt.
const char* kTexturedQuad =
    "mtllib quad.mtl\nv 0 0 0\nv 2 0 0\nv 2 0 3\nv 0 0 3\nv 5 0 0\nv 6 0 0\nv 5 0 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl skin\nf 1/1 2/2 3/3 4/4\nf 5 6 7\n";

}  // namespace

TEST(ObjFile, KeepsTextureCoordinatesPerCornerAndTheTextureOnce) {
  fs::path dir = testing_util::temp_dir("obj-texture");
  fs::create_directories(dir / "my textures");
  write_png(dir / "my textures" / "check er.png", 2, 2, {255, 0, 0, 255, 0, 0, 255, 128, 0, 0, 255, 255, 255, 0, 0, 0});
  // Options before a name with spaces, a backslash between folders, -s and -o applied.
  write(dir, "quad.mtl", "newmtl skin\nKd 0.5 1 1\nmap_Kd -s 2 3 1 -o 0.5 0.25 -clamp on my textures\\check er.png\n");
  write(dir, "quad.obj", kTexturedQuad);
  TextureImages images;
  TriangleMesh m = read_obj(dir / "quad.obj", &images);
  ASSERT_EQ(m.triangles.size(), 3u);
  ASSERT_TRUE(m.textured());
  ASSERT_EQ(m.uv.size(), 3u);
  // The quad's material has the texture; the face without vt has an untextured copy.
  ASSERT_EQ(m.materials.size(), 2u);
  const MeshMaterial& skin = m.materials[m.material[0]];
  ASSERT_TRUE(skin.texture);
  EXPECT_TRUE(skin.clamp);
  EXPECT_EQ(skin.colour, (Vec3{0.5, 1, 1}));
  EXPECT_EQ(skin.texture->width, 2);
  EXPECT_EQ(skin.texture->mime_type, "image/png");
  EXPECT_EQ(skin.texture->rgb, (std::vector<std::uint8_t>{255, 0, 0, 0, 0, 255, 0, 0, 255, 255, 0, 0}));
  const MeshMaterial& bare = m.materials[m.material[2]];
  EXPECT_FALSE(bare.texture);
  EXPECT_EQ(bare.name, "skin_untextured");
  EXPECT_EQ(bare.colour, (Vec3{0.5, 1, 1}));
  // Each corner of the quad's triangles carries its own vt, scaled by (2, 3), moved by (0.5, 0.25).
  auto expected = [](const Vec3& p) { return Uv{p[0] / 2 * 2 + 0.5, p[2] / 3 * 3 + 0.25}; };
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m.uv[t][k], expected(m.vertices[m.triangles[t][k]])) << t << " " << k;
  // Another model naming the same file shares the image.
  write(dir, "other.mtl", "newmtl skin\nmap_Kd my textures/../my textures/check er.png\n");
  write(dir, "other.obj", std::string(kTexturedQuad).replace(7, 8, "other.mtl"));
  TriangleMesh other = read_obj(dir / "other.obj", &images);
  EXPECT_EQ(other.materials[other.material[0]].texture.get(), skin.texture.get());
  EXPECT_EQ(other.materials[other.material[0]].colour, (Vec3{1, 1, 1})) << "no Kd: the texture as it is";
}

TEST(ObjFile, AMissingOrUnreadableTextureIsOneLineNamingTheMtlAndTheFile) {
  fs::path dir = testing_util::temp_dir("obj-texture-bad");
  write(dir, "quad.obj", kTexturedQuad);
  auto message = [&](const std::string& mtl) {
    write(dir, "quad.mtl", mtl);
    try {
      read_obj(dir / "quad.obj");
    } catch (const UserError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string mtl = (dir / "quad.mtl").string();
  EXPECT_EQ(message("newmtl skin\nKd 1 1 1\nmap_Kd gone.png\n"),
            mtl + " line 3: map_Kd " + (dir / "gone.png").string() +
                " does not exist; put the image there or fix the map_Kd line");
  write(dir, "broken.png", "\x89PNG\r\n\x1a\nnot really");
  EXPECT_NE(message("newmtl skin\nmap_Kd broken.png\n")
                .find(mtl + " line 2: map_Kd " + (dir / "broken.png").string() + " cannot be decoded"),
            std::string::npos);
  write(dir, "picture.bmp", "BM not a png");
  EXPECT_EQ(message("newmtl skin\nmap_Kd picture.bmp\n"),
            mtl + " line 2: map_Kd " + (dir / "picture.bmp").string() +
                " is not a PNG or JPEG file, the formats glTF embeds; convert it to PNG");
  EXPECT_EQ(message("newmtl skin\nmap_Kd -mm 0 1 picture.png\n"),
            mtl + " line 2: map_Kd option -mm is not read by Exacity (only -s, -o and -clamp); remove it");
  EXPECT_EQ(message("newmtl skin\nmap_Kd -s 2\n"),
            mtl + " line 2: map_Kd names no file; give the image's name after map_Kd");
  // A model without map_Kd keeps no texture coordinates.
  write(dir, "quad.mtl", "newmtl skin\nKd 1 0 0\n");
  EXPECT_FALSE(read_obj(dir / "quad.obj").textured());
}

TEST(ObjFile, AnMtllibNameWithSpacesIsReadWhole) {
  fs::path dir = testing_util::temp_dir("obj-mtllib-spaces");
  write(dir, "my materials.mtl", "newmtl red\nKd 0.8 0.1 0.1\n");
  TriangleMesh m =
      read_obj(write(dir, "t.obj", "mtllib my materials.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n"));
  EXPECT_EQ(m.materials[0].colour, (Vec3{0.8, 0.1, 0.1}));
}

TEST(ModelLibrary, AHugeUnitOrAFarVertexIsRefusedBeforeTheOutlineIsComputed) {
  // The exact union of a model's shadow overflowed at these sizes (a crash in the surface
  // sweep): the size is checked first, and said as a number, not a long that overflowed.
  fs::path dir = testing_util::temp_dir("library-huge");
  write(dir, "box.obj", box_obj(4, 4, 4));
  write(dir, "far.obj", box_obj(4, 4, 4) + "v 1e308 0 0\nf 1 2 9\n");
  auto message = [&](const std::string& entry) { return library_error(dir, entry); };
  for (const char* unit : {"1e300", "1e200", "1e20"}) {
    const std::string m = message(R"({"file": "box.obj", "zones": ["residential"], "up": "z", "unit": )" + std::string(unit) + "}");
    EXPECT_NE(m.find("models[0]: the model is "), std::string::npos) << m;
    EXPECT_NE(m.find("more than the 100000 m a side a model may be; check \"unit\""), std::string::npos) << m;
    EXPECT_EQ(m.find("-9223372036854775808"), std::string::npos) << m;
  }
  EXPECT_EQ(message(R"({"file": "box.obj", "zones": ["residential"], "up": "z", "unit": 1e20})"),
            (dir / "library.json").string() +
                " models[0]: the model is 4e+20 x 4e+20 x 4e+20 m at \"unit\" 1e+20, more than the 100000 m a side a "
                "model may be; check \"unit\" (\"mm\" for millimetres) and vertices far from the rest");
  EXPECT_NE(message(R"({"file": "far.obj", "zones": ["residential"], "up": "z"})").find("the model is 1e+308 x "),
            std::string::npos);
  // Within that, a placed model's own bound (1000 m wide at its largest scale) names its size.
  EXPECT_NE(message(R"({"file": "box.obj", "zones": ["residential"], "up": "z", "unit": 300, "scale": [1, 1]})")
                .find("the model is 1200 x 1200 x 1200 m at its largest \"scale\""),
            std::string::npos);
}

TEST(ModelLibrary, AScaleRefusalNamesItsLimit) {
  fs::path dir = testing_util::temp_dir("library-scale");
  write(dir, "box.obj", box_obj(4, 4, 4));
  auto message = [&](const std::string& scale) {
    return library_error(dir, R"({"file": "box.obj", "zones": ["residential"], "up": "z", "scale": )" + scale + "}");
  };
  const std::string refusal = (dir / "library.json").string() + " models[0]: \"scale\" must be [min, max] with 0 < min <= max <= 100";
  EXPECT_EQ(message("[1, 101]"), refusal);
  EXPECT_EQ(message("[0, 1]"), refusal);
  EXPECT_EQ(message("[2, 1]"), refusal);
  EXPECT_EQ(message("[1, 100]"), "no error");
}

TEST(ModelLibrary, ClutterSpacingHasAFloor) {
  // Stations along a street number its length over the spacing: 1e-9 m ran for hours.
  fs::path dir = testing_util::temp_dir("library-spacing");
  write(dir, "lamp.obj", box_obj(0.3, 0.3, 5));
  auto message = [&](const std::string& spacing) {
    return library_error(dir, R"({"file": "lamp.obj", "kind": "lamp", "up": "z", "spacing": )" + spacing + "}");
  };
  EXPECT_EQ(message("1e-9"), (dir / "library.json").string() +
                                 " models[0]: \"spacing\" is 1e-09; it must be metres between models along a street, "
                                 "at least 1");
  EXPECT_NE(message("0.5").find("\"spacing\" is 0.5"), std::string::npos);
  EXPECT_EQ(message("1"), "no error");
}

TEST(ObjFile, OnlyRegularFilesAreRead) {
  // A device reads forever: an OBJ, and an .mtl it names, must be regular files.
  fs::path dir = testing_util::temp_dir("obj-devices");
  auto message = [&](const fs::path& file) {
    try {
      read_obj(file);
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("/dev/zero"), "/dev/zero: cannot read the model file (it is not a regular file but a device, pipe or "
                                  "socket); name an .obj file in the model library");
  EXPECT_EQ(message(dir), dir.string() + ": cannot read the model file (it is a folder); name an .obj file in the model library");
  const fs::path obj = write(dir, "m.obj", "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(message(obj), "/dev/zero: cannot read the material library " + obj.string() +
                              " line 1 names (it is not a regular file but a device, pipe or socket); name an .mtl "
                              "file in the mtllib line");
}

TEST(ModelLibrary, ItsFilesStayInTheManifestsFolder) {
  // As the server keeps a sketch's files in its work folder, the MTL and texture files a
  // library's OBJ names lie below its folder: "mtllib ../../etc/passwd" is not read.
  fs::path dir = testing_util::temp_dir("library-confined"), lib = dir / "lib";
  fs::create_directories(lib / "sub");
  write(dir, "outside.obj", box_obj(4, 4, 4));
  write(dir, "outside.mtl", "newmtl red\nKd 1 0 0\n");
  write(lib, "inside.mtl", "newmtl red\nKd 1 0 0\n");
  write(lib / "sub", "deeper.mtl", "newmtl red\nKd 1 0 0\nmap_Kd ../../outside.png\n");
  auto message = [&](const std::string& file, const std::string& obj_head) {
    write(lib, "m.obj", obj_head + box_obj(4, 4, 4));
    return library_error(lib, R"({"file": ")" + file + R"(", "zones": ["residential"], "up": "z"})");
  };
  const std::string keep = "; keep an OBJ's MTL and texture files in its library's folder (an OBJ outside it: its own folder) or below";
  EXPECT_EQ(message("m.obj", "mtllib inside.mtl\nmtllib sub/../inside.mtl\n"), "no error");
  // The manifest names an OBJ anywhere (examples/nesting shares examples/models' lamp), but
  // that OBJ's own words stay below its folder.
  EXPECT_EQ(message("../outside.obj", ""), "no error");
  write(dir, "outside.obj", "mtllib ../passwd\n" + box_obj(4, 4, 4));
  EXPECT_EQ(message("../outside.obj", ""),
            (lib / ".." / "outside.obj").string() + " line 1: mtllib ../passwd lies outside " + dir.string() + keep);
  EXPECT_EQ(message("m.obj", "mtllib ../../../../etc/passwd\n"),
            (lib / "m.obj").string() + " line 1: mtllib ../../../../etc/passwd lies outside " + lib.string() + keep);
  EXPECT_EQ(message("m.obj", "mtllib ../outside.mtl\n"),
            (lib / "m.obj").string() + " line 1: mtllib ../outside.mtl lies outside " + lib.string() + keep);
  EXPECT_EQ(message("m.obj", "mtllib sub/deeper.mtl\n"),
            (lib / "sub" / "deeper.mtl").string() + " line 3: map_Kd ../../outside.png lies outside " + lib.string() + keep);
  // A symbolic link out of the folder is outside too.
  fs::remove(lib / "link.mtl");
  fs::create_symlink(dir / "outside.mtl", lib / "link.mtl");
  EXPECT_EQ(message("m.obj", "mtllib link.mtl\n"),
            (lib / "m.obj").string() + " line 1: mtllib link.mtl lies outside " + lib.string() + keep);
}
