// Nesting end to end on examples/nesting: models stand under the gateways' and
// tees' overhangs, the city writes the same bytes on one thread or two, and both validators
// (exacity validate and the GEOS cross-check) accept the nested overlaps but refuse a copy
// where a nested model is made taller than the room under the model above it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <functional>

#include "geom/polygon_check.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace cli_util;
using nlohmann::json;

namespace {

class Nesting : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(testing_util::temp_dir("nesting-" + std::to_string(::getpid())));
    const std::string sketch = (kSource / "examples" / "nesting" / "nesting.geojson").string();
    // A failure here fails every test (SetUp): an assertion in SetUpTestSuite would only
    // mark them skipped.
    setup_error_ = new std::string;
    for (int threads : {1, 2}) {
      const Result r = run("generate " + sketch + " -o " + (*root_ / ("t" + std::to_string(threads))).string() +
                           " -q --threads " + std::to_string(threads));
      if (r.code != 0) *setup_error_ += "generate --threads " + std::to_string(threads) + " exited " + std::to_string(r.code) + ":\n" + r.out;
    }
  }
  void SetUp() override { ASSERT_TRUE(setup_error_->empty()) << *setup_error_; }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
    delete setup_error_;
  }
  static fs::path out() { return *root_ / "t1"; }

  // A fresh copy of the city, its buildings layer edited.
  static fs::path tampered(const std::string& name, const std::function<void(json&)>& edit) {
    const fs::path copy = *root_ / name;
    fs::copy(out(), copy, fs::copy_options::recursive);
    json doc = json::parse(read(copy / "vector" / "buildings.geojson"));
    edit(doc["features"]);
    std::ofstream(copy / "vector" / "buildings.geojson") << doc.dump();
    return copy;
  }

  static fs::path* root_;
  static std::string* setup_error_;
};

fs::path* Nesting::root_ = nullptr;
std::string* Nesting::setup_error_ = nullptr;

geom::Ring outer_ring(const json& feature) {
  geom::Ring r;
  const json& ring = feature["geometry"]["coordinates"][0];
  for (std::size_t k = 0; k + 1 < ring.size(); ++k) r.push_back({ring[k][0].get<double>(), ring[k][1].get<double>()});
  return r;
}

// Pairs (the model above, the model under it) of buildings whose footprints meet.
std::vector<std::pair<int, int>> nested_pairs(const json& features) {
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t a = 0; a < features.size(); ++a)
    for (std::size_t b = 0; b < features.size(); ++b)
      if (a != b && features[a]["properties"]["height"] > features[b]["properties"]["height"] &&
          geom::rings_meet(outer_ring(features[a]), outer_ring(features[b])))
        pairs.push_back({static_cast<int>(a), static_cast<int>(b)});
  return pairs;
}

TEST_F(Nesting, SmallModelsStandUnderTheOverhangsAndBothValidatorsAgree) {
  const json features = json::parse(read(out() / "vector" / "buildings.geojson"))["features"];
  const auto pairs = nested_pairs(features);
  EXPECT_GE(pairs.size(), 10u);
  for (auto [above, under] : pairs) {
    EXPECT_TRUE(features[above]["properties"]["model"] == "gateway" || features[above]["properties"]["model"] == "tee");
    // Wholly under the lowest underside of the model above, which is its second slab's bottom.
    const json& slabs = features[above]["properties"]["slabs"];
    ASSERT_GE(slabs.size(), 2u);
    EXPECT_LT(features[under]["properties"]["height"].get<double>(), slabs[1]["bottom"].get<double>());
  }
  const Result v = run("validate " + out().string());
  EXPECT_EQ(v.code, 0) << v.out;
  const Result geos = shell(geos_check(out()));
  EXPECT_EQ(geos.code, 0) << geos.out;
  const Result gltf = shell(node_tool("check_glb.mjs") + " " + (out() / "city.glb").string());
  EXPECT_EQ(gltf.code, 0) << gltf.out;
  const Result cityjson = shell(node_tool("check_cityjson.mjs") + " " + (out() / "city.city.json").string());
  EXPECT_EQ(cityjson.code, 0) << cityjson.out;
}

// A written building's slabs: heights from the ground datum, and outlines.
struct Written {
  double bottom, top;
  std::vector<geom::Ring> outline;
};
std::vector<Written> written_slabs(const json& feature) {
  std::vector<Written> out;
  const double floor = feature["properties"]["floor"].get<double>();
  for (const json& s : feature["properties"]["slabs"]) {
    Written w{floor, floor, {}};
    // On flat ground every floor is 0, so the sums are the slabs' own heights, exactly.
    w.bottom += s["bottom"].get<double>(), w.top += s["top"].get<double>();
    for (const json& ring : s["outline"]) {
      w.outline.emplace_back();
      for (std::size_t k = 0; k + 1 < ring.size(); ++k)
        w.outline.back().push_back({ring[k][0].get<double>(), ring[k][1].get<double>()});
    }
    out.push_back(std::move(w));
  }
  return out;
}

