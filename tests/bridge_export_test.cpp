// Bridges as the 3D exports hold them (docs/design.md, Ground meshes): a highway
// over a river in a heightmap valley, read back from city.glb, CityJSON and city.obj, has
// its deck level from abutment to abutment over the whole crossing, on piers standing on
// the riverbed; then roads that cross water in awkward ways keep a deck at every crossing.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <set>

#include "generate/mesh/bridges.h"
#include "geom/measure.h"
#include "tests/cli_util.h"
#include "tests/river_sketch.h"
#include "tests/test_util.h"

using namespace cli_util;
using nlohmann::json;

namespace {

using Point = std::array<double, 3>;
using Triangle = std::array<Point, 3>;

// One export's ground, as triangles in city coordinates (x east, y north, z up).
struct Ground3d {
  std::string format;
  std::vector<Triangle> road;     // road surfaces, the bridges' decks among them
  std::vector<Triangle> bridge;   // the decks' sides and undersides, and the piers
  std::vector<Triangle> terrain;  // the terrain, the banks and the beds under water
  double precision = 0;           // how far apart two heights the format holds may be and mean one
};

// city.glb: the ground mesh's primitives by material, in the root node's frame (y up, -z north).
Ground3d read_glb(const fs::path& out) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, (out / "city.glb").string())) << error;
  Ground3d g{"city.glb", {}, {}, {}, 1e-5};
  if (model.scenes.empty()) return g;
  const tinygltf::Node& root = model.nodes.at(model.scenes.at(0).nodes.at(0));
  const auto& t = root.translation;
  auto data = [&](int accessor) {
    const tinygltf::Accessor& a = model.accessors.at(accessor);
    const tinygltf::BufferView& v = model.bufferViews.at(a.bufferView);
    return model.buffers.at(v.buffer).data.data() + v.byteOffset + a.byteOffset;
  };
  for (int child : root.children) {
    const tinygltf::Node& node = model.nodes.at(child);
    if (node.name != "ground") continue;
    for (const tinygltf::Primitive& p : model.meshes.at(node.mesh).primitives) {
      const std::string& material = model.materials.at(p.material).name;
      std::vector<Triangle>* into = material == "road"      ? &g.road
                                    : material == "bridge"  ? &g.bridge
                                    : material == "terrain" ? &g.terrain
                                                            : nullptr;
      if (!into) continue;
      const auto* position = reinterpret_cast<const float*>(data(p.attributes.at("POSITION")));
      const auto* index = reinterpret_cast<const std::uint32_t*>(data(p.indices));
      const std::size_t count = model.accessors.at(p.indices).count;
      for (std::size_t k = 0; k + 2 < count; k += 3) {
        Triangle tri;
        for (int c = 0; c < 3; ++c) {
          const float* q = position + 3 * index[k + c];
          tri[c] = {t[0] + q[0], -(t[2] + q[2]), t[1] + q[1]};
        }
        into->push_back(tri);
      }
    }
  }
  return g;
}

// city.obj: the objects road, bridge and terrain.
Ground3d read_obj(const fs::path& out) {
  Ground3d g{"city.obj", {}, {}, {}, 0};
  std::ifstream in(out / "city.obj");
  std::vector<Point> vertices;
  std::vector<Triangle>* into = nullptr;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string key;
    s >> key;
    if (key == "v") {
      Point p;
      s >> p[0] >> p[1] >> p[2];
      vertices.push_back(p);
    } else if (key == "o") {
      std::string name;
      s >> name;
      into = name == "road" ? &g.road : name == "bridge" ? &g.bridge : name == "terrain" ? &g.terrain : nullptr;
    } else if (key == "f" && into) {
      std::size_t a, b, c;
      s >> a >> b >> c;
      EXPECT_TRUE(s && a >= 1 && b >= 1 && c >= 1 && std::max({a, b, c}) <= vertices.size()) << line;
      into->push_back({vertices.at(a - 1), vertices.at(b - 1), vertices.at(c - 1)});
    }
  }
  return g;
}

