// Grid filling (docs/design.md, Placement) on hand-made lots and models: the serpentine, footprint grids
// that follow the real outline, largest first, a notch taken by a smaller model, never an
// overlap, and the same fill from the same stream.
#include "generate/placement/building_settings.h"
#include "generate/placement/grid_filling.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <fstream>

#include "generate/export/validate.h"
#include "generate/pipeline.h"
#include "geom/polygon_check.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

namespace exacity {
namespace {

using geom::Vec2;

// A library model from its footprint alone (placement never reads the mesh), its
// bounding box centred on the origin as the library's are.
Model model(const std::string& name, geom::Ring outline, double weight = 1) {
  Model m;
  m.name = name;
  m.weight = weight;
  m.min_scale = m.max_scale = 1;
  geom::Box box = geom::Box::none();
  for (Vec2 v : outline) box.add(v);
  const Vec2 c{(box.min_x + box.max_x) / 2, (box.min_y + box.max_y) / 2};
  for (Vec2& v : outline) v = v - c;
  m.outline = std::move(outline);
  m.width = box.width(), m.depth = box.height(), m.height = 6;
  return m;
}

// An L 20 m across, its notch (10 x 10) at the back right; a 6 m square.
ModelLibrary l_and_square() {
  ModelLibrary lib;
  lib.models.push_back(model("l", {{0, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 20}, {0, 20}}));
  lib.models.push_back(model("square", {{0, 0}, {6, 0}, {6, 6}, {0, 6}}));
  for (Model& m : lib.models) m.zones = {ZoneType::Residential};
  return lib;
}

BuildingSettings tight() {
  BuildingSettings p;
  p.setback = 0, p.building_gap = 0;
  return p;
}

std::vector<ModelInstance> fill(const geom::Cell& lot, const ModelLibrary& lib, const BuildingSettings& p, std::uint64_t seed,
                                const GridFillingSettings& grid = {}) {
  const Channels none;
  const auto filler = make_grid_filler(lib, ZoneType::Residential, none, grid);
  EXPECT_NE(filler, nullptr);
  Occupancy occupancy(lot, LotEdge::kStreet);
  Random rng(seed);
  Structures out;
  filler->place(Lot{}, p, occupancy, rng, out);
  return out.models;
}

TEST(GridFilling, TheSerpentineRunsAlongARowThenBack) {
  const std::vector<std::pair<int, int>> expected{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}, {0, 2}, {1, 2}, {2, 2}};
  EXPECT_EQ(serpentine(3, 3), expected);
  EXPECT_TRUE(serpentine(0, 4).empty());
}

TEST(GridFilling, AFootprintGridCoversTheOutlineNotItsBox) {
  const FootprintGrid l = footprint_grid({{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}}, 1);
  ASSERT_EQ(l.width, 4);
  ASSERT_EQ(l.height, 4);
  EXPECT_EQ(l.cells, 12);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) EXPECT_EQ(l.at(i, j), !(i >= 2 && j >= 2)) << i << ", " << j;
  // A square on the cells' lines covers its own cells, none beyond; one off them, every
  // cell it enters.
  EXPECT_EQ(footprint_grid({{0, 0}, {3, 0}, {3, 3}, {0, 3}}, 1).cells, 9);
  const FootprintGrid off = footprint_grid({{0.5, 0.5}, {2.7, 0.5}, {2.7, 1.2}, {0.5, 1.2}}, 1);
  EXPECT_EQ(off.width, 3);
  EXPECT_EQ(off.height, 1);
  EXPECT_EQ(off.cells, 3);
  // A diagonal sliver enters the cells along it only.
  const FootprintGrid diagonal = footprint_grid({{0, 0}, {0.2, 0}, {4, 3.8}, {4, 4}, {3.8, 4}, {0, 0.2}}, 1);
  EXPECT_EQ(diagonal.cells, 4 + 2 * 3);
}

TEST(GridFilling, LargestFirstAndTheLNotchTakesASmallModel) {
  // A lot 23 m square on its street (south): the L fills it but its notch (cells within
  // half a cell's diagonal of the lot's edge are not used).
  const geom::Cell lot = testing_util::fronted_cell({{0, 0}, {23, 0}, {23, 23}, {0, 23}}, {0});
  const ModelLibrary lib = l_and_square();
  const std::vector<ModelInstance> placed = fill(lot, lib, tight(), 3);
  ASSERT_GE(placed.size(), 2u);
  EXPECT_EQ(placed[0].placed.model, 0) << "the L is the largest: it goes first";
  int in_notch = 0;
  for (std::size_t k = 1; k < placed.size(); ++k) {
    EXPECT_EQ(placed[k].placed.model, 1);
    const Vec2 p = placed[k].placed.position;
    in_notch += p.x > 11 && p.y > 11;
  }
  EXPECT_EQ(in_notch, 1) << "one square stands in the L's notch";
  // The L stands at the serpentine's first place, its front (-y) to the street: row 0 is
  // the edge's clearance, so row 1, which runs east to west: cells 2 to 21, its centre 12.
  EXPECT_NEAR(placed[0].placed.angle, 0, 1e-12);
  EXPECT_EQ(placed[0].placed.position, (Vec2{12, 11}));
}

