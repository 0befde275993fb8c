// The robustness benchmark's families and harness: the families are deterministic, and
// the exact build passes a slice of every family (the CI slice: an exact
// failure is a bug).
#include <gtest/gtest.h>

#include <sstream>

#include "benchmarks/families.h"
#include "benchmarks/robustness.h"
#include "tests/test_util.h"

using namespace exacity::bench;

TEST(RobustnessFamilies, SameSeedSameSketchesOtherSeedOthers) {
  ASSERT_EQ(families().size(), 8u);
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

TEST(Robustness, TheExactBuildPassesEveryCaseOfTheSlice) {
  RobustnessOptions o;
  o.cases = 2;
  o.seed = 20261123;
  o.out = testing_util::temp_dir("robustness-slice");
  o.programs = std::filesystem::path(EXACITY_BINARY).parent_path();
  o.builds = {"exact"};
  o.jobs = 2;
  o.time_limit = 300;  // the test build is unoptimised; a hang would still be caught
  std::ostringstream log;
  const std::vector<FamilyResult> results = run_robustness(o, log);
  ASSERT_EQ(results.size(), families().size());
  for (const FamilyResult& f : results) {
    ASSERT_EQ(f.builds.size(), 1u);
    const Outcome& exact = f.builds[0].second;
    EXPECT_EQ(exact.cases, 2) << f.family;
    EXPECT_EQ(exact.passed, 2) << f.family << "\n" << log.str();
  }
  // The report is written, and names every family.
  for (const char* file : {"robustness.json", "robustness.md", "robustness.svg"})
    EXPECT_TRUE(std::filesystem::is_regular_file(o.out / file)) << file;
}
