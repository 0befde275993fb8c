// A city as a plan's tasks (generate/plan/plan.h, scripts/generate_city.sbatch run outside
// Slurm as its tasks would be): merged, every file the bytes exacity generate writes of the
// sketch; a merge refuses a plan with a task missing, another plan's items or a sketch
// changed since, with one line and exit 2, writing nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli_util.h"
#include "tests/test_util.h"

using namespace cli_util;

namespace {

// Small, and with what every step keeps: regions of growth and of another layout on both
// sides of a sketch road, blocks, lots and buildings.
constexpr const char* kSketch = R"({"type": "FeatureCollection", "exacity": {"seed": 9,
  "zones": {"residential": {"block_area": 5000}}}, "features": [
  {"type": "Feature", "properties": {"zone": "residential"},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [200, 0], [200, 150], [0, 150], [0, 0]]]}},
  {"type": "Feature", "properties": {"zone": "commercial"},
   "geometry": {"type": "Polygon", "coordinates": [[[200, 0], [330, 0], [330, 150], [200, 150], [200, 0]]]}},
  {"type": "Feature", "properties": {"road": "main", "width": 12},
   "geometry": {"type": "LineString", "coordinates": [[-20, 75], [350, 75]]}}]})";

// report.json without what differs from run to run: the stages' seconds and memory.
std::string report_without_timings(const fs::path& file) {
  nlohmann::ordered_json report = nlohmann::ordered_json::parse(read(file));
  report.erase("timings_s");
  report.erase("peak_memory_mib");
  return report.dump(1);
}

// Every file of `expected` has the same bytes in `actual`, and `actual` has no others.
void expect_same_files(const fs::path& expected, const fs::path& actual) {
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(expected)) {
    if (!e.is_regular_file()) continue;
    const fs::path relative = fs::relative(e.path(), expected);
    ++files;
    if (relative == "report.json")
      EXPECT_EQ(report_without_timings(e.path()), report_without_timings(actual / relative));
    else
      EXPECT_TRUE(read(e.path()) == read(actual / relative)) << relative << " differs";
  }
  for (const auto& e : fs::recursive_directory_iterator(actual))
    if (e.is_regular_file()) {
      EXPECT_TRUE(fs::exists(expected / fs::relative(e.path(), actual))) << e.path();
    }
  EXPECT_GT(files, 10);
}

struct PlannedCity {
  fs::path dir, sketch, plan;
};

// The sketch planned as `tasks` tasks, each step run by the job script as Slurm would;
// `options`, given the city's folder, gives plan's other options.
PlannedCity planned(const std::string& name, int tasks, const std::string& steps = "roads lots buildings",
                    const std::function<std::string(const fs::path&)>& options = nullptr) {
  PlannedCity c;
  c.dir = testing_util::temp_dir(name);
  c.sketch = c.dir / "city.geojson";
  std::ofstream(c.sketch) << kSketch;
  c.plan = c.dir / "plan";
  const Result plan = run("plan " + c.sketch.string() + " -o " + c.plan.string() + " --tasks " + std::to_string(tasks) +
                          (options ? " " + options(c.dir) : std::string()));
  EXPECT_EQ(plan.code, 0) << plan.out;
  std::istringstream each(steps);
  for (std::string step; each >> step;)
    for (int task = 0; task < tasks; ++task) {
      const Result r = shell("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " EXACITY=" + EXACITY_BINARY + " bash " +
                             (kSource / "scripts" / "generate_city.sbatch").string() + " " + c.plan.string() + " " + step);
      EXPECT_EQ(r.code, 0) << r.out;
    }
  return c;
}

// The merge of `c`, with `exports` (merge's options), against generate's city of its
// sketch with `options` and `exports`: every file the same bytes; every region's and
// block's plan came from the tasks.
void expect_merged_as_generated(const PlannedCity& c, const std::string& options = "", const std::string& exports = "") {
  const Result whole = run("generate " + c.sketch.string() + " " + options + " " + exports + " -q -o " + (c.dir / "whole").string());
  ASSERT_EQ(whole.code, 0) << whole.out;
  const Result merge = run("merge " + c.plan.string() + " " + exports + " -o " + (c.dir / "merged").string());
  ASSERT_EQ(merge.code, 0) << merge.out;
  // Every region's and block's plan came from the tasks, and lots' structures too but for
  // lots merged after a first placement.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(merge.out, m, std::regex("region plans (\\d+) of (\\d+), block plans (\\d+) of (\\d+), "
                                                          "lot placements (\\d+) of (\\d+)")))
      << merge.out;
  EXPECT_EQ(m[1], m[2]);
  EXPECT_EQ(m[3], m[4]);
  EXPECT_GT(std::stoi(m[5]), 0);
  EXPECT_GT(std::stoi(m[1]), 1);
  expect_same_files(c.dir / "whole", c.dir / "merged");
}

}  // namespace

