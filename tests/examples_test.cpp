// Every example through the exacity program (label slow: the test preset runs it, the
// sanitizer run leaves it to cli_test's small sketch and the unit suites): each generates
// and validates (exactly, and independently with GEOS), meets the plausibility targets, and
// its map, glTF and CityJSON hold the city; each twice for determinism; the CityJSON
// schemas on three examples; and renders.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>

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

// map.svg's shapes, group by group in drawing order: each path's d, each polyline's points,
// each circle's centre.
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
    else if (line.rfind("<circle ", 0) == 0) groups.back().second.push_back(attribute(line, "cx") + "," + attribute(line, "cy"));
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
  groups.push_back({"clutter", {}});
  for (const auto& f : layer(out, "clutter")) groups.back().second.push_back(point(f["geometry"]["coordinates"]));
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
  int buildings = 0, models = 0, clutter = 0;
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
  // Written as it is made, through scratch files past 1 MiB, yet tinygltf's bytes for it.
  std::ostringstream rewritten;
  EXPECT_TRUE(loader.WriteGltfSceneToStream(&model, rewritten, false, true));
  EXPECT_TRUE(rewritten.str() == read(out / "city.glb")) << out;
  const tinygltf::Node& root = model.nodes.at(model.scenes.at(0).nodes.at(0));
  EXPECT_EQ(root.name, "city");
  std::map<std::pair<long, long>, std::vector<std::pair<double, double>>> building_points;  // by metre square
  std::vector<const tinygltf::Node*> model_nodes;
  const tinygltf::Node* clutter = nullptr;
  for (int child : root.children) {
    const tinygltf::Node& n = model.nodes.at(child);
    if (n.name == "ground") continue;
    if (n.name == "clutter") {
      clutter = &n;
      continue;
    }
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
  // Street clutter: a node each under "clutter", in id order, its origin within a few metres
  // of where clutter.geojson says it stands (the origin is the model's, the point its base's).
  const json pieces = layer(out, "clutter");
  EXPECT_EQ(clutter ? clutter->children.size() : 0, pieces.size()) << "city.glb's clutter nodes";
  for (std::size_t i = 0; clutter && i < std::min(pieces.size(), clutter->children.size()); ++i) {
    const tinygltf::Node& n = model.nodes.at(clutter->children[i]);
    const double x = root.translation[0] + n.translation.at(0), y = -(root.translation[2] + n.translation.at(2));
    const json& at = pieces[i]["geometry"]["coordinates"];
    EXPECT_LT(std::hypot(x - at[0].get<double>(), y - at[1].get<double>()), 3) << "clutter " << i;
    EXPECT_EQ(n.name, pieces[i]["properties"]["model"].get<std::string>()) << "clutter " << i;
    ++counts.clutter;
  }
  return counts;
}

// Every output file but report.json's timings, which are measurements.
std::map<std::string, std::string> outputs(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::string rel = fs::relative(e.path(), dir).string();
    std::string text = read(e.path());
    if (rel == "report.json") {
      auto j = nlohmann::ordered_json::parse(text);
      j.erase("timings_s");
      j.erase("peak_memory_mib");
      text = j.dump();
    }
    files[rel] = text;
  }
  return files;
}

}  // namespace

TEST(Cli, SameSketchGivesByteIdenticalOutputsWhateverTheThreadCount) {
  fs::path base = testing_util::temp_dir("cli-determinism");
  for (const fs::path& sketch : examples()) {
    ASSERT_EQ(run("generate " + sketch.string() + " -o " + (base / "a").string() + " -q --threads 1").code, 0);
    ASSERT_EQ(run("generate " + sketch.string() + " -o " + (base / "b").string() + " -q --threads 2").code, 0);
    auto a = outputs(base / "a"), b = outputs(base / "b");
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [name, text] : a) EXPECT_TRUE(text == b[name]) << sketch << ": " << name << " differs";
  }
}

TEST(Cli, EveryExampleGeneratesAndValidates) {
  auto list = examples();
  ASSERT_GE(list.size(), 3u);
  GlbCounts in_glb;
  for (const fs::path& sketch : list) {
    fs::path out = testing_util::temp_dir("cli-" + sketch.filename().string()) / "out";
    Result g = run("generate " + sketch.string() + " -o " + out.string() + " --quiet");
    ASSERT_EQ(g.code, 0) << sketch << "\n" << g.out;
    for (const char* f : {"vector/zones.geojson", "vector/water.geojson", "vector/roads.geojson",
                          "vector/road_areas.geojson", "vector/blocks.geojson", "vector/lots.geojson",
                          "vector/buildings.geojson", "map.svg", "city.obj", "city.mtl", "city.ply", "city.city.json",
                          "city.glb", "report.json", "vector/clutter.geojson"})
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
    in_glb.buildings += counts.buildings, in_glb.models += counts.models, in_glb.clutter += counts.clutter;
  }
  EXPECT_GT(in_glb.buildings, 0) << "no example has an extruded building to find in city.glb";
  EXPECT_GT(in_glb.models, 0) << "no example has a placed model to find in city.glb";
  EXPECT_GT(in_glb.clutter, 0) << "no example has street clutter to find in city.glb (the hillside should)";
}

