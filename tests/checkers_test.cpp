// The test suite's external checkers are shown to refuse what they exist to catch: the
// GEOS layer check (tests/check_layers.py), the Khronos glTF validator
// (tests/js/check_glb.mjs) and the CityJSON content checks (tests/js/check_cityjson.mjs),
// and exacity's own validation with its proofs,
// each on a small city that passes, then on a copy broken one way.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "generate/export/validate.h"
#include "generate/pipeline.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace cli_util;
using nlohmann::json;

namespace {

class Checkers : public testing::Test {
 protected:
  // One small city, generated once: a residential square, so it has roads, lots and buildings.
  // ctest runs each test in a process of its own, two at a time: each process works in its
  // own folder, or one would remove the city another is reading.
  static void SetUpTestSuite() {
    root_ = new fs::path(testing_util::temp_dir("checkers-" + std::to_string(::getpid())));
    const fs::path& dir = *root_;
    std::ofstream(dir / "in.geojson") << R"({"type": "FeatureCollection", "exacity": {"seed": 2}, "features": [
      {"type": "Feature", "properties": {"zone": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [240, 0], [240, 200], [0, 200], [0, 0]]]}}]})";
    good_ = new fs::path(dir / "out");
    fs::create_directories(*good_);
    exacity::generate_city(exacity::load_sketch(dir / "in.geojson"), *good_, nullptr);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete good_;
    delete root_;
  }

  // A fresh copy of the good city.
  static fs::path copy(const std::string& name) {
    fs::path out = *root_ / name / "out";
    fs::create_directories(out.parent_path());
    fs::copy(*good_, out, fs::copy_options::recursive);
    return out;
  }

  static void edit_json(const fs::path& file, const std::function<void(json&)>& edit) {
    json doc = json::parse(read(file));
    edit(doc);
    std::ofstream(file) << doc.dump();
  }

  static fs::path* good_;
  static fs::path* root_;
};

fs::path* Checkers::good_ = nullptr;
fs::path* Checkers::root_ = nullptr;

// Rewrites a .glb's JSON chunk: padded with spaces to four bytes, the lengths set again.
void edit_glb_json(const fs::path& file, const std::function<void(json&)>& edit) {
  const std::string glb = read(file);
  std::uint32_t json_length;
  std::memcpy(&json_length, glb.data() + 12, 4);
  json doc = json::parse(glb.substr(20, json_length));
  edit(doc);
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  const std::string bin = glb.substr(20 + json_length);
  auto u32 = [](std::size_t n) {
    const auto v = static_cast<std::uint32_t>(n);
    return std::string(reinterpret_cast<const char*>(&v), 4);
  };
  std::ofstream(file, std::ios::binary) << glb.substr(0, 8) << u32(20 + text.size() + bin.size()) << u32(text.size())
                                        << glb.substr(16, 4) << text << bin;
}

// Feature i laid again over itself, under an id of its own.
void add_twin(json& doc, std::size_t i = 0) {
  json twin = doc["features"][i];
  twin["properties"]["id"] = 999999;
  doc["features"].push_back(twin);
}

// The mean of a closed ring's vertices (the closing one counted once).
std::pair<double, double> centre_of(const json& ring) {
  double cx = 0, cy = 0;
  for (std::size_t k = 0; k + 1 < ring.size(); ++k) cx += ring[k][0].get<double>(), cy += ring[k][1].get<double>();
  return {cx / static_cast<double>(ring.size() - 1), cy / static_cast<double>(ring.size() - 1)};
}

// A closed counter-clockwise ring's first corner moved `step` along the sum of its two
// edges' outward normals (inward where `step` is negative).
void move_corner(json& ring, double step) {
  auto at = [&](std::size_t k) { return std::pair{ring[k][0].get<double>(), ring[k][1].get<double>()}; };
  const auto [ux, uy] = at(ring.size() - 2);
  const auto [vx, vy] = at(0);
  const auto [wx, wy] = at(1);
  const double l1 = std::hypot(vx - ux, vy - uy), l2 = std::hypot(wx - vx, wy - vy);
  const double nx = (vy - uy) / l1 + (wy - vy) / l2, ny = -(vx - ux) / l1 - (wx - vx) / l2;
  ring[0] = ring.back() = {vx + step * nx, vy + step * ny};
}

}  // namespace

