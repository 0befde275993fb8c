// Regenerating after an edit (generate/regenerate.h): the city built with the cache of the
// city before is the city a full build of the edited sketch makes, byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <functional>
#include <iterator>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "generate/cancel.h"
#include "generate/errors.h"
#include "generate/export/validate_window.h"
#include "generate/pipeline.h"
#include "generate/regenerate.h"
#include "tests/test_util.h"

using namespace exacity;
using nlohmann::json;

namespace {

json ring(double x0, double y0, double x1, double y1) {
  return json::array({json::array({x0, y0}), json::array({x1, y0}), json::array({x1, y1}), json::array({x0, y1}),
                      json::array({x0, y0})});
}

json zone(const std::string& type, json outer) {
  return {{"type", "Feature"},
          {"properties", {{"zone", type}}},
          {"geometry", {{"type", "Polygon"}, {"coordinates", json::array({std::move(outer)})}}}};
}

// Three columns of zones in two rows between main roads, so that most regions are apart:
// an edit of one zone leaves the others' regions as they were. The middle of the lower row
// is two zones side by side (one region of growth), and there is a park and a pond.
json town() {
  json features = json::array();
  const char* types[2][3] = {{"residential", "commercial", "industrial"}, {"industrial", "residential", "commercial"}};
  for (int row = 0; row < 2; ++row)
    for (int column = 0; column < 3; ++column) {
      const double x = column * 260.0, y = row * 220.0;
      if (row == 0 && column == 1) {
        features.push_back(zone("residential", ring(x, y, x + 110, y + 200)));
        features.push_back(zone("commercial", ring(x + 110, y, x + 240, y + 200)));
      } else {
        features.push_back(zone(types[row][column], ring(x, y, x + 240, y + 200)));
      }
    }
  features.push_back(zone("park", ring(540, 260, 600, 320)));
  features.push_back(zone("water", ring(40, 40, 90, 80)));
  auto road = [](double x0, double y0, double x1, double y1) {
    return json{{"type", "Feature"},
                {"properties", {{"road", "main"}, {"width", 12}}},
                {"geometry", {{"type", "LineString"}, {"coordinates", json::array({json::array({x0, y0}), json::array({x1, y1})})}}}};
  };
  features.push_back(road(-30, 210, 800, 210));
  features.push_back(road(250, -30, 250, 450));
  features.push_back(road(510, -30, 510, 450));
  return {{"type", "FeatureCollection"},
          {"exacity", {{"seed", 3}, {"zones", {{"residential", {{"block_area", 6000}}}, {"commercial", {{"block_area", 6000}}},
                                              {"industrial", {{"block_area", 8000}}}}}}},
          {"features", features}};
}

// A random edit of one zone: a corner moved, its type changed, a zone added, or one removed
// (while more than five are left).
json edited(json sketch, std::mt19937& random) {
  json& features = sketch["features"];
  std::vector<std::size_t> zones;
  for (std::size_t i = 0; i < features.size(); ++i)
    if (features[i]["properties"].contains("zone")) zones.push_back(i);
  json& chosen = features[zones[random() % zones.size()]];
  const char* types[] = {"residential", "commercial", "industrial", "park"};
  switch (random() % (zones.size() > 5 ? 4 : 3)) {
    case 0: {  // a corner moved; the ring's first and last points stay one
      json& outer = chosen["geometry"]["coordinates"][0];
      const std::size_t corner = random() % (outer.size() - 1);
      std::uniform_real_distribution<double> step(-25, 25);
      for (int axis : {0, 1}) outer[corner][axis] = outer[corner][axis].get<double>() + std::round(step(random));
      if (corner == 0) outer[outer.size() - 1] = outer[0];
      break;
    }
    case 1: {
      const std::string now = chosen["properties"]["zone"];
      std::string next = now;
      while (next == now) next = types[random() % 4];
      chosen["properties"]["zone"] = next;
      break;
    }
    case 2: {
      std::uniform_real_distribution<double> at(0, 700);
      const double x = std::round(at(random)), y = std::round(at(random) * 0.55);
      features.push_back(zone(types[random() % 4], ring(x, y, x + 90, y + 70)));
      break;
    }
    default:
      features.erase(zones[random() % zones.size()]);
  }
  return sketch;
}

// Every file in `dir` (as write_city writes them), one text: the layers, clutter, map, CityJSON,
// glTF, OBJ, PLY and the report, less its seconds and what the build reused.
std::string folder_text(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::string all;
  for (const auto& file : files) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    std::string content = text.str();
    if (file.filename() == "report.json") {
      json report = json::parse(content);
      report.erase("timings_s");
      report.erase("peak_memory_mib");
      report.erase("reused");
      content = report.dump(1);
    }
    all += file.lexically_relative(dir).string() + "\n" + content;
  }
  return all;
}

