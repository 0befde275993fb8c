// End to end through the exacity binary: every example generates and validates (exactly,
// and independently with GEOS), its map, glTF and CityJSON hold the city; validate catches
// tampered layers; bad input exits 2 with one line and no output folder. The slow runs that
// repeat these (determinism, renders, the schemas) are in examples_test.cpp.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <functional>

#include <tiny_gltf.h>

#include "generate/export/geojson.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace cli_util;

namespace {

using nlohmann::json;

json layer(const fs::path& out, const std::string& name) {
  return json::parse(read(out / "vector" / (name + ".geojson")))["features"];
}

// map.svg's shapes, group by group in drawing order: each path's d, each polyline's points.
std::vector<std::pair<std::string, std::vector<std::string>>> svg_groups(const std::string& svg) {
  auto attribute = [](const std::string& line, const std::string& name) {
    std::size_t at = line.find(" " + name + "=\"");
    if (at == std::string::npos) return std::string("(none)");
    at += name.size() + 3;
    return line.substr(at, line.find('"', at) - at);
  };
  std::vector<std::pair<std::string, std::vector<std::string>>> groups;
  std::istringstream in(svg);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("<g ", 0) == 0) groups.push_back({attribute(line, "class"), {}});
    else if (groups.empty()) continue;
    else if (line.rfind("<path ", 0) == 0) groups.back().second.push_back(attribute(line, "d"));
    else if (line.rfind("<polyline ", 0) == 0) groups.back().second.push_back(attribute(line, "points"));
  }
  return groups;
}

// What map.svg must draw: every feature of each layer in the layer's order, bottom to top,
// each point relative to the top-left corner of the box around the ground's outer rings
// and the centre lines (north up), written as the layers write numbers.
std::vector<std::pair<std::string, std::vector<std::string>>> expected_svg_groups(const fs::path& out) {
  double min_x = INFINITY, max_y = -INFINITY;
  auto extend = [&](const json& points) {
    for (const auto& p : points) min_x = std::min(min_x, p[0].get<double>()), max_y = std::max(max_y, p[1].get<double>());
  };
  for (const char* cover : {"zones", "water", "road_areas"})
    for (const auto& f : layer(out, cover)) extend(f["geometry"]["coordinates"][0]);
  for (const auto& f : layer(out, "roads")) extend(f["geometry"]["coordinates"]);
  auto point = [&](const json& p) {
    return exacity::format_number(p[0].get<double>() - min_x) + "," + exacity::format_number(max_y - p[1].get<double>());
  };
  std::vector<std::pair<std::string, std::vector<std::string>>> groups;
  for (const char* name : {"zones", "parks", "lots", "buildings", "water", "road_areas"}) {
    groups.push_back({name, {}});
    // Parks: the green blocks.
    for (const auto& f : layer(out, std::string(name) == "parks" ? "blocks" : name)) {
      if (std::string(name) == "parks" && !f["properties"]["green"].get<bool>()) continue;
      std::string d;
      for (const auto& ring : f["geometry"]["coordinates"]) {
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) d += (i ? "L" : "M") + point(ring[i]);  // rings close with Z
        d += "Z";
      }
      groups.back().second.push_back(d);
    }
  }
  groups.push_back({"roads", {}});
  for (const auto& f : layer(out, "roads")) {
    std::string points;
    for (const auto& p : f["geometry"]["coordinates"]) points += (points.empty() ? "" : " ") + point(p);
    groups.back().second.push_back(points);
  }
  groups.push_back({"legend", {}});
  return groups;
}