// CityJSON: the Road objects, the Bridge object and the TINRelief, every surface a triangle.
Ground3d read_cityjson(const fs::path& out) {
  const json doc = json::parse(read(out / "city.city.json"));
  Ground3d g{"city.city.json", {}, {}, {}, 1e-3};
  const json& scale = doc["transform"]["scale"];
  const json& translate = doc["transform"]["translate"];
  auto vertex = [&](int i) {
    const json& v = doc["vertices"].at(i);
    Point p;
    for (int k = 0; k < 3; ++k) p[k] = v[k].get<double>() * scale[k].get<double>() + translate[k].get<double>();
    return p;
  };
  for (const auto& [id, object] : doc["CityObjects"].items()) {
    const std::string type = object["type"];
    std::vector<Triangle>* into = type == "Road"        ? &g.road
                                  : type == "Bridge"    ? &g.bridge
                                  : type == "TINRelief" ? &g.terrain
                                                        : nullptr;
    if (!into) continue;
    for (const json& surface : object["geometry"].at(0)["boundaries"]) {
      const json& ring = surface.at(0);
      EXPECT_EQ(ring.size(), 3u) << id;
      if (ring.size() == 3) into->push_back({vertex(ring[0]), vertex(ring[1]), vertex(ring[2])});
    }
  }
  return g;
}

geom::Vec2 plan(const Point& p) { return {p[0], p[1]}; }
geom::Vec2 centroid(const Triangle& t) {
  return {(t[0][0] + t[1][0] + t[2][0]) / 3, (t[0][1] + t[1][1] + t[2][1]) / 3};
}

geom::Polygon polygon(const json& coordinates) {
  auto ring = [](const json& r) {
    geom::Ring out;
    for (const json& p : r) out.push_back({p[0].get<double>(), p[1].get<double>()});
    out.pop_back();  // GeoJSON repeats the first point
    return out;
  };
  geom::Polygon p{ring(coordinates.at(0)), {}};
  for (std::size_t k = 1; k < coordinates.size(); ++k) p.holes.push_back(ring(coordinates[k]));
  return p;
}

// Near an outline: within a centimetre of it.
constexpr double kOnOutline = 0.01;

// The triangle's height over q, NaN when q is not over it in plan (or it stands upright).
double height_over(const Triangle& t, geom::Vec2 q) {
  const geom::Vec2 a = plan(t[0]), b = plan(t[1]), c = plan(t[2]);
  const double d = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (std::abs(d) < 1e-9) return NAN;
  const double u = ((b.x - q.x) * (c.y - q.y) - (b.y - q.y) * (c.x - q.x)) / d;
  const double v = ((c.x - q.x) * (a.y - q.y) - (c.y - q.y) * (a.x - q.x)) / d;
  const double w = 1 - u - v, eps = 1e-9;
  if (u < -eps || v < -eps || w < -eps) return NAN;
  return u * t[0][2] + v * t[1][2] + w * t[2][2];
}

// What the vector layers say about the crossings.
struct Crossings {
  std::vector<geom::Polygon> decks;  // the bridge road areas
  std::vector<geom::Polygon> water;
  struct Line {
    geom::Ring points;
    double width;
  };
  std::vector<Line> lines;  // the bridges' centre lines
};

Crossings crossings(const fs::path& out) {
  Crossings c;
  auto features = [&](const char* layer) {
    return json::parse(read(out / "vector" / (std::string(layer) + ".geojson")))["features"];
  };
  for (const json& f : features("road_areas"))
    if (f["properties"]["bridge"]) c.decks.push_back(polygon(f["geometry"]["coordinates"]));
  for (const json& f : features("water")) c.water.push_back(polygon(f["geometry"]["coordinates"]));
  for (const json& f : features("roads"))
    if (f["properties"]["bridge"]) {
      Crossings::Line line{{}, f["properties"]["width"].get<double>()};
      for (const json& p : f["geometry"]["coordinates"])
        line.points.push_back({p[0].get<double>(), p[1].get<double>()});
      c.lines.push_back(line);
    }
  return c;
}

struct Bridge3d {
  double top;                    // the road surface on the deck
  std::size_t pier_corners = 0;  // the piers' bottom corners
  std::size_t parapet_corners = 0;  // the parapets' top corners
};