std::string written(const Sketch& sketch, const City& city, const std::string& name) {
  const auto dir = testing_util::temp_dir(name);
  StageClock clock(nullptr, kWriteStages);
  write_city(sketch, city, dir, clock);
  return folder_text(dir);
}

// Two written folders' texts (folder_text) the same, else the first line where they differ:
// gtest's own diff of two texts of megabytes takes tens of gigabytes.
testing::AssertionResult same_text(const std::string& a, const std::string& b) {
  if (a == b) return testing::AssertionSuccess();
  const std::size_t at = std::mismatch(a.begin(), a.begin() + std::min(a.size(), b.size()), b.begin()).first - a.begin();
  const std::size_t newline = at == 0 ? std::string::npos : a.rfind('\n', at - 1);
  const std::size_t start = newline == std::string::npos ? 0 : newline + 1;  // of the line they differ in
  auto line = [&](const std::string& s) { return s.substr(start, std::min<std::size_t>(s.find('\n', start) - start, 600)); };
  return testing::AssertionFailure() << "they differ from line " << std::count(a.begin(), a.begin() + start, '\n') + 1
                                     << " (of " << std::count(a.begin(), a.end(), '\n') << " and "
                                     << std::count(b.begin(), b.end(), '\n') << "):\n  " << line(a) << "\n  " << line(b);
}

struct Built {
  Sketch sketch;
  City city;
};

// A feature of a layer file (one a line) as written.
struct FeatureLine {
  std::string text;  // the file's name and the feature's text, without the comma after it
};

// The features of every line-per-feature file written for the city: the vector layers and
// clutter (docs/design.md, Outputs).
std::vector<FeatureLine> feature_lines(const Sketch& sketch, const City& city, const std::string& name) {
  const auto dir = testing_util::temp_dir(name);
  StageClock clock(nullptr, kWriteStages);
  write_city(sketch, city, dir, clock);
  std::vector<FeatureLine> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "vector")) {
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("{\"type\":\"Feature\"", 0) != 0) continue;
      if (line.back() == ',') line.pop_back();
      if (line.size() > 2 && line.compare(line.size() - 2, 2, "]}") == 0) line.resize(line.size() - 2);
      out.push_back({entry.path().filename().string() + " " + line});
    }
  }
  return out;
}

// A feature's text with its id and the ids it names left out, and its id.
std::pair<std::string, std::string> without_ids(const std::string& text) {
  static const std::regex id(R"re("id":([0-9]+))re");
  static const std::regex names(R"re("(id|block|lot|road|region)":(-?[0-9]+|null)|"roads":\[[^\]]*\])re");
  std::smatch m;
  std::regex_search(text, m, id);
  return {std::regex_replace(text, names, ""), m.size() > 1 ? m[1].str() : ""};
}

// Every feature of `after` that is, ids and what it names left out, one of `before` (one
// each way) has that one's id: ids depend on what a feature is, not on where it comes in
// the map or on what else the edit changed. Returns how many were compared.
int expect_ids_kept(const std::vector<FeatureLine>& before, const std::vector<FeatureLine>& after, const std::string& what) {
  std::map<std::string, std::string> id_before;
  std::set<std::string> twice;
  for (const FeatureLine& f : before) {
    auto [text, id] = without_ids(f.text);
    if (!id_before.emplace(text, id).second) twice.insert(text);
  }
  int compared = 0;
  for (const FeatureLine& f : after) {
    auto [text, id] = without_ids(f.text);
    const auto it = id_before.find(text);
    if (it == id_before.end() || twice.count(text)) continue;
    ++compared;
    EXPECT_EQ(id, it->second) << what << ": " << f.text.substr(0, 300);
  }
  return compared;
}

// The sketch as write_city copies it (a parsed text has no file to copy).
Sketch parsed(const json& text) {
  Sketch sketch = parse_sketch(text.dump(), "town.geojson");
  if (sketch.geojson.empty()) sketch.geojson = text.dump();
  return sketch;
}