// The positions of one mesh's primitives in city coordinates (the glTF is y up, -z north,
// under the root node's translation).
std::vector<std::pair<double, double>> mesh_points(const tinygltf::Model& model, int mesh, const tinygltf::Node& root) {
  std::vector<std::pair<double, double>> points;
  for (const auto& primitive : model.meshes.at(mesh).primitives) {
    const tinygltf::Accessor& a = model.accessors.at(primitive.attributes.at("POSITION"));
    const tinygltf::BufferView& view = model.bufferViews.at(a.bufferView);
    const unsigned char* data = model.buffers.at(view.buffer).data.data() + view.byteOffset + a.byteOffset;
    const std::size_t stride = view.byteStride ? view.byteStride : 3 * sizeof(float);
    for (std::size_t i = 0; i < a.count; ++i) {
      float p[3];
      std::memcpy(p, data + i * stride, sizeof p);
      points.push_back({root.translation[0] + p[0], -(root.translation[2] + p[2])});
    }
  }
  return points;
}

struct GlbCounts {
  int buildings = 0, models = 0;
};

// Every extruded building of buildings.geojson stands in city.glb's building mesh (a vertex
// at each footprint corner, within the single floats' millimetre), and every placed model
// is a node of its own, in id order, standing in its footprint's box.
GlbCounts check_glb_holds_every_building(const fs::path& out) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  GlbCounts counts;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, (out / "city.glb").string())) << error;
  if (model.scenes.empty()) return counts;
  const tinygltf::Node& root = model.nodes.at(model.scenes.at(0).nodes.at(0));
  EXPECT_EQ(root.name, "city");
  std::map<std::pair<long, long>, std::vector<std::pair<double, double>>> building_points;  // by metre square
  std::vector<const tinygltf::Node*> model_nodes;
  for (int child : root.children) {
    const tinygltf::Node& n = model.nodes.at(child);
    if (n.name == "ground") continue;
    if (n.name == "buildings") {
      for (auto [x, y] : mesh_points(model, n.mesh, root))
        building_points[{std::lround(std::floor(x)), std::lround(std::floor(y))}].push_back({x, y});
    } else {
      model_nodes.push_back(&n);
    }
  }
  auto near_a_vertex = [&](double x, double y) {
    for (long i = -1; i <= 1; ++i)
      for (long j = -1; j <= 1; ++j) {
        auto it = building_points.find({std::lround(std::floor(x)) + i, std::lround(std::floor(y)) + j});
        if (it == building_points.end()) continue;
        for (auto [px, py] : it->second)
          if (std::abs(px - x) < 1e-3 && std::abs(py - y) < 1e-3) return true;
      }
    return false;
  };
  std::size_t next_model = 0;
  for (const auto& f : layer(out, "buildings")) {
    const json& outline = f["geometry"]["coordinates"][0];
    if (f["properties"]["model"].is_null()) {
      ++counts.buildings;
      for (const auto& p : outline)
        EXPECT_TRUE(near_a_vertex(p[0], p[1])) << "building " << f["properties"]["id"] << ": no vertex at " << p;
      continue;
    }
    ++counts.models;
    if (next_model >= model_nodes.size()) {
      ADD_FAILURE() << "building " << f["properties"]["id"] << ": a placed model with no node in city.glb";
      continue;
    }
    const tinygltf::Node& n = *model_nodes[next_model++];
    EXPECT_GE(n.mesh, 0);
    const double x = root.translation[0] + n.translation.at(0), y = -(root.translation[2] + n.translation.at(2));
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const auto& p : outline) x0 = std::min(x0, p[0].get<double>()), x1 = std::max(x1, p[0].get<double>()),
                                  y0 = std::min(y0, p[1].get<double>()), y1 = std::max(y1, p[1].get<double>());
    EXPECT_TRUE(x >= x0 && x <= x1 && y >= y0 && y <= y1)
        << "building " << f["properties"]["id"] << ": its node stands at " << x << ", " << y << ", off its footprint";
  }
  EXPECT_EQ(model_nodes.size(), next_model) << "city.glb places more models than buildings.geojson lists";
  return counts;
}

}  // namespace