// Each bridge road area's deck in one export: the road triangles over it all at one height,
// the structure around it at that height (the deck's sides' tops) or a deck's
// thickness lower (its underside, the piers' tops), or lower still on the riverbed (the
// piers' feet, each under a pier top), and no bank rising over the deck's ends. Every point
// of the bridges' centre lines and carriageways over water lies under a deck. By area.
std::vector<Bridge3d> check_decks(const Ground3d& g, const Crossings& c) {
  SCOPED_TRACE(g.format);
  std::vector<Bridge3d> bridges;
  std::vector<Triangle> decks;
  for (const geom::Polygon& area : c.decks) {
    std::set<double> tops;
    for (const Triangle& t : g.road)
      if (geom::odd_crossings(area, centroid(t))) {
        decks.push_back(t);
        for (const Point& p : t) tops.insert(p[2]);
      }
    if (tops.size() != 1) {
      ADD_FAILURE() << (tops.empty() ? "no deck over a bridge's road area"
                                     : "the deck is not level: from " + std::to_string(*tops.begin()) + " to " +
                                           std::to_string(*tops.rbegin()) + " m");
      continue;
    }
    Bridge3d bridge{*tops.begin()};
    // The underside: the structure's highest corner under the top, a deck's thickness down
    // (kDeckThickness, thinner over water just under it).
    const double side_top = bridge.top;
    double underside = -INFINITY;
    for (const Triangle& t : g.bridge)
      for (const Point& p : t)
        if ((geom::odd_crossings(area, plan(p)) || geom::distance_to_outline(area, plan(p)) <= kOnOutline) &&
            p[2] < side_top - g.precision)
          underside = std::max(underside, p[2]);
    EXPECT_GE(underside, side_top - exacity::kDeckThickness - g.precision);
    EXPECT_LE(underside, side_top - exacity::kThinnestDeck + g.precision);
    std::set<std::pair<double, double>> pier_tops;
    std::vector<Point> feet;
    for (const Triangle& t : g.bridge)
      for (const Point& p : t) {
        if (!geom::odd_crossings(area, plan(p)) && geom::distance_to_outline(area, plan(p)) > kOnOutline) continue;
        if (std::abs(p[2] - side_top) <= g.precision) continue;
        if (std::abs(p[2] - (side_top + exacity::kParapetHeight)) <= g.precision) {
          ++bridge.parapet_corners;
          continue;
        }
        if (std::abs(p[2] - underside) <= g.precision) {
          pier_tops.insert({p[0], p[1]});
          continue;
        }
        EXPECT_LT(p[2], underside) << "the bridge's structure rises off its deck at " << p[0] << ", " << p[1];
        feet.push_back(p);
      }
    std::set<std::pair<double, double>> corners;
    for (const Point& foot : feet) {
      corners.insert({foot[0], foot[1]});
      EXPECT_TRUE(pier_tops.count({foot[0], foot[1]}))
          << "a pier's foot at " << foot[0] << ", " << foot[1] << " under no pier top";
      double bed = NAN;
      for (const Triangle& t : g.terrain)
        if (const double z = height_over(t, plan(foot)); std::isfinite(z))
          bed = std::isfinite(bed) ? std::min(bed, z) : z;
      // On the bed, or into a bank where the pier stands on one.
      EXPECT_LE(foot[2], bed + 0.005 + g.precision)
          << "a pier's foot at " << foot[0] << ", " << foot[1] << " floats over the riverbed";
    }
    bridge.pier_corners = corners.size();
    // The banks under the deck's ends reach its top at most (their vertices along the water's
    // outline sample the terrain at other points than the deck's height did: 5 cm).
    for (const Triangle& t : g.terrain)
      for (const Point& p : t)
        if (distance_to_outline(area, plan(p)) < kOnOutline) {
          EXPECT_LE(p[2], side_top + 0.05) << "a bank over the deck's end at " << p[0] << ", " << p[1];
        }
    bridges.push_back(bridge);
  }
  // In plan: along each bridge's centre line, and a quarter metre inside its sides, every
  // half metre over water.
  int over_water = 0, uncovered = 0;
  for (const Crossings::Line& line : c.lines)
    for (std::size_t k = 1; k < line.points.size(); ++k) {
      const geom::Vec2 a = line.points[k - 1], b = line.points[k];
      const geom::Vec2 along = geom::unit_along(a, b), across = geom::left_normal({0, 0}, along);
      for (double s = 0; s <= geom::distance(a, b); s += 0.5)
        for (double off : {-(line.width / 2 - 0.25), 0.0, line.width / 2 - 0.25}) {
          const geom::Vec2 q = a + along * s + across * off;
          if (std::none_of(c.water.begin(), c.water.end(), [&](const geom::Polygon& w) { return geom::odd_crossings(w, q); }))
            continue;
          ++over_water;
          if (std::none_of(decks.begin(), decks.end(),
                           [&](const Triangle& t) { return std::isfinite(height_over(t, q)); }))
            ++uncovered;
        }
    }
  EXPECT_GT(over_water, 0);
  EXPECT_EQ(uncovered, 0) << "points of the crossing under no deck, of " << over_water;
  return bridges;
}

