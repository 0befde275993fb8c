// Street clutter on a small city of four streets: two main roads crossing (a
// junction of major roads), two local roads meeting them (approaches of minor roads to major
// ones). Where clutter may stand, checked against the exact map; which junctions get traffic
// lights and stop signs; alternate sides; channels steering the model; a library of clutter
// alone; and validate catching clutter where it must not stand.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fstream>

#include <tbb/global_control.h>

#include "generate/errors.h"
#include "generate/export/validate.h"
#include "generate/pipeline.h"
#include "generate/placement/street_nodes.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"
#include "tests/clutter_sketch.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace exacity;
using namespace clutter_sketch;

namespace {

City built(const fs::path& sketch) {
  StageClock clock(nullptr, kCityStages);
  return build_city(load_sketch(sketch), clock, {}, ExactWork::Kept);  // the checks read the map and lots
}

// The junction whose node is nearest p.
const StreetJunction& nearest(const std::vector<StreetJunction>& junctions, geom::Vec2 p) {
  return *std::min_element(junctions.begin(), junctions.end(), [&](const auto& a, const auto& b) {
    return geom::distance(a.at, p) < geom::distance(b.at, p);
  });
}

// Every piece of clutter stands strictly inside a sidewalk face or a lot, by the exact map,
// its base held by the lot and apart from its buildings. Returns (on sidewalks, in lots).
std::pair<int, int> expect_on_sidewalks_or_lots(const City& city) {
  int on_sidewalk = 0, in_lot = 0;
  for (const Clutter& c : city.clutter.items) {
    const int label = city.network.map.map.label_at(c.spot);
    EXPECT_GE(label, 0) << "clutter " << c.instance.id << " lies on an edge of the map";
    if (label < 0) continue;
    const FaceLabel& l = city.network.map.labels[label];
    EXPECT_NE(l.cover, Cover::Water) << c.instance.id;
    EXPECT_FALSE(l.bridge) << c.instance.id;
    if (l.cover == Cover::Road) {
      EXPECT_EQ(l.surface, RoadSurface::Sidewalk) << "clutter " << c.instance.id << " stands on a " << name(l.surface);
      EXPECT_EQ(c.instance.lot, -1);
      ++on_sidewalk;
      continue;
    }
    EXPECT_GE(c.instance.lot, 0) << "clutter " << c.instance.id << " stands on open land";
    if (c.instance.lot < 0) continue;
    EXPECT_TRUE(city.lots[c.instance.lot].cell.contains(c.spot)) << c.instance.id;
    EXPECT_TRUE(city.lots[c.instance.lot].cell.holds(c.instance.polygon.outer)) << c.instance.id;
    for (const Building& b : city.buildings)
      EXPECT_FALSE(geom::rings_meet(b.polygon.outer, c.instance.polygon.outer)) << c.instance.id;
    ++in_lot;
  }
  return {on_sidewalk, in_lot};
}

}  // namespace

TEST(Clutter, StandsOnASidewalkOrInALotNeverOnACarriagewayJunctionOrWaterCheckedOnTheMap) {
  for (const std::string sidewalks : {"", R"(, "roads": {"local": {"sidewalk": 2.5}, "main": {"sidewalk": 3}})"}) {
    const City city = built(four_streets("stands", sidewalks, all_of_the_library()));
    ASSERT_GT(city.clutter.items.size(), 20u) << sidewalks;
    const auto [on_sidewalk, in_lot] = expect_on_sidewalks_or_lots(city);
    if (sidewalks.empty()) {
      EXPECT_EQ(on_sidewalk, 0);
      EXPECT_GT(in_lot, 20) << "without sidewalks, clutter stands in the lots' setback";
    } else {
      EXPECT_GT(on_sidewalk, 20) << "with sidewalks, clutter stands on them";
    }
  }
}