TEST_F(Checkers, GeosRefusesOverlappingZonesAndAWronglyTurnedRing) {
  Result good = shell(geos_check(copy("geos-good")));
  EXPECT_EQ(good.code, 0) << good.out;

  fs::path out = copy("geos-overlap");
  edit_json(out / "vector" / "zones.geojson", [](json& doc) { add_twin(doc); });
  Result overlap = shell(geos_check(out));
  EXPECT_EQ(overlap.code, 1) << overlap.out;
  EXPECT_NE(overlap.out.find("zones[0] and zones["), std::string::npos) << overlap.out;
  EXPECT_NE(overlap.out.find(" overlap by "), std::string::npos) << overlap.out;

  out = copy("geos-orientation");
  edit_json(out / "vector" / "lots.geojson", [](json& doc) {
    auto& ring = doc["features"][0]["geometry"]["coordinates"][0];
    std::reverse(ring.begin(), ring.end());
  });
  Result turned = shell(geos_check(out));
  EXPECT_EQ(turned.code, 1) << turned.out;
  EXPECT_NE(turned.out.find("lots[0]: ring 0 has the wrong orientation"), std::string::npos) << turned.out;
}

TEST_F(Checkers, GltfValidatorRefusesAnAccessorLongerThanItsData) {
  const std::string check = node_tool("check_glb.mjs") + " ";
  Result good = shell(check + (copy("glb-good") / "city.glb").string());
  EXPECT_EQ(good.code, 0) << good.out;

  fs::path out = copy("glb-long");
  edit_glb_json(out / "city.glb", [](json& doc) {
    auto& a = doc["accessors"][0];
    a["count"] = a["count"].get<int>() * 2;
  });
  Result broken = shell(check + (out / "city.glb").string());
  EXPECT_EQ(broken.code, 1) << broken.out;
  EXPECT_NE(broken.out.find("error: ACCESSOR_TOO_LONG"), std::string::npos) << broken.out;
}