TEST(Cli, EveryExampleGeneratesAndValidates) {
  auto list = examples();
  ASSERT_GE(list.size(), 3u);
  GlbCounts in_glb;
  for (const fs::path& sketch : list) {
    fs::path out = testing_util::temp_dir("cli-" + sketch.stem().string()) / "out";
    Result g = run("generate " + sketch.string() + " -o " + out.string() + " --quiet");
    ASSERT_EQ(g.code, 0) << sketch << "\n" << g.out;
    for (const char* f : {"vector/zones.geojson", "vector/water.geojson", "vector/roads.geojson",
                          "vector/road_areas.geojson", "vector/blocks.geojson", "vector/lots.geojson",
                          "vector/buildings.geojson", "map.svg", "city.obj", "city.mtl", "city.ply", "city.city.json",
                          "city.glb", "report.json"})
      EXPECT_TRUE(fs::exists(out / f)) << f;
    auto report = nlohmann::json::parse(read(out / "report.json"));
    EXPECT_EQ(report["validation"]["ok"], true);
    EXPECT_GT(report["counts"]["zones"].get<int>(), 0);
    // The plausibility targets (docs/design.md, Plausibility), in every zone with lots.
    const auto& zones = report["statistics"]["zones"];
    int zones_with_lots = 0;
    for (const auto& [zone, z] : zones.items()) {
      zones_with_lots += z.contains("lots");
      EXPECT_EQ(z["blocks"]["share_area_over_4x_block_area"].get<double>(), 0.0) << sketch << " " << zone;
      EXPECT_EQ(z["lots"]["share_touching_road"].get<double>(), 1.0) << sketch << " " << zone;
      EXPECT_EQ(z["lots"]["share_depth_over_width_outside_0.5_5"].get<double>(), 0.0) << sketch << " " << zone;
      EXPECT_LE(z["lots"]["share_without_building"].get<double>(), 0.03) << sketch << " " << zone;
      EXPECT_LT(z["footprints"]["share_sharp_angle"].get<double>(), 0.01) << sketch << " " << zone;
      if (zone != "residential") continue;
      EXPECT_LT(z["footprints"]["share_under_5m_across"].get<double>(), 0.05) << sketch;
      EXPECT_LE(z["footprints"]["area_m2"]["max"].get<double>(), 2000) << sketch;
    }
    EXPECT_GT(zones_with_lots, 0) << sketch << ": no zone's statistics to hold to the targets";
    EXPECT_EQ(report["statistics"]["streets"]["dead_ends"].get<int>(), 0) << sketch;

    Result v = run("validate " + out.string());
    EXPECT_EQ(v.code, 0) << v.out;
    EXPECT_NE(v.out.find("valid"), std::string::npos);

    EXPECT_EQ(std::system((geos_check(out) + " > /dev/null").c_str()), 0) << "GEOS disagrees: " << geos_check(out);
    std::string gltf = node_tool("check_glb.mjs") + " " + (out / "city.glb").string();
    EXPECT_EQ(std::system((gltf + " > /dev/null").c_str()), 0) << "the Khronos glTF validator finds errors: " << gltf;
    // Closed solids, vertex indices in range, templates that exist; the schemas are examples_test's.
    Result cityjson = shell(node_tool("check_cityjson.mjs") + " " + (out / "city.city.json").string());
    EXPECT_EQ(cityjson.code, 0) << cityjson.out;

    EXPECT_EQ(svg_groups(read(out / "map.svg")), expected_svg_groups(out)) << sketch << ": map.svg";
    GlbCounts counts = check_glb_holds_every_building(out);
    in_glb.buildings += counts.buildings, in_glb.models += counts.models;
  }
  EXPECT_GT(in_glb.buildings, 0) << "no example has an extruded building to find in city.glb";
  EXPECT_GT(in_glb.models, 0) << "no example has a placed model to find in city.glb";
}

// Generates the town, lets `tamper` edit one layer, and returns what validate says.
Result validate_tampered(const std::string& name, const std::string& layer,
                         const std::function<void(nlohmann::json&)>& tamper) {
  fs::path out = testing_util::temp_dir("cli-tamper-" + name) / "out";
  EXPECT_EQ(run("generate " + (kSource / "examples" / "town.geojson").string() + " -o " + out.string() + " -q").code, 0);
  fs::path file = out / "vector" / (layer + ".geojson");
  auto doc = nlohmann::json::parse(read(file));
  tamper(doc);
  std::ofstream(file) << doc.dump();
  return run("validate " + out.string());
}

