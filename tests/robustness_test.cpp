// The robustness benchmark's families and harness: the families are deterministic, and
// the exact build passes a slice of every family while the baselines, the practitioner's
// float builds among them, run it too (the CI slice: an exact failure is a bug, a
// baseline's is a finding).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "benchmarks/child_process.h"
#include "benchmarks/families.h"
#include "benchmarks/judge.h"
#include "benchmarks/robustness.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

using namespace exacity::bench;

TEST(RobustnessFamilies, SameSeedSameSketchesOtherSeedOthers) {
  ASSERT_EQ(families().size(), 14u);
  for (const Family& f : families()) {
    SCOPED_TRACE(f.name);
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(family_sketch(f.name, i, 7), family_sketch(f.name, i, 7));
      EXPECT_NE(family_sketch(f.name, i, 7), family_sketch(f.name, i, 8));
    }
    EXPECT_NE(family_sketch(f.name, 0, 7), family_sketch(f.name, 1, 7));
  }
  EXPECT_THROW(family_sketch("no-such-family", 0, 1), std::invalid_argument);
}

TEST(RobustnessFamilies, EveryCaseHasALevelTheControlsIsZero) {
  for (const Family& f : families()) {
    SCOPED_TRACE(f.name);
    EXPECT_FALSE(f.level.empty());
    for (int i = 0; i < 8; ++i) {
      const FamilyCase c = family_case(f.name, i, 7);
      EXPECT_EQ(c.sketch, family_sketch(f.name, i, 7));
      EXPECT_TRUE(std::isfinite(c.level));
      if (f.name == "random") {
        EXPECT_EQ(c.level, 0);
      }
    }
  }
  // The sweeps' ends: 1e-3 rad is level 3; a distance's level is how many powers of ten it
  // lies below the snapping grid, 2^-24 m (0.1 m: -6.2, 1e-12 m: 4.8). The sweep's step
  // runs fastest, so the first cases of a family cover its levels.
  const double grid = std::ldexp(1.0, -24);
  EXPECT_DOUBLE_EQ(family_case("thin-angles", 0, 7).level, 3);
  EXPECT_DOUBLE_EQ(family_case("thin-angles", 9, 7).level, 12);
  EXPECT_NEAR(family_case("off-edge", 0, 7).level, std::log10(grid / 0.1), 1e-9);
  EXPECT_NEAR(family_case("off-edge", 11, 7).level, std::log10(grid / 1e-12), 0.01);
  EXPECT_NEAR(family_case("off-edge", 12, 7).level, std::log10(grid / 1e-13), 0.1);  // two ulps off at 300 m
  EXPECT_GT(family_case("off-edge", 13, 7).level, 6);                                // on the edge: 300 + 1e-14 is 300
  EXPECT_NEAR(family_case("off-edge", 25, 7).level, std::log10(grid / 1e-12), 0.01);
  EXPECT_DOUBLE_EQ(family_case("translated", 3, 7).level, 8);
  EXPECT_DOUBLE_EQ(family_case("translated", 5, 7).level, 9);
  EXPECT_DOUBLE_EQ(family_case("translated", 6, 7).level, 9.5);  // a 1e-6 m grid is two doubles' steps there
  EXPECT_DOUBLE_EQ(family_case("many-highways", 0, 7).level, 2);
  EXPECT_DOUBLE_EQ(family_case("many-highways", 23, 7).level, 13);
  EXPECT_NEAR(family_case("near-touching", 11, 7).level, std::log10(grid / 1e-12), 0.01);
  EXPECT_NEAR(family_case("slivers", 0, 7).level, std::log10(grid / 0.1), 0.01);
  EXPECT_NEAR(family_case("tiny-holes", 0, 7).level, std::log10(grid / 0.1), 0.01);
  EXPECT_NEAR(family_case("tiny-holes", 23, 7).level, std::log10(grid / 1e-12), 0.01);
  // Kettner's corners from 0.1 m off the line down to below a double's step there (on it).
  EXPECT_NEAR(family_case("near-collinear", 0, 7).level, std::log10(grid / 0.1), 0.01);
  EXPECT_GT(family_case("near-collinear", 13, 7).level, 6);
  // 1 to 12 zone edges in one band.
  EXPECT_DOUBLE_EQ(family_case("stacked-edges", 0, 7).level, 1);
  EXPECT_DOUBLE_EQ(family_case("parallel-edges", 23, 7).level, 12);
}

