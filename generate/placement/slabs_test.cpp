// Nesting's 3D occupancy grid made exact: models cut into slabs at their undersides, and
// grid filling with nesting, which lets a small model stand under an arch's beam only
// where no two models' slabs meet.
#include "generate/placement/building_settings.h"
#include "generate/placement/slabs.h"

#include <gtest/gtest.h>

#include "generate/placement/grid_filling.h"
#include "generate/placement/model_library.h"
#include "generate/placement/model_placement.h"
#include "geom/measure.h"
#include "geom/polygon_check.h"
#include "tests/test_util.h"

namespace exacity {
namespace {

using geom::Vec2;

// A closed box from (x0, y0, z0) to (x1, y1, z1), its triangles counter-clockwise seen from
// outside; `caps` false leaves its top and underside open (walls only).
void add_box(TriangleMesh& mesh, double x0, double y0, double z0, double x1, double y1, double z1, bool caps = true) {
  const int o = static_cast<int>(mesh.vertices.size());
  for (int k = 0; k < 8; ++k) mesh.vertices.push_back({k & 1 ? x1 : x0, k & 2 ? y1 : y0, k & 4 ? z1 : z0});
  auto quad = [&](int a, int b, int c, int d) {
    mesh.triangles.push_back({o + a, o + b, o + c});
    mesh.triangles.push_back({o + a, o + c, o + d});
  };
  if (caps) quad(0, 2, 3, 1), quad(4, 5, 7, 6);                            // underside, top
  quad(0, 1, 5, 4), quad(3, 2, 6, 7), quad(2, 0, 4, 6), quad(1, 3, 7, 5);  // -y, +y, -x, +x
  mesh.material.assign(mesh.triangles.size(), 0);
  mesh.materials.resize(1);
}

Model make_model(const std::string& name, TriangleMesh mesh) {
  Model m = normalise_model(std::move(mesh), "z", "-y", 1, name);
  m.name = name;
  m.min_scale = m.max_scale = 1;
  m.zones = {ZoneType::Commercial};
  m.slabs = model_slabs(m.mesh, m.outline, m.height);
  return m;
}

// A beam 20 m by 8 m from 7 m to 10 m on two pillars 3 m wide: 7 m clear under it.
Model arch(bool pillar_caps = true) {
  TriangleMesh mesh;
  add_box(mesh, -10, -4, 0, -7, 4, 7, pillar_caps);
  add_box(mesh, 7, -4, 0, 10, 4, 7, pillar_caps);
  add_box(mesh, -10, -4, 7, 10, 4, 10);
  return make_model("arch", std::move(mesh));
}

Model kiosk(double height) {
  TriangleMesh mesh;
  add_box(mesh, -1.5, -1.5, 0, 1.5, 1.5, height);
  return make_model("kiosk", std::move(mesh));
}

double total_area(const std::vector<geom::Ring>& rings) {
  double a = 0;
  for (const geom::Ring& r : rings) a += geom::signed_area(r);
  return a;
}

TEST(Slabs, AnArchIsItsPillarsUnderItsBeam) {
  for (bool caps : {true, false}) {
    const Model m = arch(caps);
    ASSERT_EQ(m.slabs.size(), 2u) << "caps " << caps;
    EXPECT_EQ(m.slabs[0].bottom, 0);
    EXPECT_EQ(m.slabs[0].top, 7);
    EXPECT_EQ(m.slabs[1].top, 10);
    // The pillars' walls enclose them whether or not they are capped.
    ASSERT_EQ(m.slabs[0].outline.size(), 2u) << "caps " << caps;
    EXPECT_EQ(total_area(m.slabs[0].outline), 2 * 3 * 8);
    for (const geom::Ring& r : m.slabs[0].outline)
      for (Vec2 v : r) EXPECT_GE(std::abs(v.x), 7) << "a pillar's corner lies under the open middle";
    ASSERT_EQ(m.slabs[1].outline.size(), 1u);
    EXPECT_EQ(total_area(m.slabs[1].outline), 20 * 8);
  }
}

TEST(Slabs, AModelWithoutUndersidesIsOneSlabOfItsOutline) {
  const Model m = kiosk(2.5);
  ASSERT_EQ(m.slabs.size(), 1u);
  EXPECT_EQ(m.slabs[0].top, 2.5);
  EXPECT_EQ(m.slabs[0].outline, std::vector<geom::Ring>{m.outline});
}

TEST(Slabs, ATOnAPillarLeavesRoomAroundThePillar) {
  TriangleMesh mesh;
  add_box(mesh, -2, -2, 0, 2, 2, 6);
  add_box(mesh, -8, -5, 6, 8, 5, 9);
  const Model m = make_model("tee", std::move(mesh));
  ASSERT_EQ(m.slabs.size(), 2u);
  EXPECT_EQ(total_area(m.slabs[0].outline), 16);
  EXPECT_EQ(total_area(m.slabs[1].outline), 160);
}

// The arch and a kiosk placed at `at` on floors: their slabs meet or not, exactly.
bool meet(const Model& a, const Model& k, Vec2 at, double kiosk_floor = 0) {
  const Placement pa{0, {0, 0}, 0, 1, 0}, pk{1, at, 0, 1, 0};
  return slabs_meet(placed_slabs(a, pa, placed_outline(a, pa)), 0, placed_slabs(k, pk, placed_outline(k, pk)),
                    kiosk_floor);
}

TEST(Slabs, AKioskUnderTheBeamMeetsItOnlyWhenItReachesTheUnderside) {
  const Model a = arch();
  EXPECT_FALSE(meet(a, kiosk(2.5), {0, 0}));
  EXPECT_FALSE(meet(a, kiosk(6.999), {0, 0}));
  EXPECT_TRUE(meet(a, kiosk(7), {0, 0})) << "touching the underside is not apart";
  EXPECT_TRUE(meet(a, kiosk(8), {0, 0}));
  EXPECT_TRUE(meet(a, kiosk(2.5), {-6, 0})) << "into a pillar";
  EXPECT_FALSE(meet(a, kiosk(2.5), {-5.4, 0})) << "clear of the pillar";
  EXPECT_TRUE(meet(a, kiosk(2.5), {0, 0}, 4.5)) << "on higher ground, up into the beam";
  EXPECT_FALSE(meet(a, kiosk(2.5), {0, 0}, 4.4));
}

TEST(Slabs, OccupancyLetsAModelStandUnderAnotherOnlyWhereTheirSlabsAreApart) {
  const geom::Cell lot = testing_util::fronted_cell({{-20, -20}, {20, -20}, {20, 20}, {-20, 20}}, {0});
  const Model a = arch(), low = kiosk(2.5), high = kiosk(7.5);
  auto place = [](const Model& m, Vec2 at) {
    const Placement p{0, at, 0, 1, 0};
    const geom::Ring ring = placed_outline(m, p);
    return std::pair{ring, placed_slabs(m, p, ring)};
  };
  Occupancy occupancy(lot, LotEdge::kStreet);
  const auto [arch_ring, arch_slabs] = place(a, {0, 0});
  ASSERT_TRUE(occupancy.take(arch_ring, &arch_slabs));
  const auto [high_ring, high_slabs] = place(high, {0, 0});
  EXPECT_FALSE(occupancy.free(high_ring, &high_slabs)) << "up into the beam";
  const auto [low_ring, low_slabs] = place(low, {0, 0});
  EXPECT_FALSE(occupancy.free(low_ring)) << "without its slabs, a footprint needs the plan to itself";
  EXPECT_TRUE(occupancy.take(low_ring, &low_slabs)) << "under the beam";
  const auto [next_ring, next_slabs] = place(low, {1, 0});
  EXPECT_FALSE(occupancy.free(next_ring, &next_slabs)) << "into the kiosk already there";
  const auto [pillar_ring, pillar_slabs] = place(low, {-8, 0});
  EXPECT_FALSE(occupancy.free(pillar_ring, &pillar_slabs)) << "into a pillar";
}

// A lot 48 m along its street (south) and 30 m deep, filled with arches and kiosks.
std::vector<ModelInstance> fill_arches(bool nesting, std::uint64_t seed) {
  const geom::Cell lot = testing_util::fronted_cell({{0, 0}, {48, 0}, {48, 30}, {0, 30}}, {0});
  ModelLibrary lib;
  lib.models = {arch(), kiosk(2.5)};
  lib.models[1].weight = 4;
  BuildingSettings p;
  p.setback = 1, p.building_gap = 1;
  const Channels none;
  const auto filler = make_grid_filler(lib, ZoneType::Commercial, none, {.cell = 1, .nesting = nesting});
  Occupancy occupancy(lot, LotEdge::kStreet);
  Random rng(seed);
  Structures out;
  filler->place(Lot{}, p, occupancy, rng, out);
  for (const ModelInstance& m : out.models) EXPECT_TRUE(lot.holds(m.polygon.outer));
  return out.models;
}

// Whether the kiosk's footprint lies under the arch's, in plan.
int kiosks_under_arches(const std::vector<ModelInstance>& placed) {
  int under = 0;
  for (const ModelInstance& a : placed)
    for (const ModelInstance& k : placed)
      under += a.placed.model == 0 && k.placed.model == 1 && geom::rings_meet(a.polygon.outer, k.polygon.outer);
  return under;
}

TEST(GridNesting, KiosksStandUnderTheArchesOnlyWithNesting) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const std::vector<ModelInstance> nested = fill_arches(true, seed), flat = fill_arches(false, seed);
    EXPECT_GT(kiosks_under_arches(nested), 0) << "seed " << seed;
    EXPECT_EQ(kiosks_under_arches(flat), 0) << "seed " << seed;
    for (const ModelInstance& m : flat) EXPECT_TRUE(m.slabs.empty());
    int arches = 0;
    for (const ModelInstance& m : nested) arches += m.placed.model == 0;
    EXPECT_GT(arches, 0);
  }
}