TEST(Cli, ValidateCatchesAMovedZoneVertex) {
  Result v = validate_tampered("zone", "zones", [](nlohmann::json& doc) {
    auto& ring = doc["features"][0]["geometry"]["coordinates"][0];
    ring[1][0] = ring[1][0].get<double>() + 3.0;  // now it overlaps a neighbour or leaves a gap
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("problem:"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesAMissingBlock) {
  Result v = validate_tampered("block", "blocks", [](nlohmann::json& doc) { doc["features"].erase(0); });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("holds no block"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesARoadEndingInTheOpen) {
  Result v = validate_tampered("end", "roads", [](nlohmann::json& doc) {
    for (auto& f : doc["features"])
      if (!f["properties"]["level"].is_null()) {
        auto& first = f["geometry"]["coordinates"][0];
        first[0] = first[0].get<double>() + 0.5;
        first[1] = first[1].get<double>() + 0.25;
        break;
      }
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("ends in the open"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesADisconnectedRegion) {
  Result v = validate_tampered("region", "roads", [](nlohmann::json& doc) {
    // Carry the last grown road far away from the rest of its region.
    for (auto it = doc["features"].rbegin(); it != doc["features"].rend(); ++it) {
      if ((*it)["properties"]["region"].is_null()) continue;
      for (auto& p : (*it)["geometry"]["coordinates"]) p[0] = p[0].get<double>() + 5000;
      break;
    }
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("are not connected"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesARegionWhoseStreetsAreAnIsland) {
  Result v = validate_tampered("island", "roads", [](nlohmann::json& doc) {
    // Carry all the roads of one region far away, together: connected, but to nothing else.
    const auto region = doc["features"].back()["properties"]["region"];
    for (auto& f : doc["features"])
      if (f["properties"]["region"] == region)
        for (auto& p : f["geometry"]["coordinates"]) p[0] = p[0].get<double>() + 5000;
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("reach no other road"), std::string::npos) << v.out;
  EXPECT_EQ(v.out.find("are not connected"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesAReferenceToNoFeature) {
  Result v = validate_tampered("reference", "buildings", [](nlohmann::json& doc) {
    doc["features"][0]["properties"]["lot"] = 999999;
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("\"lot\" 999999 names no feature of lots.geojson"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesCentreLinesThatMeetBetweenVertices) {
  Result v = validate_tampered("noded", "roads", [](nlohmann::json& doc) {
    // A new centre line across the middle of the first one's first segment, with no vertex there.
    auto line = doc["features"][0]["geometry"]["coordinates"];
    const double x0 = line[0][0], y0 = line[0][1], x1 = line[1][0], y1 = line[1][1];
    const double mx = (x0 + x1) / 2, my = (y0 + y1) / 2, len = std::hypot(x1 - x0, y1 - y0);
    const double nx = -(y1 - y0) / len * 5, ny = (x1 - x0) / len * 5;
    nlohmann::json crossing = doc["features"][0];
    crossing["properties"]["id"] = 999999;
    crossing["geometry"]["coordinates"] = {{mx - nx, my - ny}, {mx + nx, my + ny}};
    doc["features"].push_back(crossing);
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("meets another centre line between its vertices"), std::string::npos) << v.out;
}

TEST(Cli, StatsMeasureTheCityAndRealData) {
  fs::path dir = testing_util::temp_dir("cli-stats");
  ASSERT_EQ(run("generate " + (kSource / "examples" / "town.geojson").string() + " -o " + (dir / "out").string() + " -q").code, 0);
  // Real data in lon/lat: a 0.001 degree square footprint at 60 degrees north (about 55.6 x 111.2 m).
  std::ofstream(dir / "real.geojson") << R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "MultiPolygon", "coordinates":
      [[[[25, 60], [25.001, 60], [25.001, 60.001], [25, 60.001], [25, 60]]]]}}]})";
  Result s = run("stats " + (dir / "out").string() + " --real " + (dir / "real.geojson").string());
  EXPECT_EQ(s.code, 0) << s.out;
  EXPECT_NE(s.out.find("share of lots touching a road area: 1.0"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("dead ends 0"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("footprints: 1, area m2 median 6182"), std::string::npos) << s.out;
  Result bad = run("stats " + (dir / "nowhere").string());
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_NE(bad.out.find("not an output folder"), std::string::npos) << bad.out;
}

TEST(Cli, BadInputExitsTwoWithOneLineAndNoOutput) {
  fs::path dir = testing_util::temp_dir("cli-bad");
  struct Case {
    std::string name, text, expect;
  };
  const std::string zone = R"({"type":"Feature","properties":{"zone":"park"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[9,0],[9,9],[0,0]]]}})";
  std::vector<Case> cases = {
      {"syntax", "{\"type\": \"FeatureCollection\",\n \"features\": [}", "malformed JSON"},
      {"nogeom", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"park"},"geometry":null}]})", "no geometry"},
      {"zone", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"parc"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}]})", "did you mean \"park\""},
      {"heightmap", R"({"type":"FeatureCollection","exacity":{"terrain":{"heightmap":"missing.png","bounds":[0,0,10,10]}},"features":[)" + zone + "]}", "not found"},
      {"key", R"({"type":"FeatureCollection","exacity":{"colour":1},"features":[)" + zone + "]}", "unknown key \"colour\""},
      {"typenull", R"({"type":null,"features":[]})", "GeoJSON FeatureCollection"},
      {"typezero", R"({"type":0,"features":[]})", "GeoJSON FeatureCollection"},
      {"typeobject", R"({"type":{},"features":[]})", "GeoJSON FeatureCollection"},
      {"huge", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"park"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[9,0],[9,-1e308],[0,0]]]}}]})", "beyond 1e10 m"},
      {"far", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"residential"},"geometry":{"type":"Polygon","coordinates":[[[4e12,4e12],[4.000000001e12,4e12],[4.000000001e12,4.000000001e12],[4e12,4e12]]]}}]})", "beyond 1e10 m"},
      {"vast", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"residential"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1e6,0],[1e6,1e6],[0,0]]]}}]})", "more than the 50000 one run builds"},
      {"library", R"({"type":"FeatureCollection","exacity":{"models":"missing.json"},"features":[)" + zone + "]}", "cannot read the model library"},
      {"model", R"({"type":"FeatureCollection","exacity":{"models":"bad-library.json"},"features":[)" + zone + "]}", "line 2: vertex index 2 points to none"},
      {"grammar", R"({"type":"FeatureCollection","exacity":{"zones":{"park":{"layout":"grammar","grammar":"bad.grammar"}}},"features":[)" + zone + "]}", "bad.grammar:2: the corner count \"5\""},
      {"deadend", R"({"type":"FeatureCollection","exacity":{"roads":{"dead_ends":"error"}},"features":[)" + zone + R"(,{"type":"Feature","properties":{"road":"local"},"geometry":{"type":"LineString","coordinates":[[0,0],[9,9]]}}]})", "meeting no other road"},
  };
  std::ofstream(dir / "bad-library.json") << R"({"models": [{"file": "bad.obj", "zones": ["residential"]}]})";
  std::ofstream(dir / "bad.obj") << "v 0 0 0\nf 1 2 5\n";
  std::ofstream(dir / "bad.grammar") << "1 Town 4 Park,0,0,1,0,1,1,0,1\n1 Park 5 Park,0,0,1,0,1,1,0,1\n";
  for (const Case& c : cases) {
    fs::path sketch = dir / (c.name + ".geojson");
    std::ofstream(sketch) << c.text;
    fs::path out = dir / ("out-" + c.name);
    Result r = run("generate " + sketch.string() + " -o " + out.string() + " --quiet");
    EXPECT_EQ(r.code, 2) << c.name << ": " << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.name << ": " << r.out;
    std::string file = c.name == "heightmap" ? (dir / "missing.png").string()
                       : c.name == "library" ? (dir / "missing.json").string()
                       : c.name == "model"   ? (dir / "bad.obj").string()
                       : c.name == "grammar" ? (dir / "bad.grammar").string()
                                             : sketch.string();
    EXPECT_NE(r.out.find(file), std::string::npos) << "names the file: " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "one line: " << r.out;
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  // No staging folder left behind either.
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string().find(".out-"), std::string::npos);
}