// The band families: case i holds 1 + i % 12 zones over the background, each with one edge
// from within half the band (3e-7 m in the first 12 cases, 5e-6 m in the next) of one point
// to within half the band of another; the parallel family's edges are one another moved.
TEST(RobustnessFamilies, TheBandFamiliesEdgesRunInTheirBand) {
  for (const char* family : {"stacked-edges", "parallel-edges"})
    for (int i : {0, 5, 11, 12, 23}) {
      SCOPED_TRACE(std::string(family) + " " + std::to_string(i));
      const auto sketch = nlohmann::json::parse(family_sketch(family, i, 7));
      const auto& features = sketch["features"];
      const double band = i < 12 ? 3e-7 : 5e-6;
      std::vector<nlohmann::json> edges;
      for (const auto& f : features)
        if (f["properties"].contains("zone") && f["properties"]["zone"] != "residential")
          edges.push_back(f["geometry"]["coordinates"][0]);
      ASSERT_EQ(edges.size(), static_cast<std::size_t>(1 + i % 12));
      // Each zone's edge from its first corner to the one next to it (even zones) or before
      // the closing one (odd zones).
      auto ends = [](const nlohmann::json& ring, std::size_t k) {
        const auto& p = ring[0];
        const auto& q = k % 2 == 0 ? ring[1] : ring[ring.size() - 2];
        return std::array<double, 4>{p[0].get<double>(), p[1].get<double>(), q[0].get<double>(), q[1].get<double>()};
      };
      const auto first = ends(edges[0], 0);
      for (std::size_t k = 0; k < edges.size(); ++k) {
        const auto e = ends(edges[k], k);
        for (int c = 0; c < 4; ++c) EXPECT_LE(std::abs(e[c] - first[c]), band) << k << " " << c;
        if (std::string(family) == "parallel-edges") {
          // Moved as one: the same offset at both ends, to a few ulps.
          EXPECT_NEAR(e[0] - first[0], e[2] - first[2], 1e-12) << k;
          EXPECT_NEAR(e[1] - first[1], e[3] - first[3], 1e-12) << k;
        }
      }
    }
}

// The stacked families: case i holds 1 + i % 12 zones over the background, each a third of
// a grid step (2e-8 m in the first 12 cases, 3e-7 m in the next) from the last: nested
// squares whose corners move in by that much on each axis of the square, or slivers that wide.
TEST(RobustnessFamilies, TheStackedFamiliesStepAThirdOfAGridStep) {
  for (const char* family : {"nested-rings", "sliver-stack"})
    for (int i : {0, 5, 11, 12, 23}) {
      SCOPED_TRACE(std::string(family) + " " + std::to_string(i));
      const FamilyCase c = family_case(family, i, 7);
      EXPECT_DOUBLE_EQ(c.level, 1 + i % 12);
      const auto sketch = nlohmann::json::parse(c.sketch);
      std::vector<std::array<double, 2>> first_corners;
      for (const auto& f : sketch["features"])
        if (f["properties"].contains("zone") && f["properties"]["zone"] != "residential") {
          const auto& p = f["geometry"]["coordinates"][0][0];
          first_corners.push_back({p[0].get<double>(), p[1].get<double>()});
        }
      ASSERT_EQ(first_corners.size(), static_cast<std::size_t>(1 + i % 12));
      const double step = (i < 12 ? 2e-8 : 3e-7) * (std::string(family) == "nested-rings" ? std::sqrt(2.0) : 1.0);
      for (std::size_t k = 1; k < first_corners.size(); ++k)
        EXPECT_NEAR(std::hypot(first_corners[k][0] - first_corners[k - 1][0], first_corners[k][1] - first_corners[k - 1][1]),
                    step, 1e-12) << k;
    }
}