TEST(Clutter, ASpotOnAnotherRoadsCarriagewayIsRefusedAndCounted) {
  // A local road 10.2 m north of the main road's centre line: its kerb is 0.2 m from the main
  // road's, so its south side's lamps, half a metre past its kerb, would stand on the main road.
  const fs::path sketch = four_streets("carriageway", "", all_of_the_library());
  std::ifstream in(sketch);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  text.insert(text.find(R"({"type": "Feature", "properties": {"road": "main"})"),
              R"({"type": "Feature", "properties": {"road": "local"},
                  "geometry": {"type": "LineString", "coordinates": [[-180, 10.2], [-120, 10.2]]}},
      )");
  write(sketch, text);
  const City city = built(sketch);
  expect_on_sidewalks_or_lots(city);
  int refused = 0;
  for (const auto& [key, n] : city.clutter.tally.missed)
    if (key.first == "lamp" && key.second == "on a carriageway or in a junction") refused += n;
  EXPECT_GE(refused, 2) << "60 m of road, a lamp every 20 m on its south side";
}

TEST(Clutter, TrafficLightsStandOnlyAtJunctionsOfMajorRoadsAndStopSignsOnlyOnLocalApproaches) {
  const City city = built(four_streets("junctions", "", all_of_the_library()));
  const std::vector<StreetJunction> junctions = street_junctions(city.ground.roads);
  int lights = 0, signs = 0;
  for (const Clutter& c : city.clutter.items) {
    if (c.instance.kind != ModelKind::TrafficLight && c.instance.kind != ModelKind::Sign) continue;
    const StreetJunction& j = nearest(junctions, c.spot);
    EXPECT_LT(geom::distance(j.at, c.spot), 25) << "clutter " << c.instance.id << " stands far from any junction";
    if (c.instance.kind == ModelKind::TrafficLight) {
      ++lights;
      EXPECT_TRUE(j.of_major_roads()) << "a traffic light at a junction that is no junction of major roads";
      EXPECT_LT(geom::distance(j.at, {0, 0}), 1) << "the only junction of major roads is the crossing at (0, 0)";
    } else {
      ++signs;
      EXPECT_TRUE(j.local_meets_major()) << "a stop sign where no local road meets a major one";
      EXPECT_EQ(city.ground.roads[c.road].road_class, RoadClass::Local) << "a stop sign on a major road's approach";
    }
  }
  EXPECT_EQ(lights, 4) << "one at each corner of the crossing";
  EXPECT_EQ(signs, 2) << "one on each local road where it meets the main road";
}

TEST(Clutter, AnAlternateEntryStandsOnEachSideInTurn) {
  const City city = built(four_streets(
      "alternate", "", std::string(kHouse) + R"(, {"file": "lamp.obj", "kind": "lamp", "up": "z", "scale": [1, 1],
                                                   "spacing": 20, "side": "alternate"})"));
  int pairs = 0;
  for (std::size_t r = 0; r < city.ground.roads.size(); ++r) {
    const geom::Polyline& line = city.ground.roads[r].line;
    // The streets are straight: its lamps by distance along it, and the side each stands on.
    const geom::Vec2 a = line.front(), u = geom::unit_along(line.front(), line.back());
    std::vector<std::pair<double, int>> lamps;
    for (const Clutter& c : city.clutter.items)
      if (c.road == static_cast<int>(r))
        lamps.push_back({geom::dot(c.spot - a, u), geom::cross(u, c.spot - a) > 0 ? 1 : -1});
    std::sort(lamps.begin(), lamps.end());
    for (std::size_t k = 1; k < lamps.size(); ++k) {
      const double gap = lamps[k].first - lamps[k - 1].first;
      EXPECT_GT(gap, 10) << "road " << r << ": two lamps of one station (both sides) at " << lamps[k].first;
      if (gap >= 25) continue;  // a spot between them found no place
      ++pairs;
      EXPECT_NE(lamps[k].second, lamps[k - 1].second) << "road " << r << " at " << lamps[k].first;
    }
  }
  EXPECT_GT(pairs, 30) << "neighbouring lamps to compare";
}

