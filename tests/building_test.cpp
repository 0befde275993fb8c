// Building meshes: closed, outward, the volume of their prism; and the OBJ they make.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "generate/placement/building_settings.h"
#include "generate/mesh/bridges.h"
#include "generate/mesh/building_mesh.h"
#include "generate/mesh/ground_mesh.h"
#include "generate/export/mesh_export.h"
#include "generate/city/terrain.h"
#include "geom/polygon_check.h"
#include "tests/test_util.h"

using namespace exacity;

namespace {

Building prism(geom::Polygon footprint, double height) {
  Building b;
  b.polygon = std::move(footprint);
  b.height = height;
  b.eaves = height;  // flat
  return b;
}

// Divergence theorem over the faces, fanned from their first vertex.
double volume(const Mesh& mesh) {
  double v = 0;
  for (const Mesh::Face f : mesh.faces()) {
    const Vec3& a = mesh.points[f.corners[0]];
    for (std::size_t i = 1; i + 1 < f.corners.size(); ++i) {
      const Vec3 &b = mesh.points[f.corners[i]], &c = mesh.points[f.corners[i + 1]];
      v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
    }
  }
  return v;
}

// Every edge of a face is met once the other way by another face.
void expect_closed(const Mesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const Mesh::Face f : mesh.faces())
    for (std::size_t i = 0; i < f.corners.size(); ++i) ++edges[{f.corners[i], f.corners[(i + 1) % f.corners.size()]}];
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1) << "edge used twice the same way";
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << "open edge";
  }
}

int faces_of(const Mesh& mesh, Surface s) {
  int n = 0;
  for (const Mesh::Face f : mesh.faces()) n += f.surface == s;
  return n;
}

}  // namespace

TEST(BuildingMesh, BoxIsClosedWithItsVolume) {
  Mesh m = building_mesh(prism({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {}}, 5));
  expect_closed(m);
  EXPECT_DOUBLE_EQ(volume(m), 500);  // positive: faces point outwards
  EXPECT_EQ(m.face_count(), 4u + 2u + 2u);
  EXPECT_EQ(faces_of(m, Surface::Roof), 2);
}

TEST(BuildingMesh, CourtyardAndLShapeAreClosed) {
  geom::Polygon courtyard{{{0, 0}, {20, 0}, {20, 20}, {0, 20}}, {{{5, 5}, {5, 15}, {15, 15}, {15, 5}}}};
  Mesh c = building_mesh(prism(courtyard, 9));
  expect_closed(c);
  EXPECT_NEAR(volume(c), (400 - 100) * 9, 1e-9);
  Mesh l = building_mesh(prism({{{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}}, {}}, 3));
  expect_closed(l);
  EXPECT_NEAR(volume(l), 64 * 3, 1e-9);
}

TEST(BuildingMesh, ObjHoldsEveryBuildingAtFullPrecision) {
  auto dir = testing_util::temp_dir("obj");
  std::vector<Building> buildings{prism({{{0.1, 0.2}, {10, 0}, {10, 10}, {0, 10}}, {}}, 5),
                                  prism({{{500000.123456789, 5000000.5}, {500010, 5000000.5}, {500010, 5000010}}, {}}, 7.25)};
  buildings[0].id = 0, buildings[1].id = 1;
  const std::vector<Mesh> meshes = structure_meshes(buildings, {}, nullptr);
  MeshCounts counts = write_meshes(
      {.ground = {}, .ground_layers = {}, .buildings = buildings, .models = {}, .meshes = meshes, .clutter = {}, .crs = {}},
      dir / "city.obj", dir / "city.ply");
  EXPECT_EQ(counts.vertices, 8u + 6u);
  EXPECT_EQ(counts.faces, 8u + 3u + 1u + 1u);
  std::ifstream in(dir / "city.obj");
  std::string line, text;
  std::size_t vertices = 0, faces = 0;
  while (std::getline(in, line)) {
    text += line + "\n";
    if (line.rfind("v ", 0) == 0) ++vertices;
    if (line.rfind("f ", 0) == 0) {
      ++faces;
      std::istringstream ss(line.substr(2));
      std::size_t i;
      while (ss >> i) EXPECT_LE(i, counts.vertices);
    }
  }
  EXPECT_EQ(vertices, counts.vertices);
  EXPECT_EQ(faces, counts.faces);
  EXPECT_NE(text.find("v 500000.123456789 5000000.5 7.25"), std::string::npos) << "shortest round-trip doubles";
  EXPECT_TRUE(std::filesystem::exists(dir / "city.mtl"));
  // The PLY holds the same mesh: its header counts, then the same doubles.
  std::ifstream ply(dir / "city.ply");
  std::string ply_text((std::istreambuf_iterator<char>(ply)), std::istreambuf_iterator<char>());
  EXPECT_NE(ply_text.find("element vertex " + std::to_string(counts.vertices) + "\n"), std::string::npos);
  EXPECT_NE(ply_text.find("element face " + std::to_string(counts.faces) + "\n"), std::string::npos);
  EXPECT_NE(ply_text.find("\n500000.123456789 5000000.5 7.25\n"), std::string::npos);
}