TEST(Cli, OutputPathsThatMustNotBeOverwritten) {
  fs::path dir = testing_util::temp_dir("cli-paths");
  std::string town = (kSource / "examples" / "town.geojson").string();
  std::ofstream(dir / "a-file") << "mine";
  Result r = run("generate " + town + " -o " + (dir / "a-file").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("is a file"), std::string::npos) << r.out;
  EXPECT_EQ(read(dir / "a-file"), "mine");

  fs::create_directories(dir / "notes");
  std::ofstream(dir / "notes" / "todo.txt") << "keep me";
  r = run("generate " + town + " -o " + (dir / "notes").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(read(dir / "notes" / "todo.txt"), "keep me");

  // An earlier exacity output is replaced whole.
  ASSERT_EQ(run("generate " + town + " -o " + (dir / "out").string() + " -q").code, 0);
  std::ofstream(dir / "out" / "stale.txt") << "old";
  ASSERT_EQ(run("generate " + town + " -o " + (dir / "out").string() + " -q").code, 0);
  EXPECT_FALSE(fs::exists(dir / "out" / "stale.txt"));
}

TEST(Cli, StagingFoldersOfDeadRunsAreRemovedAndAnInterruptLeavesNoTrace) {
  fs::path dir = testing_util::temp_dir("cli-staging");
  std::string town = (kSource / "examples" / "town.geojson").string();
  // What a crashed or killed run leaves: its process is gone (pids stop below 2^22 on Linux).
  fs::create_directories(dir / ".out.partial-4999999" / "inside");
  fs::create_directories(dir / ".out.old-4999998");
  fs::create_directories(dir / ".other.partial-4999999");
  ASSERT_EQ(run("generate " + town + " -o " + (dir / "out").string() + " -q").code, 0);
  EXPECT_FALSE(fs::exists(dir / ".out.partial-4999999"));
  EXPECT_FALSE(fs::exists(dir / ".out.old-4999998"));
  EXPECT_TRUE(fs::exists(dir / ".other.partial-4999999")) << "another output's folder is not this run's to remove";
  const std::string before = read(dir / "out" / "report.json");

  // SIGTERM while a long run writes into the same place: the earlier output stays whole.
  std::string big = (kSource / "benchmarks" / "city_10km.geojson").string();
  std::string cmd = std::string(EXACITY_BINARY) + " generate " + big + " -o " + (dir / "out").string() +
                    " -q > /dev/null 2>&1 & echo $!";
  FILE* pipe = popen(cmd.c_str(), "r");
  int pid = 0;
  ASSERT_EQ(fscanf(pipe, "%d", &pid), 1);
  pclose(pipe);
  const fs::path staging = dir / (".out.partial-" + std::to_string(pid));
  for (int i = 0; i < 600 && !fs::exists(staging); ++i) usleep(100000);
  ASSERT_TRUE(fs::exists(staging));
  kill(pid, SIGTERM);
  for (int i = 0; i < 600 && kill(pid, 0) == 0; ++i) usleep(100000);
  EXPECT_NE(kill(pid, 0), 0) << "still running";
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_EQ(read(dir / "out" / "report.json"), before);
}

TEST(Cli, HelpAndVersion) {
  Result h = run("--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("generate"), std::string::npos);
  EXPECT_NE(h.out.find("validate"), std::string::npos);
  EXPECT_EQ(run("generate --help").code, 0);
  Result v = run("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.out.find("exacity 0."), std::string::npos);
  EXPECT_EQ(run("frobnicate").code, 2);
  EXPECT_EQ(run("generate").code, 2);  // no sketch
}