TEST(Clutter, ChannelsSteerWhichEntryStandsWhere) {
  // A channel 0 on the west half and 1 on the east half; two lamps asking for 0 and 1.
  const fs::path sketch = four_streets(
      "channels",
      R"(, "channels": {"east": {"image": "east.png", "bounds": [-200, -150, 200, 150]}}, "channel_sharpness": 40)",
      std::string(kHouse) + R"(,
      {"name": "west_lamp", "file": "lamp.obj", "kind": "lamp", "up": "z", "spacing": 20, "channels": {"east": 0}},
      {"name": "east_lamp", "file": "lamp.obj", "kind": "lamp", "up": "z", "spacing": 20, "channels": {"east": 1}})");
  const std::vector<unsigned char> pixels{0, 0, 255, 255};
  auto out = OIIO::ImageOutput::create((sketch.parent_path() / "east.png").string());
  ASSERT_TRUE(out &&
              out->open((sketch.parent_path() / "east.png").string(), OIIO::ImageSpec(4, 1, 1, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
  const City city = built(sketch);
  int west = 0, east = 0;
  for (const Clutter& c : city.clutter.items) {
    const std::string& model = city.library->models[c.instance.placed.model].name;
    if (model == "west_lamp") {
      ++west;
      EXPECT_LT(c.spot.x, 5) << "a west lamp on the east half";
    } else {
      ++east;
      EXPECT_GT(c.spot.x, -5) << "an east lamp on the west half";
    }
  }
  EXPECT_GT(west, 10);
  EXPECT_GT(east, 10);
}

TEST(Clutter, ALibraryOfClutterAloneLeavesTheLotsToExtrudedBuildings) {
  const City city = built(four_streets("alone", "", std::string(kLamp) + "," + kSign));
  EXPECT_GT(city.buildings.size(), 10u) << "extruded buildings fill the lots";
  EXPECT_TRUE(city.models.empty());
  EXPECT_GT(city.clutter.items.size(), 10u);
  for (const Clutter& c : city.clutter.items)
    for (const Building& b : city.buildings)
      EXPECT_FALSE(geom::rings_meet(b.polygon.outer, c.instance.polygon.outer)) << c.instance.id;
}

TEST(Clutter, SpotsWithoutGroundAreCountedNotDropped) {
  // A park along the east of the east-west road: lamps may stand in parks, but a park has
  // neither sidewalk nor lot, so its spots are counted in the tally.
  const fs::path sketch = four_streets("park", "", all_of_the_library());
  std::ifstream in(sketch);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string park = R"({"type": "Feature", "properties": {"zone": "park"},
       "geometry": {"type": "Polygon", "coordinates": [[[110, 1], [200, 1], [200, 60], [110, 60], [110, 1]]]}},
      )";
  text.insert(text.find(R"({"type": "Feature", "properties": {"road": "main"})"), park);
  write(sketch, text);
  const City city = built(sketch);
  int no_ground = 0;
  for (const auto& [key, n] : city.clutter.tally.missed)
    if (key.first == "lamp" && key.second.find("no sidewalk or lot") != std::string::npos) no_ground += n;
  EXPECT_GE(no_ground, 3) << "about 90 m of park along the road, a lamp every 20 m";
  for (const Clutter& c : city.clutter.items)
    EXPECT_FALSE(c.spot.x > 110 && c.spot.x < 200 && c.spot.y > 1 && c.spot.y < 60) << "clutter in the park";
}

namespace {

// The four streets with all of the library, generated valid into `name`/out; its clutter layer.
fs::path valid_clutter_layer(const std::string& name) {
  const fs::path sketch = four_streets(name, "", all_of_the_library());
  const fs::path out = sketch.parent_path() / "out";
  EXPECT_TRUE(generate_city(load_sketch(sketch), out, nullptr).valid);
  return out / "vector" / "clutter.geojson";
}

}  // namespace

TEST(Clutter, ValidateFindsClutterWhereItMustNotStand) {
  const fs::path layer = valid_clutter_layer("validate");
  const fs::path out = layer.parent_path().parent_path();
  std::ifstream in(layer);
  const std::string good((std::istreambuf_iterator<char>(in)), {});
  auto broken = [&](const std::function<void(nlohmann::ordered_json&)>& edit) {
    nlohmann::ordered_json doc = nlohmann::ordered_json::parse(good);
    edit(doc["features"]);
    write(layer, doc.dump());
    const Validation v = validate_output(out);
    write(layer, good);
    std::string all;
    for (const std::string& p : v.problems) all += p + "\n";
    return all;
  };
  EXPECT_EQ(broken([](auto&) {}), "");
  // On the east-west road's centre line, in its carriageway; then at the crossing.
  EXPECT_NE(broken([](auto& f) {
              f[0]["geometry"]["coordinates"] = {-150.5, 0.25};
            }).find("(carriageway)"),
            std::string::npos);
  EXPECT_NE(broken([](auto& f) {
              f[0]["geometry"]["coordinates"] = {0.5, 0.5};
            }).find("clutter.geojson features[0]"),
            std::string::npos);
  EXPECT_NE(broken([](auto& f) { f[1]["properties"]["id"] = f[0]["properties"]["id"]; }).find("not unique"),
            std::string::npos);
  EXPECT_NE(broken([](auto& f) { f[0]["properties"]["road"] = 9999; }).find("names no feature of roads.geojson"),
            std::string::npos);
  EXPECT_NE(broken([](auto& f) { f[0]["properties"]["kind"] = "building"; }).find("no clutter kind"),
            std::string::npos);
}

// Validation checks the clutter in runs of pieces at once: on a layer of 10,000 pieces (the
// city's first one again and again, each with an id of its own), problems broken into
// different runs are stated in the pieces' order, each once, a repeated id at its later
// piece, and the same at one thread and at two; a number written "1.0e" sends the layer to
// the JSON parser, which names it.
TEST(Clutter, ValidationStatesClutterProblemsInThePiecesOrderAtAnyThreadCount) {
  const fs::path layer = valid_clutter_layer("validate-runs");
  const fs::path out = layer.parent_path().parent_path();
  std::ifstream in(layer);
  nlohmann::ordered_json doc = nlohmann::ordered_json::parse(std::string((std::istreambuf_iterator<char>(in)), {}));
  nlohmann::ordered_json& features = doc["features"];
  ASSERT_FALSE(features.empty());
  const nlohmann::ordered_json first = features[0];
  features = nlohmann::ordered_json::array();
  for (int i = 0; i < 10000; ++i) {
    features.push_back(first);
    features.back()["properties"]["id"] = 1000000 + i;
  }
  features[9000]["properties"]["road"] = 9999;
  features[100]["properties"]["kind"] = "fountain";
  features[9500]["properties"]["id"] = 1005000;  // piece 5000's
  features[4096]["properties"]["heading"] = 360;
  // One feature a line, as write_geojson lays a layer out, so the scanner reads it.
  std::string text = "{\"type\":\"FeatureCollection\",\"name\":\"clutter\",\"features\":[";
  for (std::size_t i = 0; i < features.size(); ++i) text += (i ? ",\n" : "\n") + features[i].dump();
  text += "\n]}\n";
  write(layer, text);
  auto problems = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::string all;
    for (const std::string& p : validate_output(out).problems) all += p + "\n";
    return all;
  };
  const std::string expected =
      "clutter.geojson features[100]: \"kind\" is \"fountain\", no clutter kind\n"
      "clutter.geojson features[4096]: \"heading\" is not degrees in [0, 360)\n"
      "clutter.geojson features[9000]: \"road\" 9999 names no feature of roads.geojson\n"
      "clutter.geojson features[9500]: its id is missing or not unique\n";
  EXPECT_EQ(problems(1), expected);
  EXPECT_EQ(problems(2), expected);
  const std::size_t at = text.find("\"heading\":", text.find("1000007"));
  ASSERT_NE(at, std::string::npos);
  text.insert(text.find_first_of(",}", at + 10), ".0e");
  write(layer, text);
  const std::string broken = problems(2);
  EXPECT_NE(broken.find("clutter.geojson: not a GeoJSON FeatureCollection"), std::string::npos) << broken;
  EXPECT_EQ(problems(1), broken);
}