TEST(GridFilling, NothingOverlapsAndEverythingStandsInTheLot) {
  // A long skewed lot, two streets, the default gaps, three passes.
  const geom::Cell lot = testing_util::fronted_cell({{0, 0}, {90, 8}, {84, 70}, {-6, 55}}, {0, 1});
  ModelLibrary lib = l_and_square();
  lib.models.push_back(model("bar", {{0, 0}, {14, 0}, {14, 5}, {0, 5}}, 2));
  lib.models.back().zones = {ZoneType::Residential};
  const BuildingSettings p;
  const GridFillingSettings grid{.cell = 0.5, .passes = 3};
  const std::vector<ModelInstance> placed = fill(lot, lib, p, 11, grid);
  ASSERT_GT(placed.size(), 8u);
  for (std::size_t a = 0; a < placed.size(); ++a) {
    EXPECT_TRUE(lot.holds(placed[a].polygon.outer));
    for (std::size_t b = a + 1; b < placed.size(); ++b)
      EXPECT_FALSE(geom::rings_meet(placed[a].polygon.outer, placed[b].polygon.outer)) << a << " and " << b;
  }
  // The same stream fills the same way.
  const std::vector<ModelInstance> again = fill(lot, lib, p, 11, grid);
  ASSERT_EQ(again.size(), placed.size());
  for (std::size_t k = 0; k < placed.size(); ++k) EXPECT_EQ(again[k].polygon.outer, placed[k].polygon.outer);
}

TEST(GridFilling, AModelLargerThanTheLotIsLeftOut) {
  const geom::Cell lot = testing_util::fronted_cell({{0, 0}, {8, 0}, {8, 8}, {0, 8}}, {0});
  ModelLibrary lib;
  lib.models.push_back(model("tower", {{0, 0}, {30, 0}, {30, 30}, {0, 30}}));
  lib.models.back().zones = {ZoneType::Residential};
  EXPECT_TRUE(fill(lot, lib, tight(), 1).empty());
}

// A small city of the example library's models, grid-filled: it validates, every zone's
// models stand, and one or two threads write the same bytes.
TEST(GridFilling, ACityFilledOnTheGridValidatesTheSameWhateverTheThreadCount) {
  auto generate = [](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const auto dir = testing_util::temp_dir("grid-filling-" + std::to_string(threads));
    const std::string grid = R"({"placement": "grid"})";
    std::ofstream(dir / "in.geojson") << R"({"type": "FeatureCollection", "exacity": {"seed": 4, "models": ")"
                                      << (cli_util::kSource / "examples" / "models" / "library.json").string()
                                      << R"(", "zones": {"residential": )" << grid << R"(, "commercial": )" << grid << R"(}},
      "features": [
      {"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[300,0],[300,250],[0,250],[0,0]]]}},
      {"type": "Feature", "properties": {"zone": "commercial"}, "geometry": {"type": "Polygon", "coordinates": [[[300,0],[500,0],[500,250],[300,250],[300,0]]]}},
      {"type": "Feature", "properties": {"road": "main"}, "geometry": {"type": "LineString", "coordinates": [[-20,125],[520,125]]}}]})";
    std::filesystem::create_directories(dir / "out");
    const auto result = generate_city(load_sketch(dir / "in.geojson"), dir / "out", nullptr);
    const Validation v = validate_output(dir / "out");
    EXPECT_TRUE(v.ok()) << (v.problems.empty() ? "" : v.problems[0]);
    for (const char* zone : {"residential", "commercial"})
      EXPECT_LE(result.report["statistics"]["zones"][zone]["lots"]["share_without_building"].get<double>(), 0.2) << zone;
    return cli_util::read(dir / "out" / "vector" / "buildings.geojson") + cli_util::read(dir / "out" / "city.glb");
  };
  const std::string one = generate(1);
  EXPECT_NE(one.find("\"model\""), std::string::npos) << "no placed model";
  EXPECT_EQ(one, generate(2));
}

}  // namespace
}  // namespace exacity