// Schemas only: cli_test checks every example's solids, indices and templates without them.
TEST(Cli, CityJsonMatchesTheSchemas) {
  const fs::path schemas = cityjson_schemas();
  if (!fs::exists(schemas / "cityjson.schema.json")) GTEST_SKIP() << "no CityJSON schemas at " << schemas;
  for (const char* example : {"tangle", "valley", "hillside"}) {
    fs::path out = testing_util::temp_dir(std::string("cli-cityjson-") + example) / "out";
    ASSERT_EQ(run("generate " + (kSource / "examples" / (std::string(example) + ".geojson")).string() + " -o " +
                  out.string() + " -q").code, 0);
    std::string check = node_tool("check_cityjson.mjs") + " " + (out / "city.city.json").string() + " " + schemas.string();
    EXPECT_EQ(std::system((check + " > /dev/null").c_str()), 0) << check;
  }
}

TEST(Cli, RenderWritesStillOverviewAndMinimapTheSameWhateverTheThreadCount) {
  fs::path base = testing_util::temp_dir("cli-render");
  fs::path out = base / "out";
  Result g = run("generate " + (kSource / "examples" / "hillside.geojson").string() + " -o " + out.string() +
                 " -q --render --size 96x64 --spp 2");
  ASSERT_EQ(g.code, 0) << g.out;
  for (const char* f : {"render/still.png", "render/still.exr", "render/overview.png", "render/minimap.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  auto report = nlohmann::json::parse(read(out / "report.json"));
  ASSERT_TRUE(report.contains("render"));
  EXPECT_GT(report["render"]["tiles"]["count"].get<int>(), 0);
  EXPECT_GT(report["render"]["still"]["camera_rays"].get<long>(), 0);

  const std::string camera = " --camera orbit:target=400,600,40,azimuth=250,elevation=25,distance=500 --size 80x48 --spp 3 --minimap";
  for (int threads : {1, 2}) {
    Result r = run("render " + out.string() + camera + " -q --threads " + std::to_string(threads) + " -o " +
                   (base / ("still" + std::to_string(threads) + ".png")).string());
    ASSERT_EQ(r.code, 0) << r.out;
  }
  EXPECT_TRUE(read(base / "still1.png") == read(base / "still2.png"));
  EXPECT_TRUE(read(base / "still1.exr") == read(base / "still2.exr"));
  EXPECT_TRUE(fs::exists(base / "minimap.png"));
  auto stats = nlohmann::json::parse(read(base / "still1.json"));
  EXPECT_EQ(stats["size"][0], 80);
  EXPECT_GT(stats["tiles"]["culled"].get<int>(), 0) << "a close camera leaves tiles out";

  // Into the folder itself: report.json records the render.
  Result into = run("render " + out.string() + camera + " -q");
  ASSERT_EQ(into.code, 0) << into.out;
  EXPECT_TRUE(fs::exists(out / "render" / "still.json"));
  auto updated = nlohmann::json::parse(read(out / "report.json"));
  EXPECT_EQ(updated["render"]["size"][0], 80);
  EXPECT_EQ(updated["validation"]["ok"], true);

  Result bad = run("render " + out.string() + " --camera orbit:target=1,2 -q");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.out.find("--camera"), std::string::npos) << bad.out;
  EXPECT_EQ(std::count(bad.out.begin(), bad.out.end(), '\n'), 1) << bad.out;
  Result nowhere = run("render " + (base / "missing").string() + " -q");
  EXPECT_EQ(nowhere.code, 2);

  // A sketch's bad camera stops generate --render before anything is written.
  std::ofstream(base / "camera.geojson") << R"({"type": "FeatureCollection", "exacity": {"camera": "orbit:target=0,0"},
    "features": [{"type": "Feature", "properties": {"zone": "park"},
                  "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [50, 0], [50, 50], [0, 0]]]}}]})";
  Result camera_error = run("generate " + (base / "camera.geojson").string() + " -o " + (base / "camera-out").string() + " --render -q");
  EXPECT_EQ(camera_error.code, 2);
  EXPECT_NE(camera_error.out.find("\"exacity\".camera"), std::string::npos) << camera_error.out;
  EXPECT_FALSE(fs::exists(base / "camera-out"));
}