// A distance family is cumulative: a deeper case holds a feature at every step of the sweep
// down to its own, so it has more vertices than a shallower one of the same variant.
TEST(RobustnessFamilies, ADeeperCaseHoldsEveryShallowerStep) {
  for (const char* family : {"near-collinear", "off-edge", "slivers", "near-touching", "tiny-holes"}) {
    SCOPED_TRACE(family);
    std::size_t last_vertices = 0;
    double last_level = -INFINITY;
    for (int i = 0; i < 12; ++i) {
      const FamilyCase c = family_case(family, i, 7);
      const std::size_t vertices = static_cast<std::size_t>(std::count(c.sketch.begin(), c.sketch.end(), '['));
      EXPECT_GT(vertices, last_vertices) << i;
      EXPECT_GT(c.level, last_level) << i;
      last_vertices = vertices, last_level = c.level;
    }
  }
}

TEST(Robustness, TheExactBuildPassesEveryCaseOfTheSliceAndTheBaselinesRunIt) {
  RobustnessOptions o;
  o.cases = 2;
  o.seed = 20261123;
  o.out = testing_util::temp_dir("robustness-slice");
  o.programs = std::filesystem::path(EXACITY_BINARY).parent_path();
  // Not float-simple-snapped: it fails exactly the cases float-snapped fails (docs/benchmarks.md),
  // so the slice would learn nothing from it for one more geom/ library in the test build.
  o.builds = {"exact", "float-grid", "float-snapped", "cgal-snap", "geos-floating", "geos-fixed"};
  o.jobs = 2;
  o.time_limit = 300;  // the test build is unoptimised; a hang would still be caught
  std::ostringstream log;
  const std::vector<FamilyResult> results = run_robustness(o, log);
  ASSERT_EQ(results.size(), families().size());
  for (const FamilyResult& f : results) {
    ASSERT_EQ(f.builds.size(), o.builds.size());
    const Outcome& exact = f.builds[0].second;
    EXPECT_EQ(exact.cases, 2) << f.family;
    EXPECT_EQ(exact.passed, 2) << f.family << "\n" << log.str();
    for (std::size_t b = 1; b < o.builds.size(); ++b) {
      EXPECT_EQ(f.builds[b].first, o.builds[b]);
      EXPECT_EQ(f.builds[b].second.cases, 2) << f.family;  // it may fail them; it ran them
    }
    ASSERT_EQ(f.cases.size(), 2u);
    for (const CaseResult& c : f.cases) {
      EXPECT_EQ(c.level, family_case(f.family, c.index, o.seed).level);
      EXPECT_EQ(c.results.at(0), "passed");
      // Every baseline has a verdict on every case: a crash or a hang inside CGAL on
      // inexact predicates is that case's failure, not the run's.
      ASSERT_EQ(c.results.size(), o.builds.size());
      for (const std::string& r : c.results)
        EXPECT_TRUE(r == "passed" || r == "crash" || r == "hang" || r == "error" || r == "rejected") << r;
    }
  }
  // The report is written; the JSON has each case's level and results.
  for (const char* file : {"robustness.json", "robustness.md", "robustness.svg"})
    EXPECT_TRUE(std::filesystem::is_regular_file(o.out / file)) << file;
  std::ifstream in(o.out / "robustness.json");
  const auto doc = nlohmann::json::parse(in);
  ASSERT_EQ(doc["families"].size(), families().size());
  const auto& first = doc["families"][0];
  ASSERT_EQ(first["per_case"].size(), 2u);
  EXPECT_EQ(first["per_case"][0]["exact"], "passed");
  EXPECT_TRUE(first["per_case"][0].contains("level"));
  EXPECT_TRUE(first["per_case"][0].contains("float-snapped"));
  EXPECT_TRUE(first["per_case"][0].contains("float-grid"));
  EXPECT_TRUE(first["per_case"][0].contains("cgal-snap"));
  EXPECT_TRUE(first["per_case"][0].contains("geos-fixed"));
  // Per stage, for every build but the exact one; the partition baselines write no stage timings.
  const auto& by_stage = doc["exact_over_this_time_by_stage"];
  for (const char* build : {"float-grid", "float-snapped", "cgal-snap", "geos-floating", "geos-fixed"})
    EXPECT_TRUE(by_stage.contains(build)) << build;
  EXPECT_TRUE(by_stage["cgal-snap"].empty());
  EXPECT_TRUE(by_stage["geos-fixed"].empty());
  // Each build's failures by level where a family's cases differ in level (never the control's).
  for (const auto& family : doc["families"]) {
    SCOPED_TRACE(family["family"].get<std::string>());
    // As drawn, not as the JSON rounds them to a thousandth: two cases a double's rounding
    // apart differ.
    const std::string name = family["family"];
    const bool levels_differ = family_case(name, 0, o.seed).level != family_case(name, 1, o.seed).level;
    EXPECT_EQ(family["float-snapped"].contains("by_level"), levels_differ);
    if (family["family"] == "random") {
      EXPECT_FALSE(levels_differ);
    }
  }
  for (const auto& [stage, r] : by_stage["float-snapped"].items()) {
    EXPECT_GT(r["cases"].get<int>(), 0) << stage;
    EXPECT_LE(r["p25"].get<double>(), r["median"].get<double>()) << stage;
    EXPECT_LE(r["median"].get<double>(), r["p75"].get<double>()) << stage;
  }
}

