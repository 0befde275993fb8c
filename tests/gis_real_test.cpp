// A real OpenStreetMap extract (../shared/data, beside the repository, not in it) generated,
// validated and cross-checked with GEOS: a whole real city, so the sanitizer run leaves it
// to the test preset (label slow).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

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


// Helsinki's centre from its land use and streets (ogr2ogr exports of an extract): every
// centre line's road has a road area and a CityJSON Road object, short ways lying wholly on
// wider streets' surfaces among them (eight had none).
TEST(Gis, EveryRealRoadWithACentreLineHasAnAreaAndARoadObject) {
  const fs::path osm = cli_util::kSource / ".." / "shared" / "data" / "osm";
  if (!fs::exists(osm / "helsinki_centre_streets.geojson"))
    GTEST_SKIP() << osm << " is not here (../shared/data holds real data beside the repository)";
  const fs::path out = testing_util::temp_dir("gis-helsinki") / "out";
  fs::create_directories(out);
  StageClock clock(nullptr, kCityStages + kWriteStages);
  const Sketch sketch = load_sketch({osm / "helsinki_centre_landuse.geojson", osm / "helsinki_centre_streets.geojson"});
  const City city = build_city(sketch, clock);
  std::set<int> with_area;
  for (const RoadArea& a : city.ground.road_areas) with_area.insert(city.ground.roads.at(a.road).stable_id);
  EXPECT_EQ(with_area.size(), city.ground.roads.size());
  EXPECT_TRUE(city.ground.roads_without_area.empty());
  const GenerateResult result = write_city(sketch, city, out, clock);
  EXPECT_TRUE(result.valid) << result.report["validation"].dump();
  EXPECT_EQ(result.report["roads_without_area"], nlohmann::ordered_json::array());
  const nlohmann::json cityjson = nlohmann::json::parse(cli_util::read(out / "city.city.json"));
  std::set<int> road_objects;
  for (const auto& [id, o] : cityjson["CityObjects"].items())
    if (o["type"] == "Road") road_objects.insert(o["attributes"]["road"].get<int>());
  EXPECT_EQ(road_objects, with_area);
}

namespace {

// `exacity generate` of a place's land use and streets from ../shared/data/osm (PLACE_landuse
// and PLACE_streets.geojson) with `like` after them; its report.
nlohmann::json place_report(const std::string& place, const std::string& like, const fs::path& out) {
  const fs::path osm = cli_util::kSource / ".." / "shared" / "data" / "osm";
  const auto r = cli_util::run("generate " + (osm / (place + "_landuse.geojson")).string() + " " +
                               (osm / (place + "_streets.geojson")).string() + like + " -q -o " + out.string());
  EXPECT_EQ(r.code, 0) << r.out;
  return nlohmann::json::parse(cli_util::read(out / "report.json"));
}

// A generated figure within a quarter of the place's (the target; docs/gis.md,
// Looking like the place).
void expect_within_a_quarter(const std::string& zone, const nlohmann::json& is, const nlohmann::json& place) {
  EXPECT_LT(std::abs(is.get<double>() - place.get<double>()), 0.25 * place.get<double>())
      << zone << ": " << is << " against " << place;
}

// The generated footprints' median, p90 and coverage of the land use in each zone within a
// quarter of the mapped ones'.
void expect_like_the_place(const nlohmann::json& report, const std::vector<std::string>& zones) {
  for (const std::string& zone : zones) {
    const nlohmann::json& measured = report["like"]["zones"][zone]["measured"];
    const nlohmann::json& generated = report["footprints_by_zone"][zone]["generated"];
    expect_within_a_quarter(zone, generated["median_m2"], measured["area_m2"]["median"]);
    expect_within_a_quarter(zone, generated["p90_m2"], measured["area_m2"]["p90"]);
    expect_within_a_quarter(zone, generated["coverage_of_land_use"], measured["coverage_of_land_use"]);
  }
}

}  // namespace

// Helsinki's centre generated on its land use and streets without its buildings: with
// --like its buildings, the generated residential and commercial footprints' median comes
// from the defaults' houses to within a quarter of the mapped ones', and their p90 and
// coverage within a quarter too; perimeter blocks, since its buildings touch.
TEST(Gis, LikeBringsHelsinkisMedianFootprintToItsBuildings) {
  const fs::path osm = cli_util::kSource / ".." / "shared" / "data" / "osm";
  if (!fs::exists(osm / "helsinki_centre_buildings.geojson"))
    GTEST_SKIP() << osm << " is not here (../shared/data holds real data beside the repository)";
  const fs::path dir = testing_util::temp_dir("like_helsinki");
  const nlohmann::json before = place_report("helsinki_centre", "", dir / "before");
  const nlohmann::json after =
      place_report("helsinki_centre", " --like " + (osm / "helsinki_centre_buildings.geojson").string(), dir / "after");
  for (const char* zone : {"residential", "commercial"}) {
    const double mapped = after["like"]["zones"][zone]["measured"]["area_m2"]["median"].get<double>();
    const double was = before["footprints_by_zone"][zone]["generated"]["median_m2"].get<double>();
    EXPECT_GT(std::abs(was - mapped), 0.25 * mapped) << zone << ": " << was << " against " << mapped;
  }
  expect_like_the_place(after, {"residential", "commercial"});
}