// The ground's layers follow the buildings in both files: in the OBJ an object and a
// material each, named as city.glb names its materials; in the PLY each triangle with its
// layer's surface class.
TEST(BuildingMesh, ObjAndPlyCarryTheGroundLayers) {
  auto dir = testing_util::temp_dir("obj-ground");
  Ground ground;
  ground.zones.push_back({ZoneType::Park, {{{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {}}});
  ground.water.push_back({{{40, 0}, {60, 0}, {60, 100}, {40, 100}}, {}});
  ground.road_areas.push_back({0, true, RoadSurface::Carriageway, {{{40, 45}, {60, 45}, {60, 55}, {40, 55}}, {}}});
  const std::vector<GroundLayer> layers = ground_layers(ground, nullptr);
  std::vector<std::string> names;
  std::size_t layer_vertices = 0, layer_triangles = 0;
  for (const GroundLayer& l : layers) {
    names.push_back(l.name);
    layer_vertices += l.mesh.vertices.size(), layer_triangles += l.mesh.triangles.size();
  }
  EXPECT_EQ(names, (std::vector<std::string>{"terrain", "ground_park", "water", "road", "bridge"}));
  std::vector<Building> buildings{prism({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {}}, 5)};
  buildings[0].id = 0, buildings[0].stable_id = 7;  // OBJ names a building by the id the layers write
  const std::vector<Mesh> meshes = structure_meshes(buildings, {}, nullptr);
  MeshCounts counts = write_meshes(
      {.ground = ground, .ground_layers = layers, .buildings = buildings, .models = {}, .meshes = meshes, .clutter = {}, .crs = {}},
      dir / "city.obj", dir / "city.ply");
  EXPECT_EQ(counts.vertices, 8u + layer_vertices);
  EXPECT_EQ(counts.faces, 8u + layer_triangles);

  std::ifstream obj(dir / "city.obj");
  std::vector<std::string> objects, materials;
  for (std::string line; std::getline(obj, line);) {
    if (line.rfind("o ", 0) == 0) objects.push_back(line.substr(2));
    if (line.rfind("usemtl ", 0) == 0) materials.push_back(line.substr(7));
  }
  EXPECT_EQ(objects, (std::vector<std::string>{"building_7", "terrain", "ground_park", "water", "road", "bridge"}));
  EXPECT_EQ(std::vector<std::string>(materials.end() - 5, materials.end()), names);
  std::ifstream mtl_file(dir / "city.mtl");
  const std::string mtl((std::istreambuf_iterator<char>(mtl_file)), std::istreambuf_iterator<char>());
  for (const std::string& n : names) EXPECT_NE(mtl.find("newmtl " + n + "\nKd "), std::string::npos) << n;

  // PLY faces: vertex count, indices, surface class.
  std::ifstream ply(dir / "city.ply");
  std::string line;
  while (std::getline(ply, line) && line != "end_header") {
  }
  for (std::size_t v = 0; v < counts.vertices; ++v) std::getline(ply, line);
  std::map<int, std::size_t> by_surface;
  for (std::size_t f = 0; f < counts.faces; ++f) {
    ASSERT_TRUE(std::getline(ply, line));
    std::istringstream s(line);
    int n = 0, surface = -1;
    std::size_t index;
    s >> n;
    for (int k = 0; k < n; ++k) {
      s >> index;
      EXPECT_LT(index, counts.vertices);
    }
    s >> surface;
    ASSERT_TRUE(s) << line;
    ++by_surface[surface];
  }
  EXPECT_FALSE(std::getline(ply, line));
  std::map<int, std::size_t> expected{{0, 2}, {1, 4}, {2, 2}};  // the building: ground, walls, roof
  for (const GroundLayer& l : layers) expected[3 + static_cast<int>(l.kind)] += l.mesh.triangles.size();
  EXPECT_EQ(by_surface, expected);
}

namespace {

Building roofed(geom::Polygon footprint, double height, const std::string& roof) {
  Building b = prism(std::move(footprint), height);
  BuildingSettings p = default_building_settings(ZoneType::Residential);
  p.roof = roof;
  choose_roof(b, p);
  return b;
}

// Every face of the mesh, seen from above, is a simple polygon (walls are upright and skipped).
void expect_simple_roof_faces(const Mesh& m) {
  for (const Mesh::Face f : m.faces()) {
    if (f.surface != Surface::Roof) continue;
    geom::Ring r;
    for (std::uint32_t v : f.corners) r.push_back({m.points[v][0], m.points[v][1]});
    EXPECT_TRUE(geom::ring_is_simple(r));
  }
}

}  // namespace

TEST(BuildingMesh, HippedRoofsOnLAndUShapesAreClosedAndSimple) {
  geom::Polygon l{{{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}, {}};
  geom::Polygon u{{{0, 0}, {24, 0}, {24, 20}, {16, 20}, {16, 8}, {8, 8}, {8, 20}, {0, 20}}, {}};
  for (const auto& [footprint, area] : {std::pair{l, 256.0}, std::pair{u, 384.0}}) {
    Building b = roofed(footprint, 12, "hipped");
    ASSERT_EQ(b.roof, "hipped");
    EXPECT_NEAR(b.eaves, 12 - 4 * std::tan(M_PI / 6), 1e-9);  // arms 8 wide: the ridge 4 in
    Mesh m = building_mesh(b);
    expect_closed(m);
    expect_simple_roof_faces(m);
    EXPECT_GT(volume(m), area * b.eaves);
    EXPECT_LT(volume(m), area * b.height);
  }
}

TEST(BuildingMesh, GabledRoofHasItsPrismVolume) {
  Building b = roofed({{{0, 0}, {10, 0}, {10, 6}, {0, 6}}, {}}, 9, "gabled");
  ASSERT_EQ(b.roof, "gabled");
  double rise = 3 * std::tan(M_PI / 6);
  EXPECT_NEAR(b.eaves, 9 - rise, 1e-12);
  Mesh m = building_mesh(b);
  expect_closed(m);
  EXPECT_NEAR(volume(m), 60 * b.eaves + 0.5 * 6 * rise * 10, 1e-9);
  EXPECT_EQ(faces_of(m, Surface::Wall), 4 + 2);  // four walls and two gables
}

TEST(BuildingMesh, RoofTooTallForTheBuildingFallsBackToFlat) {
  Building b = roofed({{{0, 0}, {40, 0}, {40, 40}, {0, 40}}, {}}, 8, "hipped");  // the rise would be 11.5 m
  EXPECT_EQ(b.roof, "flat");
  EXPECT_EQ(b.eaves, 8);
}

TEST(BuildingMesh, OnASlopeTheWallsReachTheLowestGroundAndTheHeightCountsFromTheHighest) {
  // Values rising west to east: heights 0 m to 20 m over 100 m, linear between pixel centres.
  TerrainSpec spec{"ramp.png", {0, 0, 100, 100}, 0, 20};
  std::vector<float> values;
  for (int row = 0; row < 10; ++row)
    for (int col = 0; col < 10; ++col) values.push_back(static_cast<float>(col) / 9);
  Terrain ramp(spec, 10, 10, values);
  Building b = prism({{{30, 30}, {50, 30}, {50, 45}, {30, 45}}, {}}, 7);
  std::tie(b.base, b.floor) = ramp.range_under(b.polygon.outer);
  EXPECT_EQ(b.base, ramp.height_at({30, 30}));
  EXPECT_EQ(b.floor, ramp.height_at({50, 30}));
  EXPECT_NEAR(b.floor - b.base, 20.0 * 20 / 90, 1e-6);  // 20 m across, 20 m per 90 m between the outer centres
  Mesh m = building_mesh(b);
  expect_closed(m);
  double low = INFINITY, high = -INFINITY;
  for (const Vec3& p : m.points) low = std::min(low, p[2]), high = std::max(high, p[2]);
  EXPECT_EQ(low, b.base);
  EXPECT_EQ(high, b.floor + 7);
  EXPECT_NEAR(volume(m), 300 * (b.floor + 7 - b.base), 1e-9);
}

TEST(Ground, DrapedSurfacesBendWithTheTerrainAndCoverThePolygon) {
  // A ridge along x = 50: a road crossing it must rise over it, not cut through.
  TerrainSpec spec{"ridge.png", {0, 0, 100, 100}, 0, 30};
  std::vector<float> values;
  for (int row = 0; row < 20; ++row)
    for (int col = 0; col < 20; ++col) values.push_back(1.0f - std::abs(col - 9.5f) / 9.5f);
  Terrain ridge(spec, 20, 20, values);
  geom::Polygon road{{{10, 45}, {90, 45}, {90, 55}, {10, 55}}, {{{40, 48}, {40, 52}, {60, 52}, {60, 48}}}};
  GroundMesh m;
  drape(road, &ridge, 0.1, m);
  double area = 0, top = -INFINITY;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    double twice = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    EXPECT_GT(twice, 0);  // counter-clockwise from above
    area += twice / 2;
  }
  for (const Vec3& v : m.vertices) {
    EXPECT_EQ(v[2], ridge.height_at({v[0], v[1]}) + 0.1);
    top = std::max(top, v[2]);
  }
  EXPECT_NEAR(area, 800 - 80, 1e-9);
  EXPECT_GT(top, 28.0);  // the crest (30 m) is reached, not bridged from the road's ends (~3 m)
  GroundMesh flat;
  drape(road, nullptr, 0, flat);
  EXPECT_EQ(flat.vertices.size(), 8u);
}

namespace {

// The height of the mesh's surface over p: the highest triangle over it, NaN where none is.
double surface_at(const GroundMesh& m, geom::Vec2 p) {
  double top = NAN;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const double d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if (d == 0) continue;  // upright: a bank
    const double u = ((b[0] - p.x) * (c[1] - p.y) - (c[0] - p.x) * (b[1] - p.y)) / d;
    const double v = ((c[0] - p.x) * (a[1] - p.y) - (a[0] - p.x) * (c[1] - p.y)) / d;
    const double w = 1 - u - v;
    if (u < 0 || v < 0 || w < 0) continue;
    const double z = u * a[2] + v * b[2] + w * c[2];
    top = std::isnan(top) ? z : std::max(top, z);
  }
  return top;
}

}  // namespace

// Without a heightmap, drawn water lies some decimetres under the flat land around it,
// with a bank edge down to it and its bed under it: it lay at the lawn's level.
TEST(Ground, DrawnWaterOnFlatLandLiesUnderItsBanks) {
  const geom::Polygon pond{{{20, 20}, {80, 25}, {75, 80}, {25, 70}}, {}};
  const double level = water_level(pond, nullptr);
  EXPECT_DOUBLE_EQ(level, -kWaterBelowBank);
  EXPECT_LE(level, -0.3);
  const GroundMesh m = terrain_mesh(nullptr, {0, 0, 100, 100}, {0, 0, 100, 100}, {pond}, 512);
  EXPECT_DOUBLE_EQ(surface_at(m, {50, 50}), level - kBedDepth);  // the bed, under the water
  EXPECT_DOUBLE_EQ(surface_at(m, {10, 50}), 0);                  // the land
  EXPECT_DOUBLE_EQ(surface_at(m, {50, 95}), 0);
  // The bank: upright from the land down to the bed along the whole outline.
  double bank = 0;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double up = u[0] * v[1] - u[1] * v[0];
    if (std::abs(up) < 1e-9)
      bank += std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2]) / 2;
  }
  EXPECT_NEAR(bank, geom::perimeter(pond) * (kBedDepth - level), 1e-6);
}