TEST(GridNesting, NoTwoModelsMeetIn3D) {
  for (std::uint64_t seed : {1, 2, 3, 4, 5}) {
    const std::vector<ModelInstance> placed = fill_arches(true, seed);
    ASSERT_GT(placed.size(), 3u);
    for (std::size_t a = 0; a < placed.size(); ++a) {
      ASSERT_FALSE(placed[a].slabs.empty());
      EXPECT_EQ(placed[a].slabs.back().top, placed[a].height);
      for (std::size_t b = a + 1; b < placed.size(); ++b)
        EXPECT_FALSE(slabs_meet(placed[a].slabs, 0, placed[b].slabs, 0))
            << "seed " << seed << ": " << a << " and " << b;
    }
    // Two kiosks never share the plan; only a kiosk and an arch do.
    for (std::size_t a = 0; a < placed.size(); ++a)
      for (std::size_t b = a + 1; b < placed.size(); ++b)
        if (placed[a].placed.model == placed[b].placed.model) {
          EXPECT_FALSE(geom::rings_meet(placed[a].polygon.outer, placed[b].polygon.outer));
        }
  }
}

TEST(GridNesting, TheSameStreamNestsTheSameWay) {
  const std::vector<ModelInstance> one = fill_arches(true, 7), two = fill_arches(true, 7);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) EXPECT_EQ(one[k].polygon.outer, two[k].polygon.outer);
}

}  // namespace
}  // namespace exacity