TEST_F(Checkers, CityJsonContentChecksRefuseAnOpenSolidABadIndexAndAMissingTemplate) {
  const std::string check = node_tool("check_cityjson.mjs") + " ";
  Result good = shell(check + (copy("cityjson-good") / "city.city.json").string());
  EXPECT_EQ(good.code, 0) << good.out;
  EXPECT_NE(good.out.find("content only, no schemas"), std::string::npos) << good.out;

  // The first Solid, from the first city object that has one.
  auto first_solid = [](json& doc) -> json& {
    for (auto& [id, object] : doc["CityObjects"].items())
      for (auto& g : object["geometry"])
        if (g["type"] == "Solid") return g;
    throw std::runtime_error("no Solid in the city");
  };
  struct Case {
    std::string name, expect;
    std::function<void(json&)> tamper;
  };
  const std::vector<Case> cases = {
      {"open", "shell is not closed", [&](json& doc) { first_solid(doc)["boundaries"][0].erase(0); }},
      {"index", "vertex index out of range",
       [&](json& doc) { first_solid(doc)["boundaries"][0][0][0][0] = doc["vertices"].size(); }},
      {"template", "no template 99",
       [](json& doc) {
         auto& object = doc["CityObjects"].begin().value();
         object["geometry"].push_back({{"type", "GeometryInstance"}, {"template", 99}, {"boundaries", {0}},
                                       {"transformationMatrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
       }},
  };
  for (const Case& c : cases) {
    fs::path out = copy("cityjson-" + c.name);
    edit_json(out / "city.city.json", c.tamper);
    Result broken = shell(check + (out / "city.city.json").string());
    EXPECT_EQ(broken.code, 1) << c.name << ": " << broken.out;
    EXPECT_NE(broken.out.find(c.expect), std::string::npos) << c.name << ": " << broken.out;
  }
}

// exacity's own validation proves blocks, lots and buildings sound before it builds the map
// of every polygon, and leaves them out of it (docs/design.md, Validation by tiles: proofs);
// what is left is mapped with the zoning map. Layers broken one way each: the proofs fail,
// the map without what they proved finds the problem, and the problems stated are those of
// the whole maps, word for word.
TEST_F(Checkers, ValidationsProofsFallBackToTheWholeMapsMessages) {
  using exacity::MapProofs;
  const fs::path good = copy("proofs-good");
  EXPECT_TRUE(exacity::validate_output(good, 0, MapProofs::First).ok());
  EXPECT_TRUE(exacity::validate_output(good, 0, MapProofs::None).ok());
  // A block's ring written from another vertex is still its zone's: proven, and valid.
  const fs::path rotated = copy("proofs-rotated");
  edit_json(rotated / "vector" / "blocks.geojson", [](json& doc) {
    json& ring = doc["features"][0]["geometry"]["coordinates"][0];
    ring.erase(ring.size() - 1);
    std::rotate(ring.begin(), ring.begin() + 1, ring.end());
    ring.push_back(ring[0]);
  });
  EXPECT_TRUE(exacity::validate_output(rotated, 0, MapProofs::First).ok());

  // The outer ring of feature i, closed as written.
  auto ring_of = [](json& doc, std::size_t i = 0) -> json& { return doc["features"][i]["geometry"]["coordinates"][0]; };
  auto shift = [](json& ring, double dx, double dy) {
    for (auto& p : ring) p = {p[0].get<double>() + dx, p[1].get<double>() + dy};
  };
  struct Case {
    std::string name, layer, expect;
    std::function<void(json&)> tamper;
  };
  const std::vector<Case> cases = {
      // A lot laid again over itself, and one moved a metre out of its block.
      {"overlap", "lots", " overlap",
       [&](json& doc) { add_twin(doc); }},
      {"shifted", "lots", "leaves its block", [&](json& doc) { shift(ring_of(doc), 1, 1); }},
      // A block's corner pulled in: land of the zone left without a block.
      {"gap", "blocks", "holds no block",
       [&](json& doc) {
         json& ring = ring_of(doc);
         const auto [cx, cy] = centre_of(ring);
         ring[0] = ring.back() = {ring[0][0].get<double>() * 0.9 + cx * 0.1, ring[0][1].get<double>() * 0.9 + cy * 0.1};
       }},
      // A lot naming another block than the one it lies in.
      {"lot-outside", "lots", "leaves its block",
       [&](json& doc) {
         const int block = doc["features"][0]["properties"]["block"];
         for (auto& f : doc["features"])
           if (f["properties"]["block"] != block) return void(doc["features"][0]["properties"]["block"] = f["properties"]["block"]);
         throw std::runtime_error("one block only");
       }},
      // A lot's corner moved a nanometre out (along the sum of its edges' outward normals):
      // a sliver over its neighbour or out of its block.
      {"sliver", "lots", "lots.geojson features[0]", [&](json& doc) { move_corner(ring_of(doc), 1e-9); }},
      // A building carried off its lot, and one laid over another.
      {"building-off", "buildings", "leaves its lot", [&](json& doc) { shift(ring_of(doc), 30, 0); }},
      {"building-twice", "buildings", " overlap",
       [&](json& doc) { add_twin(doc); }},
      // A block that says another zone than the zone of its rings: a block is proven only
      // with the zone's type.
      {"block-zone", "blocks", "says \"commercial\" inside",
       [&](json& doc) { doc["features"][0]["properties"]["zone"] = "commercial"; }},
      // A block laid twice, and a zone: a block is proven only as the one block of the one
      // zone with its rings.
      {"block-twice", "blocks", " overlap",
       [&](json& doc) { add_twin(doc); }},
      {"zone-twice", "zones", " overlap",
       [&](json& doc) { add_twin(doc); }},
      // A block's corner moved a nanometre in: a gap in its zone that no block covers, so
      // the rings are compared exactly.
      {"block-sliver", "blocks", "holds no block",
       [&](json& doc) {
         json& ring = ring_of(doc);
         const auto [cx, cy] = centre_of(ring);
         const double x = ring[0][0].get<double>(), y = ring[0][1].get<double>(), d = std::hypot(cx - x, cy - y);
         ring[0] = ring.back() = {x + 1e-9 * (cx - x) / d, y + 1e-9 * (cy - y) / d};
       }},
      // A road area laid twice: the zoning map, holding what the proofs left, checks the
      // polygons too.
      {"road-twice", "road_areas", " overlap",
       [&](json& doc) { add_twin(doc); }},
      // A lot shrunk off the road areas.
      {"no-frontage", "lots", "touches no road area",
       [&](json& doc) {
         json& ring = ring_of(doc);
         const auto [cx, cy] = centre_of(ring);
         for (auto& p : ring) p = {cx + (p[0].get<double>() - cx) * 0.9, cy + (p[1].get<double>() - cy) * 0.9};
       }},
  };
  for (const Case& c : cases) {
    const fs::path out = copy("proofs-" + c.name);
    edit_json(out / "vector" / (c.layer + ".geojson"), c.tamper);
    const exacity::Validation with = exacity::validate_output(out, 0, MapProofs::First);
    const exacity::Validation whole = exacity::validate_output(out, 0, MapProofs::None);
    EXPECT_FALSE(with.ok()) << c.name;
    EXPECT_EQ(with.problems, whole.problems) << c.name;
    std::string all;
    for (const std::string& p : with.problems) all += p + "\n";
    EXPECT_NE(all.find(c.expect), std::string::npos) << c.name << ":\n" << all;
  }
}

// The zoning map holds, in place of the zones and road areas away from the drawn edges, their
// outline: their edges less those that two of them have, one each way (docs/design.md,
// Validation by tiles: the zoning map's proof). Layers broken one way each, inside the drawn
// square, where those polygons are: the problems are the whole zoning map's, word for word,
// and a gap no wider than rounding is the sliver the whole map measures.
TEST_F(Checkers, ZoningMapsOutlineProofFindsWhatTheWholeMapFinds) {
  using exacity::MapProofs;
  // The feature of the layer (of the surface, if given) whose box lies farthest inside the
  // drawn square (0, 0)-(240, 200).
  auto innermost = [](json& doc, const std::string& surface = "") {
    std::size_t best = 0;
    double depth = -1;
    for (std::size_t i = 0; i < doc["features"].size(); ++i) {
      json& f = doc["features"][i];
      if (!surface.empty() && f["properties"].value("surface", "") != surface) continue;
      double d = 1e9;
      for (const auto& p : f["geometry"]["coordinates"][0]) {
        const double x = p[0], y = p[1];
        d = std::min({d, x, y, 240 - x, 200 - y});
      }
      if (d > depth) depth = d, best = i;
    }
    if (depth <= 1) throw std::runtime_error("no feature inside the square");
    return best;
  };
  auto twice = [&](const std::string& surface) { return [=](json& doc) { add_twin(doc, innermost(doc, surface)); }; };
  // A carriageway's corner moved a nanometre in, along its edges' inward normals: a gap
  // between it and what it touches, narrower than rounding.
  auto corner_in = [&](double step) {
    return [=](json& doc) { move_corner(doc["features"][innermost(doc, "carriageway")]["geometry"]["coordinates"][0], -step); };
  };
  struct Case {
    std::string name, layer, expect;  // expect empty: valid
    std::function<void(json&)> tamper;
  };
  const std::vector<Case> cases = {
      {"carriageway-gone", "road_areas", "is not covered",
       [&](json& doc) { doc["features"].erase(innermost(doc, "carriageway")); }},
      {"carriageway-twice", "road_areas", " overlap", twice("carriageway")},
      {"zone-twice", "zones", " overlap", twice("")},
      {"zone-moved", "zones", " overlap",
       [&](json& doc) {
         for (auto& p : doc["features"][innermost(doc)]["geometry"]["coordinates"][0]) p[0] = p[0].get<double>() + 0.5;
       }},
      // Wider than rounding: a gap.
      {"carriageway-corner", "road_areas", "is not covered", corner_in(1e-3)},
      {"carriageway-sliver", "road_areas", "", corner_in(1e-9)},
  };
  for (const Case& c : cases) {
    const fs::path out = copy("outline-" + c.name);
    edit_json(out / "vector" / (c.layer + ".geojson"), c.tamper);
    const exacity::Validation with = exacity::validate_output(out, 0, MapProofs::First);
    const exacity::Validation whole = exacity::validate_output(out, 0, MapProofs::None);
    EXPECT_EQ(with.problems, whole.problems) << c.name;
    EXPECT_EQ(with.widest_sliver, whole.widest_sliver) << c.name;
    std::string all;
    for (const std::string& p : with.problems) all += p + "\n";
    if (c.expect.empty()) {
      EXPECT_TRUE(with.ok()) << c.name << ":\n" << all;
      EXPECT_GT(with.widest_sliver, 0) << c.name;
    } else {
      EXPECT_NE(all.find(c.expect), std::string::npos) << c.name << ":\n" << all;
    }
  }
  // A zone and its block (the same rings) that say another zone than the sketch draws: the
  // block is proven, the zone is not far.
  const fs::path out = copy("outline-zone-type");
  json zones = json::parse(read(out / "vector" / "zones.geojson"));
  json& zone = zones["features"][innermost(zones)];
  zone["properties"]["zone"] = "commercial";
  std::ofstream(out / "vector" / "zones.geojson") << zones.dump();
  edit_json(out / "vector" / "blocks.geojson", [&](json& doc) {
    for (auto& f : doc["features"])
      if (f["geometry"] == zone["geometry"]) f["properties"]["zone"] = "commercial";
  });
  const exacity::Validation with = exacity::validate_output(out, 0, MapProofs::First);
  EXPECT_EQ(with.problems, exacity::validate_output(out, 0, MapProofs::None).problems);
  ASSERT_EQ(with.problems.size(), 1u);
  EXPECT_NE(with.problems[0].find("says zone \"commercial\" where the sketch draws \"residential\""), std::string::npos)
      << with.problems[0];
}

// The centre lines are proven to meet only at vertices of both, segment against segment,
// before any map of them (validate.cpp, roads_meet_at_vertices): roads broken one way
// each, the problems are the map's, word for word.
TEST_F(Checkers, RoadsProofFindsWhatTheMapFinds) {
  using exacity::MapProofs;
  struct Case {
    std::string name, expect;  // expect empty: whatever the map finds
    std::function<void(json&)> tamper;
  };
  auto added = [](json& doc, json line) {
    json road = doc["features"][0];
    road["properties"]["id"] = 999999;
    road["geometry"]["coordinates"] = std::move(line);
    doc["features"].push_back(road);
  };
  const std::vector<Case> cases = {
      {"twice", " runs along road ", [&](json& doc) { added(doc, doc["features"][0]["geometry"]["coordinates"]); }},
      {"across", " meets another centre line between its vertices",
       [&](json& doc) { added(doc, json::array({{-10, 100.5}, {250, 100.5}})); }},
      // A road from a vertex of another to a point inside one of its segments.
      {"inside", " meets another centre line between its vertices",
       [&](json& doc) {
         const json& line = doc["features"][0]["geometry"]["coordinates"];
         const double x = line[0][0], y = line[0][1], u = line[1][0], v = line[1][1];
         added(doc, json::array({{x, y}, {x + 7, y + 5}, {x + (u - x) / 2, y + (v - y) / 2}}));
       }},
      // A road that goes back along its own last segment: the same segment of one line.
      {"back", "",
       [&](json& doc) {
         json& line = doc["features"][0]["geometry"]["coordinates"];
         line.push_back(line[line.size() - 2]);
       }},
  };
  for (const Case& c : cases) {
    const fs::path out = copy("roads-" + c.name);
    edit_json(out / "vector" / "roads.geojson", c.tamper);
    const exacity::Validation with = exacity::validate_output(out, 0, MapProofs::First);
    const exacity::Validation whole = exacity::validate_output(out, 0, MapProofs::None);
    EXPECT_EQ(with.problems, whole.problems) << c.name;
    std::string all;
    for (const std::string& p : with.problems) all += p + "\n";
    if (!c.expect.empty()) {
      EXPECT_NE(all.find(c.expect), std::string::npos) << c.name << ":\n" << all;
    }
  }
}