// The sketch in its own folder, generated; the output folder.
fs::path generate(const std::string& name, double (*value)(int, int), const std::string& roads) {
  const fs::path dir = testing_util::temp_dir("bridge-" + name);
  std::ofstream(dir / "sketch.geojson") << river_sketch::write(dir, value, river_sketch::kPark + ", " + roads);
  const Result r = run("generate " + (dir / "sketch.geojson").string() + " -o " + (dir / "out").string() + " -q");
  EXPECT_EQ(r.code, 0) << name << ": " << r.out;
  return dir / "out";
}

}  // namespace

// A highway across the straight river (x 80 to 120 m): one bridge of 40 m, so one pier.
TEST(BridgeExport, DeckIsLevelFromAbutmentToAbutmentOverTheWholeCrossingOnPiersInEveryExport) {
  const fs::path out =
      generate("straight", river_sketch::straight_river, river_sketch::highway("[-20, 100], [220, 100]"));
  const Crossings c = crossings(out);
  ASSERT_FALSE(c.decks.empty());
  ASSERT_EQ(c.lines.size(), 1u);
  std::map<std::string, double> top;
  for (const Ground3d& g : {read_glb(out), read_cityjson(out), read_obj(out)}) {
    ASSERT_FALSE(g.bridge.empty()) << g.format << " holds no bridge";
    const std::vector<Bridge3d> bridges = check_decks(g, c);
    EXPECT_EQ(bridges.size(), c.decks.size()) << g.format;
    if (bridges.empty()) continue;
    for (const Bridge3d& b : bridges) EXPECT_EQ(b.top, bridges[0].top) << g.format << ": one bridge, one level";
    std::size_t pier_corners = 0;
    for (const Bridge3d& b : bridges) pier_corners += b.pier_corners;
    EXPECT_EQ(pier_corners, 4u) << g.format << ": one pier in the middle";
    std::size_t parapet_corners = 0;
    for (const Bridge3d& b : bridges) parapet_corners += b.parapet_corners;
    EXPECT_GT(parapet_corners, 0u) << g.format << ": parapets along the deck";
    top[g.format] = bridges[0].top;
  }
  // The same deck in each, metres over the riverbed.
  EXPECT_NEAR(top["city.glb"], top["city.obj"], 1e-5);
  EXPECT_NEAR(top["city.city.json"], top["city.obj"], 1e-3);
  EXPECT_GT(top["city.obj"], 5);
}

// Roads that cross water awkwardly: each generates, validates and keeps a level deck over
// every crossing, with a pier every 30 m or less between its ends, in every export.
TEST(BridgeExport, AwkwardCrossingsEachKeepTheirDeck) {
  // The river along the map's east edge (x 170 to 200 m), the terrain past it mirrored.
  auto east_edge_river = [](int col, int) { return col >= 17 ? 0.0 : 0.4 + 0.01 * std::abs(col - 17); };
  // A river one pixel (10 m) wide, x 100 to 110 m.
  auto narrow_river = [](int col, int) { return col == 10 ? 0.0 : 0.4 + 0.01 * std::abs(col - 10); };
  struct Case {
    std::string name;
    double (*value)(int, int);
    std::string roads;
    std::size_t bridges, piers;
  };
  const std::vector<Case> cases{
      // Four crossings of 41 m.
      {"zigzag", river_sketch::straight_river,
       river_sketch::highway("[20, 20], [180, 60], [20, 100], [180, 140], [20, 180]"), 4, 4},
      // 30 m from the west bank to the map's edge.
      {"map-edge", east_edge_river, river_sketch::highway("[120, 100], [260, 100]"), 1, 1},
      // 10 m.
      {"short", narrow_river, river_sketch::highway("[-20, 100], [220, 100]"), 1, 0},
      // 14 degrees to the river: 165 m over it.
      {"shallow", river_sketch::straight_river, river_sketch::highway("[70, -20], [130, 220]"), 1, 5},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    const fs::path out = generate(k.name, k.value, k.roads);
    EXPECT_EQ(json::parse(read(out / "report.json"))["validation"]["ok"], true);
    const Crossings c = crossings(out);
    EXPECT_EQ(c.lines.size(), k.bridges) << "bridge centre lines";
    for (const Ground3d& g : {read_glb(out), read_cityjson(out), read_obj(out)}) {
      const std::vector<Bridge3d> bridges = check_decks(g, c);
      EXPECT_EQ(bridges.size(), c.decks.size()) << g.format;
      std::size_t pier_corners = 0;
      for (const Bridge3d& b : bridges) pier_corners += b.pier_corners;
      EXPECT_EQ(pier_corners, 4 * k.piers) << g.format;
    }
  }
}