// A road over drawn water on flat land is a bridge: its deck over the water with room
// under it, parapets along its sides over the water (not across its ends on the banks),
// and piers down to the bed. It lay flush on the water, its deck's underside in it.
TEST(Ground, ABridgeOverDrawnWaterHasADeckPiersAndParapets) {
  Ground ground;
  ground.water.push_back({{{20, 0}, {80, 0}, {80, 100}, {20, 100}}, {}});
  ground.road_areas.push_back({0, true, RoadSurface::Carriageway, {{{20, 45}, {80, 45}, {80, 55}, {20, 55}}, {}}});
  ground.roads.push_back({RoadClass::Highway, 10, -1, -1, true, {{20, 50}, {80, 50}}, 0, {}});
  const BridgeDecks decks = bridge_decks(ground, nullptr);
  const double top = decks.height[0], level = water_level(ground.water[0], nullptr);
  EXPECT_DOUBLE_EQ(top, kRoadOverTerrain);
  GroundMesh m;
  bridge_structure(ground, nullptr, decks, m);
  std::set<double> heights;
  for (const Vec3& v : m.vertices) heights.insert(v[2]);
  // The bed, the deck's underside, its top and the parapets' top.
  ASSERT_EQ(heights.size(), 4u);
  const std::vector<double> z(heights.begin(), heights.end());
  EXPECT_DOUBLE_EQ(z[0], level - kBedDepth);  // the piers' feet
  EXPECT_LT(z[0], level);
  EXPECT_GE(z[1] - level, 0.5) << "no room under the deck";
  EXPECT_DOUBLE_EQ(z[2], top);
  EXPECT_NEAR(z[3], top + 1, 0.1);
  // Two piers (a third and two thirds of the way), four corners each at the bed.
  EXPECT_EQ(std::count_if(m.vertices.begin(), m.vertices.end(), [&](const Vec3& v) { return v[2] == z[0]; }), 8);
  // The parapets' tops: along both sides, none across the ends.
  double south = 0, north = 0, ends = 0;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    if (a[2] != z[3] || b[2] != z[3] || c[2] != z[3]) continue;
    const double area = std::abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2;
    const double x = (a[0] + b[0] + c[0]) / 3, y = (a[1] + b[1] + c[1]) / 3;
    if (x < 21 || x > 79) ends += area * (y > 46 && y < 54);
    (y < 50 ? south : north) += area;
  }
  EXPECT_NEAR(south, 60 * kParapetThickness, 1e-9);
  EXPECT_NEAR(north, 60 * kParapetThickness, 1e-9);
  EXPECT_EQ(ends, 0);
}