// Kotka without its buildings, --like them: rows of footprints on lots apart from each
// other; its industrial land's few large halls among many sheds came out 32% and 43% under
// at the median and p90 while lots drew their footprints one at a time. Its industrial land
// gets about 80 footprints, whose p90 (the ninth largest) is one draw's: the same sketch at
// other seeds gives 959 to 1,920 m2 against the place's 1,682, and 80 footprints drawn from
// the place's own sizes miss a quarter's window one time in six. So the industrial land is
// held to its median and coverage; the residential land (about 1,500 footprints) to all three.
TEST(Gis, LikeBringsKotkasFootprintsToItsBuildings) {
  const fs::path osm = cli_util::kSource / ".." / "shared" / "data" / "osm";
  if (!fs::exists(osm / "kotka_pyrosm_test_buildings.geojson"))
    GTEST_SKIP() << osm << " is not here (../shared/data holds real data beside the repository)";
  const fs::path dir = testing_util::temp_dir("like_kotka");
  const nlohmann::json report =
      place_report("kotka_pyrosm_test", " --like " + (osm / "kotka_pyrosm_test_buildings.geojson").string(), dir / "out");
  expect_like_the_place(report, {"residential"});
  const nlohmann::json& measured = report["like"]["zones"]["industrial"]["measured"];
  const nlohmann::json& generated = report["footprints_by_zone"]["industrial"]["generated"];
  expect_within_a_quarter("industrial", generated["median_m2"], measured["area_m2"]["median"]);
  expect_within_a_quarter("industrial", generated["coverage_of_land_use"], measured["coverage_of_land_use"]);
}

// Completing a place: Helsinki's centre with half its buildings (those whose first corner
// lies in the dark squares of a 250 m checkerboard), --like all of them. What is mapped is
// kept, and the land the other half stood on is built with footprints whose median and p90
// are within a quarter of the place's, covering their lots within a quarter of what the
// mapped half covers of theirs.
TEST(Gis, CompletingHalfOfHelsinkisBuildingsBuildsTheRestLikeThePlace) {
  const fs::path osm = cli_util::kSource / ".." / "shared" / "data" / "osm";
  if (!fs::exists(osm / "helsinki_centre_buildings.geojson"))
    GTEST_SKIP() << osm << " is not here (../shared/data holds real data beside the repository)";
  const fs::path dir = testing_util::temp_dir("complete_helsinki");
  nlohmann::json buildings = nlohmann::json::parse(cli_util::read(osm / "helsinki_centre_buildings.geojson"));
  nlohmann::json half = nlohmann::json::array();
  const double metres_per_degree = 111320 * std::cos(60.17 * M_PI / 180);
  for (const nlohmann::json& f : buildings["features"]) {
    const nlohmann::json& g = f["geometry"];
    const nlohmann::json& corner = g["type"] == "Polygon" ? g["coordinates"][0][0] : g["coordinates"][0][0][0];
    const long x = std::lround(std::floor(corner[0].get<double>() * metres_per_degree / 250));
    const long y = std::lround(std::floor(corner[1].get<double>() * 110540 / 250));
    if ((x + y) % 2 != 0) half.push_back(f);
  }
  ASSERT_GT(half.size(), buildings["features"].size() / 3);
  ASSERT_LT(half.size(), 2 * buildings["features"].size() / 3);
  const std::size_t mapped = half.size();
  buildings["features"] = std::move(half);
  std::ofstream(dir / "half.geojson") << buildings.dump();
  const nlohmann::json report =
      place_report("helsinki_centre", " " + (dir / "half.geojson").string() + " --like " +
                                          (osm / "helsinki_centre_buildings.geojson").string(), dir / "out");
  EXPECT_TRUE(report["validation"]["ok"].get<bool>()) << report["validation"].dump();
  // Each polygon of a multipolygon is one in the sketch; all but the unbuildable few kept.
  const nlohmann::json& tally = report["mapped_buildings"];
  EXPECT_GE(tally["in_sketch"].get<std::size_t>(), mapped);
  EXPECT_GT(tally["kept"].get<int>() + tally["repaired"].get<int>(), 0.95 * tally["in_sketch"].get<int>()) << tally.dump(1);
  for (const char* zone : {"residential", "commercial"}) {
    const nlohmann::json& measured = report["like"]["zones"][zone]["measured"];
    const nlohmann::json& figures = report["footprints_by_zone"][zone];
    const nlohmann::json& generated = figures["generated"];
    EXPECT_GT(generated["footprints"].get<int>(), 30) << zone;
    expect_within_a_quarter(zone, generated["median_m2"], measured["area_m2"]["median"]);
    expect_within_a_quarter(zone, generated["p90_m2"], measured["area_m2"]["p90"]);
    expect_within_a_quarter(zone, generated["coverage_of_lots"], figures["mapped"]["coverage_of_lots"]);
  }
}