TEST(Clutter, NoLampHeadHangsInOrNearATreesCrown) {
  // Exacity's own lamps and trees on residential streets (lamps every 30 m, trees every
  // 12 m, each half a metre in from the kerb): the lamp's head hangs 1.3 m out at 5.8 m,
  // where a tree's crown is when the tree stands beside the lamp. Measured on the meshes:
  // a head's glass is "near" a crown when it is within 1 m of one of its leaves' points or
  // inside the cylinder around the tree's trunk that holds them.
  const fs::path dir = testing_util::temp_dir("clutter-crowns");
  write(dir / "sketch.geojson", R"({"type": "FeatureCollection", "exacity": {"seed": 5,
    "zones": {"residential": {"layout": "streets"}}}, "features": [
      {"type": "Feature", "properties": {"zone": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[-200, -150], [200, -150], [200, 150], [-200, 150], [-200, -150]]]}},
      {"type": "Feature", "properties": {"road": "main"},
       "geometry": {"type": "LineString", "coordinates": [[-200, 0], [200, 0]]}},
      {"type": "Feature", "properties": {"road": "main"},
       "geometry": {"type": "LineString", "coordinates": [[0, -150], [0, 150]]}}]})");
  const City city = built(dir / "sketch.geojson");
  const ModelLibrary& lib = *city.model_library();
  struct Crown {
    std::vector<Vec3> leaves;
    Vec3 axis;
    double radius = 0, low = INFINITY, high = -INFINITY;
  };
  std::vector<Crown> crowns;
  std::vector<Vec3> heads;
  for (const Clutter& c : city.clutter.items) {
    const Model& m = lib.models[static_cast<std::size_t>(c.instance.placed.model)];
    const TriangleMesh& mesh = m.mesh;
    if (m.kind == ModelKind::Tree) {
      Crown crown;
      crown.axis = c.instance.placed.apply({0, 0, 0}, c.instance.floor);
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (mesh.materials[static_cast<std::size_t>(mesh.material[t])].name == "bark") continue;
        for (int k : mesh.triangles[t]) {
          const Vec3 v = c.instance.placed.apply(mesh.vertices[static_cast<std::size_t>(k)], c.instance.floor);
          crown.leaves.push_back(v);
          crown.radius = std::max(crown.radius, std::hypot(v[0] - crown.axis[0], v[1] - crown.axis[1]));
          crown.low = std::min(crown.low, v[2]), crown.high = std::max(crown.high, v[2]);
        }
      }
      crowns.push_back(std::move(crown));
    } else if (m.kind == ModelKind::Lamp) {
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        if (mesh.materials[static_cast<std::size_t>(mesh.material[t])].name == "lamp_glass")
          for (int k : mesh.triangles[t])
            heads.push_back(c.instance.placed.apply(mesh.vertices[static_cast<std::size_t>(k)], c.instance.floor));
    }
  }
  ASSERT_GT(crowns.size(), 40u);
  ASSERT_GT(heads.size(), 40u);
  int near = 0;
  for (const Vec3& h : heads)
    for (const Crown& crown : crowns) {
      const bool inside = std::hypot(h[0] - crown.axis[0], h[1] - crown.axis[1]) < crown.radius &&
                          crown.low < h[2] && h[2] < crown.high;
      const bool close = std::any_of(crown.leaves.begin(), crown.leaves.end(), [&](const Vec3& v) {
        return std::hypot(h[0] - v[0], h[1] - v[1], h[2] - v[2]) < 1;
      });
      if (inside || close) {
        ++near;
        break;
      }
    }
  EXPECT_EQ(near, 0) << "of " << heads.size() << " lamp head corners";
  std::map<std::string, int> refused;
  for (const auto& [key, n] : city.clutter.tally.missed) refused[key.first] += n;
  EXPECT_LT(refused["tree"], static_cast<int>(crowns.size())) << "most trees still stand";
}