namespace {

// A river across a 200 m map of 20 x 20 pixels (x 80 to 120 m), running off its north and
// south edges; the land 40 m high west of it, rising east from 42 m.
Terrain river_terrain() {
  std::vector<float> values;
  for (int row = 0; row < 20; ++row)
    for (int col = 0; col < 20; ++col)
      values.push_back(col >= 8 && col <= 11 ? 0.0f : col < 8 ? 0.4f : 0.42f + 0.01f * (col - 12));
  return Terrain({"river.png", {0, 0, 200, 200}, 0, 100}, 20, 20, values);
}

const geom::Polygon kRiver{{{80, 0}, {120, 0}, {120, 200}, {80, 200}}, {}};

// How steeply each triangle rises: its height's gradient; infinite for an upright one.
double steepest(const GroundMesh& m) {
  double most = 0;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double nx = u[1] * v[2] - u[2] * v[1], ny = u[2] * v[0] - u[0] * v[2], nz = u[0] * v[1] - u[1] * v[0];
    most = std::max(most, nz == 0 ? INFINITY : std::hypot(nx, ny) / std::abs(nz));
  }
  return most;
}

}  // namespace

// On a heightmap the banks slope from the land down under the water (1 in 2 here), and
// past the map's edge, where the river runs off it, the ground runs on without walls:
// banks were upright walls from the land's edge to the bed, the land fell into them from
// 40 m to the water pixels' 0 within a pixel, and past the edges the mirrored water
// pixels made walled grooves.
TEST(Ground, BanksSlopeFromTheLandUnderTheWaterAndNoWallStandsPastTheWatersEnd) {
  const Terrain t = river_terrain();
  const double level = water_level(kRiver, &t);
  EXPECT_NEAR(level, 40 - kWaterBelowBank, 1e-5);  // the heightmap's values are floats
  // The ground 100 m past the north and south edges, where the river runs off the map.
  const GroundMesh m = terrain_mesh(&t, {0, -100, 200, 300}, {0, -100, 200, 300}, {kRiver}, 512);
  // Where two banks meet at a corner of the outline a triangle spans both: √2 steeper.
  EXPECT_LE(steepest(m), kBankSlope * std::sqrt(2) + 1e-3);
  EXPECT_NEAR(surface_at(m, {100, 100}), level - kBedDepth, 1e-9);  // the bed in the middle
  // West, the land at 40 m down to the bed 1.3 m under it, 2.6 m out; east, from 42 m, 6.6 m out.
  EXPECT_NEAR(surface_at(m, {80, 100}), 40, 1e-5);
  EXPECT_NEAR(surface_at(m, {81.3, 100}), level - kBedDepth + 0.65, 0.1);
  EXPECT_NEAR(surface_at(m, {120 - 3.3, 100}), (42 + level - kBedDepth) / 2, 0.1);
  EXPECT_NEAR(surface_at(m, {100, 250}), 40, 1.5);  // past the north edge: land, level with the river's
}