TEST_F(Nesting, NoTwoModelsMeetIn3DAnywhere) {
  const json features = json::parse(read(out() / "vector" / "buildings.geojson"))["features"];
  std::vector<std::vector<Written>> stacks;
  for (const json& f : features) {
    ASSERT_TRUE(f["properties"].contains("slabs")) << f["properties"].dump();
    EXPECT_EQ(f["properties"]["floor"], 0);
    stacks.push_back(written_slabs(f));
  }
  for (std::size_t a = 0; a < stacks.size(); ++a)
    for (std::size_t b = a + 1; b < stacks.size(); ++b)
      for (const Written& s : stacks[a])
        for (const Written& t : stacks[b])
          if (s.bottom <= t.top && t.bottom <= s.top) {
            for (const geom::Ring& p : s.outline)
              for (const geom::Ring& q : t.outline)
                EXPECT_FALSE(geom::rings_meet(p, q)) << "buildings " << a << " and " << b;
          }
}

TEST_F(Nesting, OneThreadOrTwoWriteTheSameBytes) {
  for (const auto& e : fs::recursive_directory_iterator(out())) {
    if (!e.is_regular_file() || e.path().filename() == "report.json") continue;
    const fs::path other = *root_ / "t2" / fs::relative(e.path(), out());
    EXPECT_EQ(read(e.path()), read(other)) << e.path();
  }
}

TEST_F(Nesting, BothValidatorsRefuseANestedModelMadeTallerThanTheRoomAboveIt) {
  const json features = json::parse(read(out() / "vector" / "buildings.geojson"))["features"];
  const auto pairs = nested_pairs(features);
  ASSERT_FALSE(pairs.empty());
  const auto [above, under] = pairs.front();
  const double clearance = features[above]["properties"]["slabs"][1]["bottom"].get<double>();
  // Taller, its slabs with it: the slabs now meet the beam.
  const fs::path taller = tampered("taller", [&](json& f) {
    f[under]["properties"]["height"] = clearance + 1;
    f[under]["properties"]["slabs"].back()["top"] = clearance + 1;
  });
  Result v = run("validate " + taller.string());
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("overlap in 3D"), std::string::npos) << v.out;
  Result geos = shell(geos_check(taller));
  EXPECT_EQ(geos.code, 1) << geos.out;
  EXPECT_NE(geos.out.find("overlap in plan"), std::string::npos) << geos.out;

  // Taller without its slabs: they no longer say what it holds.
  const fs::path height_only =
      tampered("height-only", [&](json& f) { f[under]["properties"]["height"] = clearance + 1; });
  v = run("validate " + height_only.string());
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("do not reach its height"), std::string::npos) << v.out;
  geos = shell(geos_check(height_only));
  EXPECT_EQ(geos.code, 1) << geos.out;

  // Without slabs, an overlap is an overlap.
  const fs::path bare = tampered("bare", [&](json& f) { f[under]["properties"].erase("slabs"); });
  v = run("validate " + bare.string());
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("carries no \"slabs\""), std::string::npos) << v.out;
  geos = shell(geos_check(bare));
  EXPECT_EQ(geos.code, 1) << geos.out;
}

// On a heightmap each model's heights count from its own floor: the city still validates,
// with models nested on ground lower or higher than the model above them.
TEST_F(Nesting, OnAHeightmapBothValidatorsAcceptIt) {
  const fs::path dir = *root_ / "terrain";
  fs::create_directories(dir);
  json sketch = json::parse(read(kSource / "examples" / "nesting" / "nesting.geojson"));
  sketch["exacity"]["models"] = (kSource / "examples" / "nesting" / "library.json").string();
  sketch["exacity"]["terrain"] = {{"heightmap", (kSource / "examples" / "valley.png").string()},
                                  {"bounds", {0, 0, 2000, 1500}},
                                  {"height", {0, 120}}};
  sketch["features"][0]["geometry"]["coordinates"] = {{{200, 300}, {500, 300}, {500, 600}, {200, 600}, {200, 300}}};
  std::ofstream(dir / "in.geojson") << sketch.dump();
  const Result r = run("generate " + (dir / "in.geojson").string() + " -o " + (dir / "out").string() + " -q");
  ASSERT_EQ(r.code, 0) << r.out;  // generate validates what it wrote
  const json features = json::parse(read(dir / "out" / "vector" / "buildings.geojson"))["features"];
  int uneven = 0;
  const auto pairs = nested_pairs(features);
  for (auto [above, under] : pairs)
    uneven += features[above]["properties"]["floor"] != features[under]["properties"]["floor"];
  EXPECT_GT(uneven, 10) << "of " << pairs.size() << " nested pairs";
  const Result geos = shell(geos_check(dir / "out"));
  EXPECT_EQ(geos.code, 0) << geos.out;
}

TEST_F(Nesting, WithoutNestingNothingStandsUnderAnother) {
  const fs::path dir = *root_ / "flat";
  fs::create_directories(dir);
  json sketch = json::parse(read(kSource / "examples" / "nesting" / "nesting.geojson"));
  sketch["exacity"]["zones"]["commercial"]["nesting"] = false;
  sketch["exacity"]["models"] = (kSource / "examples" / "nesting" / "library.json").string();
  std::ofstream(dir / "in.geojson") << sketch.dump();
  const Result r = run("generate " + (dir / "in.geojson").string() + " -o " + (dir / "out").string() + " -q");
  ASSERT_EQ(r.code, 0) << r.out;
  const json features = json::parse(read(dir / "out" / "vector" / "buildings.geojson"))["features"];
  EXPECT_GT(features.size(), 10u);
  EXPECT_TRUE(nested_pairs(features).empty());
  for (const json& f : features) EXPECT_FALSE(f["properties"].contains("slabs"));
}

}  // namespace