TEST(Plan, FourTasksMergedAreTheBytesGenerateWrites) { expect_merged_as_generated(planned("plan-merge", 4)); }

// What generate takes besides the sketch: plan carries --models and --like to its tasks and
// the merge (the zone parameters measured from the place before any item: else the merge
// would compute every item again), and merge writes the export options. (Plan refused them
// all before.) One task: the seams are the test above's. --buildings is carried as --models
// is, but reading footprints through OGR and PROJ costs a second a run in this build.
TEST(Plan, LikeModelsAndExportsAreGeneratesToo) {
  // Twelve footprints in metres, as drawn by hand (whole numbers): a place to measure.
  std::string place = R"({"type": "FeatureCollection", "features": [)";
  for (int i = 0; i < 12; ++i) {
    const int x = 210 + 18 * (i % 6), y = 100 + 20 * (i / 6), w = 8 + i % 3;
    place += std::string(i ? "," : "") + R"({"type": "Feature", "properties": {"building": "house"},
      "geometry": {"type": "Polygon", "coordinates": [[[)" + std::to_string(x) + ", " + std::to_string(y) + "], [" +
             std::to_string(x + w) + ", " + std::to_string(y) + "], [" + std::to_string(x + w) + ", " +
             std::to_string(y + 9) + "], [" + std::to_string(x) + ", " + std::to_string(y + 9) + "], [" +
             std::to_string(x) + ", " + std::to_string(y) + "]]]}}";
  }
  place += "]}";
  std::string options;
  const PlannedCity c = planned("plan-options", 1, "roads lots buildings", [&](const fs::path& dir) {
    std::ofstream(dir / "place.geojson") << place;
    options = "--like " + (dir / "place.geojson").string() + " --models " +
              (kSource / "examples" / "models" / "library.json").string();
    return options;
  });
  expect_merged_as_generated(c, options, "--cityjson-seq --osm-ids-from 1000");
  EXPECT_TRUE(fs::exists(c.dir / "merged" / "city.city.jsonl"));
}

TEST(Plan, MergeRefusesAMissingTaskAnotherPlansItemsAndAChangedSketch) {
  const PlannedCity c = planned("plan-refuse", 2);
  const fs::path out = c.dir / "merged";
  auto refused = [&](const std::string& why, const std::string& expected) {
    const Result r = run("merge " + c.plan.string() + " -q -o " + out.string());
    EXPECT_EQ(r.code, 2) << why << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << why << ": " << r.out;
    EXPECT_NE(r.out.find(expected), std::string::npos) << why << ": " << r.out;
    EXPECT_FALSE(fs::exists(out)) << why;
  };
  const fs::path items = c.plan / "tasks" / "1" / "buildings.items";
  const std::string kept = read(items);
  fs::remove(items);
  refused("task 1's buildings missing", items.string() + ": missing: task 1 has not run step buildings");
  std::ofstream(items, std::ios::binary) << kept;
  // A digit changed in the middle of task 0's lots, which still read as lots (it merged
  // into a city of other lots before the items' content id was checked).
  const fs::path lots = c.plan / "tasks" / "0" / "lots.items";
  const std::string lots_kept = read(lots);
  std::string changed = lots_kept;
  const std::size_t digit = changed.find_first_of("123456789", changed.size() / 2);
  ASSERT_NE(digit, std::string::npos);
  changed[digit] = changed[digit] == '9' ? '8' : static_cast<char>(changed[digit] + 1);
  std::ofstream(lots, std::ios::binary) << changed;
  refused("a digit of task 0's lots changed", "lots.items: damaged (its items are not the ones its task wrote)");
  std::ofstream(lots, std::ios::binary) << lots_kept;
  // Another plan's items: task 1 of a plan of 3 tasks.
  const PlannedCity other = planned("plan-refuse-other", 3, "roads");
  fs::copy_file(other.plan / "tasks" / "1" / "roads.items", c.plan / "tasks" / "1" / "roads.items",
                fs::copy_options::overwrite_existing);
  refused("another plan's roads", "roads.items: not this plan's task 1");
  // The sketch changed after the plan.
  std::ofstream(c.sketch, std::ios::app) << "\n";
  refused("the sketch changed", "changed since this plan was made");
}