// A road on the land ending at the water's edge stays on the land: it ran down the bank
// as the terrain fell to the water pixels' 0.
TEST(Ground, ARoadEndingAtTheWaterStaysOnTheLand) {
  const Terrain t = river_terrain();
  GroundMesh road;
  drape({{{50, 95}, {80, 95}, {80, 105}, {50, 105}}, {}}, &t, kRoadOverTerrain, road);
  double low = INFINITY, high = -INFINITY;
  for (const Vec3& v : road.vertices) low = std::min(low, v[2]), high = std::max(high, v[2]);
  EXPECT_NEAR(low, 40 + kRoadOverTerrain, 1e-6);
  EXPECT_NEAR(high, 40 + kRoadOverTerrain, 1e-6);
}

// A library model whose third triangle cannot join the first two (it runs along their shared
// edge the way the first does): every placed instance keeps all three, the third on vertices
// of its own at the same points, after its foundation where it has one; the many instances'
// meshes (the model's triangles joined once) are each instance's own (joined for it alone).
TEST(BuildingMesh, EveryInstanceOfAModelKeepsTheTrianglesThatCannotJoin) {
  ModelLibrary library;
  library.models.resize(1);
  TriangleMesh& fin = library.models[0].mesh;
  fin.vertices = {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, -1, 0}, {1, 0, 1}};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  std::vector<ModelInstance> models(2);
  for (int k = 0; k < 2; ++k) {
    ModelInstance& m = models[static_cast<std::size_t>(k)];
    m.id = k;
    m.polygon.outer = {{10.0 * k, 0}, {10.0 * k + 2, 0}, {10.0 * k + 2, 2}, {10.0 * k, 2}};
    m.placed.position = {10.0 * k + 1, 1};
    m.placed.model = 0, m.placed.angle = 0.5 * k;
    m.floor = 2;
    m.base = k == 0 ? 2 : 0.5;  // the second on a foundation
  }
  const std::vector<Mesh> meshes = structure_meshes({}, models, &library);
  for (std::size_t k = 0; k < 2; ++k) {
    const Mesh& mesh = meshes[k];
    const Mesh alone = model_mesh(models[k], &library);
    EXPECT_EQ(mesh.points, alone.points);
    std::vector<std::vector<std::uint32_t>> faces, alone_faces;
    for (const Mesh::Face f : mesh.faces()) faces.emplace_back(f.corners.begin(), f.corners.end());
    for (const Mesh::Face f : alone.faces()) alone_faces.emplace_back(f.corners.begin(), f.corners.end());
    EXPECT_EQ(faces, alone_faces);
    // The foundation: 4 walls and 2 triangles a cap over 8 points; then 5 + 3 points, 3 triangles.
    const std::size_t first = k == 0 ? 0 : 8;
    ASSERT_EQ(mesh.points.size(), first + 8);
    ASSERT_EQ(faces.size(), (k == 0 ? 0u : 8u) + 3u);
    const std::vector<std::uint32_t> third = faces.back();
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(third[static_cast<std::size_t>(c)], first + 5) << "the third triangle shares a vertex";
      EXPECT_EQ(mesh.points[third[static_cast<std::size_t>(c)]],
                models[k].placed.apply(fin.vertices[static_cast<std::size_t>(fin.triangles[2][static_cast<std::size_t>(c)])],
                                       models[k].floor));
    }
  }
}