Built build(const json& text, std::shared_ptr<RegionCache> cache = {}) {
  StageClock clock(nullptr, kCityStages);
  Built b{parsed(text), {}};
  b.city = build_city(b.sketch, clock, std::move(cache));
  return b;
}

Built regenerated(const City& previous, const json& text) {
  StageClock clock(nullptr, kCityStages);
  Built b{parsed(text), {}};
  b.city = regenerate(previous, b.sketch, clock);
  return b;
}

std::string written(const Built& b, const std::string& name) { return written(b.sketch, b.city, name); }

}  // namespace

// A key's number is C's %a text (keys made before and after must compare alike), whatever
// the double: zeros, subnormals, the largest, infinities, random bits.
TEST(Regenerate, AKeysNumberIsPrintfsHexText) {
  std::vector<double> values{0.0, -0.0, 1.0, -2.5, 0.1, 1e-310, -4.9e-324, 1.7976931348623157e308,
                             std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  std::mt19937_64 rng(3);
  for (int i = 0; i < 100000; ++i) {
    const double v = std::bit_cast<double>(rng());
    if (!std::isnan(v)) values.push_back(v);
  }
  for (const double v : values) {
    std::string key;
    append_key(key, v);
    char text[40];
    std::snprintf(text, sizeof text, "%a ", v);
    ASSERT_EQ(key, text);
  }
}

TEST(Regenerate, UnchangedSketchReusesEveryRegionBlockLotAndMesh) {
  const Built first = build(town(), std::make_shared<RegionCache>());
  const std::string first_written = written(first, "first");  // as the server does, before the next build
  const Built again = regenerated(first.city, town());
  const std::string again_written = written(again, "again");
  const RegionCache& cache = *again.city.regions;
  EXPECT_GT(cache.road_plans.hits(), 0);
  EXPECT_EQ(cache.road_plans.misses(), 0);
  EXPECT_EQ(cache.lot_plans.misses(), 0);
  EXPECT_GT(cache.block_lots.hits(), 0);  // each block's lots, from its own map
  EXPECT_EQ(cache.block_lots.misses(), 0);
  EXPECT_EQ(cache.placements.misses(), 0);
  EXPECT_GT(cache.meshes.hits(), 0);
  EXPECT_EQ(cache.meshes.misses(), 0);
  EXPECT_TRUE(same_text(again_written, first_written));
  const json reused = reuse_report(cache);
  EXPECT_EQ(reused["structure_meshes"]["reused"], cache.meshes.hits());
  EXPECT_EQ(reused["region_plans"]["of"], cache.road_plans.hits());
}

// A city nothing reads after its files has its map, blocks, lots and vector layers freed
// before the 3D export (the peak of a large city): it writes the same files and report.
TEST(Regenerate, ACityFreedAsItIsWrittenWritesWhatAKeptOneDoes) {
  const Built kept = build(town());
  Built freed = build(town());
  const auto dir = testing_util::temp_dir("freed");
  StageClock clock(nullptr, kWriteStages);
  EXPECT_TRUE(write_city(freed.sketch, std::move(freed.city), dir, clock).valid);
  EXPECT_TRUE(freed.city.lots.empty());  // NOLINT(bugprone-use-after-move): what the overload frees
  EXPECT_TRUE(freed.city.layers.buildings.features.empty());
  EXPECT_FALSE(freed.city.buildings.empty());  // the 3D export's
  EXPECT_TRUE(same_text(folder_text(dir), written(kept, "kept")));
}

// Each edit regenerated from the city before it, which was written (so its meshes are kept),
// against the edited sketch built whole without a cache; and every feature of the layers
// and clutter the edit left as it was keeps its id. The sanitizers make each edit about seven
// times as slow and find nothing more in the later ones: they run the first six.
#ifdef __SANITIZE_ADDRESS__
constexpr int kRandomEdits = 6;
#else
constexpr int kRandomEdits = 16;
#endif
TEST(Regenerate, RandomEditsGiveTheFullBuildsCity) {
  std::mt19937 random(11);
  json sketch = town();
  Built previous = build(sketch, std::make_shared<RegionCache>());
  written(previous, "first");
  std::vector<FeatureLine> lines = feature_lines(previous.sketch, previous.city, "first lines");
  int reused = 0, meshes_reused = 0, kept = 0;
  for (int edit = 0; edit < kRandomEdits; ++edit) {
    json next = edited(sketch, random);
    Built city;
    try {
      city = regenerated(previous.city, next);
    } catch (const UserError&) {
      EXPECT_THROW(build(next), UserError);  // an edit the reader refuses is refused by a full build too
      continue;
    }
    const std::string regenerated_written = written(city, "regenerated");
    reused += city.city.regions->hits();
    meshes_reused += city.city.regions->meshes.hits();
    const Built full = build(next);
    EXPECT_TRUE(same_text(regenerated_written, written(full, "full"))) << "edit " << edit << ": " << next.dump();
    std::vector<FeatureLine> next_lines = feature_lines(full.sketch, full.city, "full lines");
    kept += expect_ids_kept(lines, next_lines, "edit " + std::to_string(edit));
    lines = std::move(next_lines);
    sketch = std::move(next);
    previous = std::move(city);
  }
  // Not every edit reaches every region, block, lot or structure: some were reused.
  EXPECT_GT(reused, 0);
  EXPECT_GT(meshes_reused, 0);
  EXPECT_GT(kept, 1000);
}

// A zone drawn apart from the others is a region of its own: adding it and removing it
// again, each regenerated, give the full builds' cities, and the first build's cache serves
// the regions, blocks and lots the new zone did not reach.
TEST(Regenerate, AddingAndRemovingARegion) {
  Built previous = build(town(), std::make_shared<RegionCache>());
  written(previous, "first");
  json added = town();
  added["features"].push_back(zone("residential", ring(820, 0, 1000, 160)));
  Built with = regenerated(previous.city, added);
  EXPECT_GT(with.city.regions->road_plans.hits(), 0);
  EXPECT_GT(with.city.regions->road_plans.misses(), 0);  // the new region
  EXPECT_GT(with.city.regions->placements.hits(), 0);
  EXPECT_TRUE(same_text(written(with, "added"), written(build(added), "added full")));
  Built without = regenerated(with.city, town());
  const std::string without_written = written(without, "removed");
  EXPECT_EQ(without.city.regions->road_plans.misses(), 0);
  EXPECT_GT(without.city.regions->meshes.hits(), 0);
  EXPECT_TRUE(same_text(without_written, written(previous, "removed full")));
}

namespace {

// The town written with a cache into a new folder `name` (its path into `dir`): the
// polygons its validation kept for the next.
std::shared_ptr<ValidatedPolygons> written_town(const std::string& name, std::filesystem::path& dir) {
  const Built city = build(town(), std::make_shared<RegionCache>());
  dir = testing_util::temp_dir(name);
  StageClock clock(nullptr, kWriteStages);
  EXPECT_TRUE(write_city(city.sketch, city.city, dir, clock).valid);
  return city.city.regions->validated;
}

}  // namespace

// A city written with a cache is validated where it changed since the last one that passed
// (generate/export/validate_window.h): a lot moved to another block, or a building pushed off
// its lot, is found there, with the problems the whole check states.
TEST(Regenerate, AWindowedValidationFindsWhatTheWholeOneFinds) {
  std::filesystem::path dir;
  std::shared_ptr<ValidatedPolygons> last = written_town("windowed", dir);
  ASSERT_TRUE(last);
  EXPECT_TRUE(validate_output(dir, last).ok());  // nothing changed: an empty window
  ASSERT_TRUE(last);
  auto rewrite = [&](const std::string& layer, const std::function<void(json&)>& edit) {
    const auto file = dir / "vector" / (layer + ".geojson");
    std::ifstream in(file);
    json doc = json::parse(in);
    edit(doc["features"]);
    std::ofstream(file) << doc.dump();
  };
  const auto lots_before = std::filesystem::path(dir / "vector" / "lots.geojson");
  std::ifstream saved_in(lots_before);
  const std::string saved((std::istreambuf_iterator<char>(saved_in)), std::istreambuf_iterator<char>());
  rewrite("lots", [](json& lots) {
    json& lot = lots[lots.size() / 2];
    lot["properties"]["block"] = lot["properties"]["block"].get<int>() + 1;
  });
  const Validation moved = validate_output(dir, last);
  EXPECT_FALSE(moved.ok());
  EXPECT_FALSE(last);  // a city that fails keeps nothing for the next
  EXPECT_EQ(moved.problems, validate_output(dir).problems);
  EXPECT_NE(testing::PrintToString(moved.problems).find("leaves its block"), std::string::npos) << testing::PrintToString(moved.problems);

  std::ofstream(lots_before) << saved;
  last = nullptr;
  ASSERT_TRUE(validate_output(dir, last).ok());  // whole, and kept
  rewrite("buildings", [](json& buildings) {
    json& outer = buildings[buildings.size() / 3]["geometry"]["coordinates"][0];
    for (std::size_t k : {std::size_t(0), outer.size() - 1}) outer[k][0] = outer[k][0].get<double>() + 40;
  });
  const Validation pushed = validate_output(dir, last);
  EXPECT_FALSE(pushed.ok());
  EXPECT_EQ(pushed.problems, validate_output(dir).problems);
}

// exacity serve stops a validation whose city the next generation replaces: the last city
// that passed stays the one the next validation is windowed against, its lines kept.
TEST(Regenerate, ACancelledValidationKeepsTheLastThatPassed) {
  std::filesystem::path dir;
  std::shared_ptr<ValidatedPolygons> last = written_town("cancelled_validation", dir);
  ASSERT_TRUE(last);
  const ValidatedPolygons* const passed = last.get();
  {
    const std::atomic<bool> cancelled{true};
    const CancelScope scope(cancelled);
    EXPECT_THROW(validate_output(dir, last), Cancelled);
  }
  EXPECT_EQ(last.get(), passed);
  EXPECT_TRUE(validate_output(dir, last).ok());
  EXPECT_TRUE(last);
}

// The map of every polygon is checked tile by tile (docs/design.md, Validation by tiles):
// with 40 m tiles, whose seams run through every block, a broken town gives the problems one
// map of the whole town gives (a tile as wide as the world), but for where each is said to be.
TEST(Regenerate, ValidationByTilesFindsWhatOneMapFinds) {
  const Built city = build(town());
  const auto dir = testing_util::temp_dir("tiles");
  StageClock clock(nullptr, kWriteStages);
  ASSERT_TRUE(write_city(city.sketch, city.city, dir, clock).valid);
  EXPECT_TRUE(validate_output(dir, 40).ok());
  auto said = [&](double tile_side) {
    std::set<std::string> problems;
    for (std::string p : validate_output(dir, tile_side).problems) problems.insert(p.substr(0, p.find(" near (")));
    return problems;
  };
  auto broken = [&](const std::string& layer, const std::function<void(json&)>& edit, const std::string& expected) {
    const auto file = dir / "vector" / (layer + ".geojson");
    std::string saved;
    {
      std::ifstream in(file);
      saved.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    json doc = json::parse(saved);
    edit(doc["features"]);
    std::ofstream(file) << doc.dump();
    const std::set<std::string> tiled = said(40), whole = said(1e9);
    EXPECT_EQ(tiled, whole) << layer;
    EXPECT_NE(testing::PrintToString(tiled).find(expected), std::string::npos) << testing::PrintToString(tiled);
    std::ofstream(file) << saved;
  };
  broken("lots", [](json& lots) { lots[lots.size() / 2]["properties"]["block"] = lots[lots.size() / 2]["properties"]["block"].get<int>() + 1; },
         "leaves its block");
  broken("buildings", [](json& buildings) {
    for (auto& p : buildings[buildings.size() / 3]["geometry"]["coordinates"][0]) p[0] = p[0].get<double>() + 40;
  }, "leaves its lot");
  broken("blocks", [](json& blocks) { blocks.erase(blocks.size() / 2); }, "holds no block");
  broken("lots", [](json& lots) {
    // A hole that runs along the outer ring's first edge.
    json& outer = lots[lots.size() / 3]["geometry"]["coordinates"][0];
    const double cx = (outer[0][0].get<double>() + outer[1][0].get<double>() + outer[2][0].get<double>()) / 3;
    const double cy = (outer[0][1].get<double>() + outer[1][1].get<double>() + outer[2][1].get<double>()) / 3;
    lots[lots.size() / 3]["geometry"]["coordinates"].push_back(json::array({outer[0], json::array({cx, cy}), outer[1], outer[0]}));
  }, "two of its rings share an edge");
  broken("zones", [](json& zones) { zones.erase(zones.size() / 2); }, "lies outside the zones");
}