// Each build runs a case in a child process, so a baseline that dies inside CGAL (on inexact
// predicates its sweep can segfault or loop) fails that case and the run goes on: a signal
// is a crash, and a child still running at the limit is killed and counted a hang.
TEST(Robustness, AChildThatDiesOrOutrunsItsLimitIsContained) {
  using Child = exacity::bench::Run;  // gtest's Test has a Run of its own
  const std::filesystem::path dir = testing_util::temp_dir("robustness-child");
  const Child crashed = run_child({"/bin/sh", "-c", "kill -SEGV $$"}, dir / "crash.log", 60);
  EXPECT_EQ(crashed.status, Child::Signalled);
  EXPECT_EQ(crashed.code, SIGSEGV);
  const Child hung = run_child({"/bin/sleep", "600"}, dir / "hang.log", 0.2);
  EXPECT_EQ(hung.status, Child::TimedOut);
  const Child failed = run_child({"/bin/sh", "-c", "exit 3"}, dir / "exit.log", 60);
  EXPECT_EQ(failed.status, Child::Exited);
  EXPECT_EQ(failed.code, 3);
}

// A build name the benchmark does not know is refused, before anything runs: left out, a
// run the caller took for a measure of that build would not be one.
TEST(Robustness, AnUnknownBuildIsRefused) {
  RobustnessOptions o;
  o.families = {"random"};
  o.cases = 1;
  o.out = testing_util::temp_dir("robustness-unknown-build");
  o.programs = o.out / "programs";
  std::filesystem::create_directories(o.programs);
  std::ofstream(o.programs / "exacity") << "";  // the exact build is there; nothing runs
  o.builds = {"exact", "float-snaped"};
  std::ostringstream log;
  try {
    run_robustness(o, log);
    ADD_FAILURE() << "ran without float-snaped:\n" << log.str();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--build float-snaped: no such build"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(o.out / "robustness.json"));
}

// A build's failures rise with the level where it fails more of the cases above the family's
// median level than of the others; the control, all at one level, has no upper half.
TEST(Robustness, LevelTrendComparesTheCasesAboveTheMedianLevelWithTheRest) {
  FamilyResult f{"off-edge", {}, {}, {}};
  const double levels[] = {1, 2, 2, 5, 9};
  const char* baseline[] = {"passed", "crash", "passed", "rejected", "hang"};
  for (int i = 0; i < 5; ++i) f.cases.push_back({i, levels[i], {"passed", baseline[i]}});
  const LevelTrend exact = level_trend(f, 0), other = level_trend(f, 1);
  EXPECT_EQ(other.median_level, 2);
  EXPECT_EQ(other.low_cases, 3);
  EXPECT_EQ(other.low_failed, 1);
  EXPECT_EQ(other.high_cases, 2);
  EXPECT_EQ(other.high_failed, 2);
  EXPECT_TRUE(other.rises());
  EXPECT_FALSE(exact.rises());
  FamilyResult control{"random", {}, {{0, 0, {"passed", "crash"}}, {1, 0, {"passed", "passed"}}}, {}};
  EXPECT_EQ(level_trend(control, 1).high_cases, 0);
  EXPECT_FALSE(level_trend(control, 1).rises());
}

// --export writes each case's sketch as the benchmark runs it, and beside it its level and
// the judge's invariants, for another tool to be scored on the same cases.
TEST(Robustness, ExportWritesEveryCaseWithItsLevelAndTheJudgesInvariants) {
  RobustnessOptions o;
  o.cases = 2;
  o.seed = 7;
  o.families = {"off-edge", "random"};
  const std::filesystem::path dir = testing_util::temp_dir("robustness-export");
  EXPECT_EQ(export_cases(o, dir), 4);
  for (const std::string& family : o.families)
    for (int i = 0; i < 2; ++i) {
      SCOPED_TRACE(family + " " + std::to_string(i));
      EXPECT_EQ(cli_util::read(dir / family / (std::to_string(i) + ".geojson")), family_sketch(family, i, 7));
      std::ifstream in(dir / family / (std::to_string(i) + ".json"));
      const auto about = nlohmann::json::parse(in);
      EXPECT_EQ(about["level"].get<double>(), family_case(family, i, 7).level);
      EXPECT_EQ(about["sketch"], std::to_string(i) + ".geojson");
      std::set<std::string> kinds;
      for (const auto& inv : about["judge"]["invariants"]) kinds.insert(inv["kind"].get<std::string>());
      EXPECT_EQ(kinds, (std::set<std::string>{"invalid", "overlap", "gap", "label", "outside", "network"}));
    }
}

// A baseline program beside exacity generating an example into `out` (made empty first).
cli_util::Result generate_with(const char* program, const char* example, const std::filesystem::path& out,
                               const std::string& options) {
  std::filesystem::remove_all(out);
  const std::filesystem::path binary = std::filesystem::path(EXACITY_BINARY).parent_path() / program;
  return cli_util::shell(binary.string() + " generate " + (cli_util::kSource / "examples" / example).string() + " -o " +
                         out.string() + " " + options);
}

// The GEOS baseline writes Exacity's layers, which the judge reads: the default example's
// partition in GEOS's default (floating) overlay passes it. A sketch it cannot read is one
// line, exit 2, and nothing written.
TEST(Robustness, TheGeosBaselinePartitionsTheTownAsTheJudgeWants) {
  const std::filesystem::path out = testing_util::temp_dir("geos-town");
  const cli_util::Result r = generate_with("exacity-geos", "town.geojson", out, "--precision floating");
  ASSERT_EQ(r.code, 0) << r.out;
  const Verdict v = judge(out);
  EXPECT_TRUE(v.passed()) << testing::PrintToString(v.problems);
  std::ifstream in(out / "vector" / "lots.geojson");
  EXPECT_GT(nlohmann::json::parse(in)["features"].size(), 100u);

  const cli_util::Result bad = generate_with("exacity-geos", "grid/town.grid", out, "");
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_NE(bad.out.find("not a GeoJSON FeatureCollection"), std::string::npos) << bad.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The CGAL baseline's partition is sound where constructions are exact: on the exact kernel
// the town passes the judge (on the inexact one, as the benchmark runs it, CGAL's own
// intersection sweep inside snap rounding fails on it). A kernel it does not know is one
// line, exit 2, and nothing written.
TEST(Robustness, TheCgalBaselinePartitionsTheTownOnTheExactKernel) {
  const std::filesystem::path out = testing_util::temp_dir("cgal-snap-town");
  const cli_util::Result r = generate_with("exacity-cgal-snap", "town.geojson", out, "--kernel exact");
  ASSERT_EQ(r.code, 0) << r.out;
  const Verdict v = judge(out);
  EXPECT_TRUE(v.passed()) << testing::PrintToString(v.problems);
  std::ifstream in(out / "vector" / "lots.geojson");
  EXPECT_GT(nlohmann::json::parse(in)["features"].size(), 100u);

  const cli_util::Result bad = generate_with("exacity-cgal-snap", "town.geojson", out, "--kernel double");
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_NE(bad.out.find("--kernel: inexact or exact"), std::string::npos) << bad.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The practitioner's float build runs the examples: tangle's grown roads stop at edges that
// the city map's batch routed through other hot pixels, and ended in the open beside them
// until ends got a snap tolerance. Its output passes the exact build's validator.
TEST(Robustness, TheSnappedBuildsTangleEndsNoRoadInTheOpen) {
  const std::filesystem::path out = testing_util::temp_dir("snapped-tangle");
  const cli_util::Result r = generate_with("exacity-float-snapped", "tangle.geojson", out, "-q --threads 1");
  ASSERT_EQ(r.code, 0) << r.out;
  const cli_util::Result v = cli_util::shell(std::string(EXACITY_BINARY) + " validate " + out.string());
  EXPECT_EQ(v.code, 0) << v.out;
  EXPECT_EQ(v.out.find("ends in the open"), std::string::npos) << v.out;
}

// A family's case run through a build, as the benchmark runs it (one thread), into `out`.
cli_util::Result generate_case(const char* program, const std::string& family, int index, std::uint64_t seed,
                               const std::filesystem::path& out) {
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out.parent_path());
  const std::filesystem::path sketch = out.string() + ".geojson";
  std::ofstream(sketch, std::ios::binary) << family_sketch(family, index, seed);
  const std::filesystem::path binary = std::filesystem::path(EXACITY_BINARY).parent_path() / program;
  return cli_util::shell(binary.string() + " generate " + sketch.string() + " -o " + out.string() + " -q --threads 1");
}

// A zone's corner 1 cm inside its neighbour, 238 m up a shared edge of 400 m: the sliver's
// long edges rise 4 mm for every nanometre they run across. While lots went into the
// block beside it, the practitioner's float build snapped the ends of the map's own edges
// (copied into the block's arrangement) to its grid: a sliver edge that had been split at
// a point off the grid, less than a grid step wide, became a vertical one running the other
// way, the block's outside was taken for its inside, and CGAL's precondition `f == f2`
// stopped the insertion (exit 3). The ends of edges the arrangement has stay where they are.
TEST(Robustness, TheSnappedBuildKeepsTheMapsVerticesWhereTheyAreBesideACentimetreSliver) {
  const std::filesystem::path dir = testing_util::temp_dir("snapped-sliver"), out = dir / "out";
  const std::filesystem::path sketch = dir / "sliver.geojson";
  std::ofstream(sketch, std::ios::binary)
      << R"({"type":"FeatureCollection","exacity":{"version":1,"seed":4531091233315400},"features":[)"
      << R"({"type":"Feature","properties":{"zone":"residential"},"geometry":{"type":"Polygon","coordinates":)"
      << R"([[[0,0],[300,0],[300,400],[0,400],[0,0]]]}},)"
      << R"({"type":"Feature","properties":{"zone":"commercial"},"geometry":{"type":"Polygon","coordinates":)"
      << R"([[[300,0],[600,0],[600,400],[300,400],[299.99,238.24421125493612],[300,0]]]}}]})";
  const std::filesystem::path binary = std::filesystem::path(EXACITY_BINARY).parent_path() / "exacity-float-snapped";
  const cli_util::Result r =
      cli_util::shell(binary.string() + " generate " + sketch.string() + " -o " + out.string() + " -q --threads 1");
  ASSERT_EQ(r.code, 0) << r.out;
  const Verdict v = judge(out);
  EXPECT_TRUE(v.passed()) << testing::PrintToString(v.problems);
  const cli_util::Result check = cli_util::shell(std::string(EXACITY_BINARY) + " validate " + out.string());
  EXPECT_EQ(check.code, 0) << check.out;
}

// The practitioner's float build split the map's edges in place at the hot pixels of each
// new batch, bending them off their lines; a bent edge could leave the edges around its end
// out of order or a vertex on its wrong side, and CGAL's precondition `f == f2` stopped the
// control's case 2 at seed 1 when the grown roads went in. The bent edges now go in again by
// CGAL's insertion: the case passes the judge and the exact validator.
TEST(Robustness, TheSnappedBuildInsertsBentEdgesAgainAndPassesTheControlCaseItCrashedOn) {
  const std::filesystem::path out = testing_util::temp_dir("snapped-random-2") / "out";
  const cli_util::Result r = generate_case("exacity-float-snapped", "random", 2, 1, out);
  ASSERT_EQ(r.code, 0) << r.out;
  const Verdict v = judge(out);
  EXPECT_TRUE(v.passed()) << testing::PrintToString(v.problems);
  const cli_util::Result check = cli_util::shell(std::string(EXACITY_BINARY) + " validate " + out.string());
  EXPECT_EQ(check.code, 0) << check.out;
}

// The grid build (exacity-float-grid, a decimal 1e-6 m grid) snapped the sketch's own corners
// onto its grid with every constructed point, so the written zones missed the drawn ones by
// sub-micrometre slivers (this control case: 0.0006 m2 uncovered, more than the judge's 1e-9
// of the drawn area, and 14 of its 16 drawn corners written up to 0.7 µm off; 1 of the 40
// control cases passed). Snap rounding now decides on the grid which pixels each segment
// passes through, and a pixel holding a drawn corner is written at that corner.
TEST(Robustness, TheGridBuildKeepsTheSketchsCornersAsDrawnAndPassesTheControl) {
  const std::filesystem::path out = testing_util::temp_dir("grid-random-0") / "out";
  const cli_util::Result r = generate_case("exacity-float-grid", "random", 0, 1, out);
  ASSERT_EQ(r.code, 0) << r.out;
  const Verdict v = judge(out);
  EXPECT_TRUE(v.passed()) << testing::PrintToString(v.problems);
  const cli_util::Result check = cli_util::shell(std::string(EXACITY_BINARY) + " validate " + out.string());
  EXPECT_EQ(check.code, 0) << check.out;
  auto corners = [](const nlohmann::json& doc, const char* key) {
    std::set<std::pair<double, double>> points;
    for (const auto& f : doc["features"]) {
      if (key && !f["properties"].contains(key)) continue;
      const auto& g = f["geometry"];
      const auto polygons = g["type"] == "Polygon" ? nlohmann::json::array({g["coordinates"]}) : g["coordinates"];
      for (const auto& polygon : polygons)
        for (const auto& ring : polygon)
          for (const auto& p : ring) points.insert({p[0].get<double>(), p[1].get<double>()});
    }
    return points;
  };
  std::ifstream sketch(out.string() + ".geojson");
  const auto drawn = corners(nlohmann::json::parse(sketch), "zone");
  std::set<std::pair<double, double>> written;
  for (const char* layer : {"zones", "water", "road_areas"}) {
    std::ifstream in(out / "vector" / (std::string(layer) + ".geojson"));
    written.merge(corners(nlohmann::json::parse(in), nullptr));
  }
  // A corner under a zone drawn later is no written vertex; one that is, is written exactly:
  // no written vertex lies within a micrometre of a drawn corner but the corner itself.
  int exactly = 0;
  for (const auto& [x, y] : drawn) {
    exactly += written.count({x, y});
    for (auto it = written.lower_bound({x - 1e-6, -INFINITY}); it != written.end() && it->first <= x + 1e-6; ++it)
      if (std::abs(it->second - y) <= 1e-6) {
        EXPECT_TRUE(it->first == x && it->second == y)
            << x << " " << y << " written at " << it->first << " " << it->second;
      }
  }
  EXPECT_GE(exactly, 10) << "of " << drawn.size();
}
