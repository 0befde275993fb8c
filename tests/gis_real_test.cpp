// A real OpenStreetMap extract (../shared/data, beside the repository, not in it) generated,
// validated and cross-checked with GEOS: a whole real city, so the sanitizer run leaves it
// to the test preset (label slow).
#include <gtest/gtest.h>

#include "generate/sketch/sketch.h"
#include "generate/pipeline.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

using namespace exacity;
namespace fs = std::filesystem;

TEST(Gis, ARealExtractGeneratesAndValidates) {
  const fs::path extract = cli_util::kSource / ".." / "shared" / "data" / "osm" / "kotka_pyrosm_test.osm";
  if (!fs::exists(extract)) GTEST_SKIP() << extract << " is not here (../shared/data holds real data beside the repository)";
  const fs::path out = testing_util::temp_dir("gis-kotka") / "out";
  fs::create_directories(out);
  StageClock clock(nullptr, kCityStages + kWriteStages);
  const Sketch sketch = load_sketch(extract);
  const GenerateResult result = write_city(sketch, build_city(sketch, clock), out, clock);
  EXPECT_TRUE(result.valid) << result.report["validation"].dump();
  EXPECT_GT(result.report["counts"]["buildings"].get<int>(), 500);
  EXPECT_EQ(result.report["exports"]["city_osm"], "city.osm");
  EXPECT_EQ(cli_util::shell(cli_util::geos_check(out)).code, 0);
}

