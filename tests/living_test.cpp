// A living city (docs/design.md, Placement: built-in models; Rendering: facades and roofs):
// Exacity's own trees and lamps where a sketch has no library, placed only where clutter and
// lot trees may stand and checked by validate; the sketch's "builtin_models" choosing them;
// a library's own trees taking their place; the renderer's facades (windows in rows per
// storey over a commercial shop floor) and a park's trees seen in the id layer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "generate/city/palette.h"
#include "generate/errors.h"
#include "generate/export/validate.h"
#include "generate/pipeline.h"
#include "generate/placement/builtin_models.h"
#include "geom/measure.h"
#include "geom/polygon_check.h"
#include "render/facade.h"
#include "render/paving.h"
#include "render/scene.h"
#include "render/sky.h"
#include "tests/test_util.h"

using namespace exacity;

namespace {

// A residential quarter with a park in it and a commercial strip, grown by growth.
std::string sketch_text(const std::string& builtin) {
  return R"({"type": "FeatureCollection", "exacity": {"seed": 5)" + builtin + R"(}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [360, 0], [360, 300], [0, 300], [0, 0]]]}},
    {"type": "Feature", "properties": {"zone": "park"},
     "geometry": {"type": "Polygon", "coordinates": [[[120, 100], [220, 100], [220, 190], [120, 190], [120, 100]]]}},
    {"type": "Feature", "properties": {"zone": "commercial"},
     "geometry": {"type": "Polygon", "coordinates": [[[360, 0], [520, 0], [520, 300], [360, 300], [360, 0]]]}}]})";
}

Sketch living_sketch(const std::string& builtin) {
  Sketch sketch = parse_sketch(sketch_text(builtin), "living.geojson");
  sketch.geojson = sketch_text(builtin);  // what write_city copies, there being no file
  return sketch;
}

City built(const std::string& builtin) {
  StageClock clock(nullptr, kCityStages);
  return build_city(living_sketch(builtin), clock, {}, ExactWork::Kept);  // the checks read the map and lots
}

struct Counts {
  int street_trees = 0, park_trees = 0, lamps = 0, lot_trees = 0;
};

Counts count(const City& city) {
  Counts c;
  for (const Clutter& k : city.clutter.items) {
    if (k.instance.kind == ModelKind::Lamp) ++c.lamps;
    if (k.instance.kind == ModelKind::Tree) ++(k.road < 0 ? c.park_trees : c.street_trees);
  }
  for (const ModelInstance& m : city.models) c.lot_trees += m.kind == ModelKind::Tree;
  return c;
}

bool in_park(const City& city, geom::Vec2 p) {
  const int label = city.network.map.map.label_at(p);
  if (label < 0) return false;
  const FaceLabel& l = city.network.map.labels[label];
  return l.cover == Cover::Zone && l.zone >= 0 && city.drawn.zones[l.zone].type == ZoneType::Park;
}

}  // namespace

TEST(BuiltinModels, MeshesAreClosedAndStandOnTheGround) {
  for (const TriangleMesh& mesh : {broadleaf_mesh(), conifer_mesh(), lamp_mesh()}) {
    // Closed: every directed edge has its reverse once.
    std::map<std::pair<int, int>, int> edges;
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    for (const auto& [e, n] : edges) {
      const auto back = edges.find({e.second, e.first});
      EXPECT_EQ(back == edges.end() ? 0 : back->second, n);
    }
    double low = INFINITY;
    for (const Vec3& v : mesh.vertices) low = std::min(low, v[2]);
    EXPECT_EQ(low, 0);
    EXPECT_EQ(mesh.material.size(), mesh.triangles.size());
  }
}

TEST(BuiltinModels, TreesAndLampsStandWhereTheyMayAndTheCityValidates) {
  const City city = built("");
  const Counts c = count(city);
  EXPECT_GT(c.street_trees, 0);
  EXPECT_GT(c.park_trees, 5);
  EXPECT_GT(c.lamps, 10);
  EXPECT_GT(c.lot_trees, 10);
  ASSERT_TRUE(city.library);
  EXPECT_TRUE(city.library->file.empty());
  for (const Clutter& k : city.clutter.items) {
    const int label = city.network.map.map.label_at(k.spot);
    ASSERT_GE(label, 0);
    const FaceLabel& l = city.network.map.labels[label];
    if (k.road < 0) {
      // A park's tree: on the park's open land, its trunk too.
      EXPECT_EQ(k.instance.kind, ModelKind::Tree);
      EXPECT_TRUE(in_park(city, k.spot)) << k.instance.id;
      for (geom::Vec2 p : k.instance.polygon.outer) EXPECT_TRUE(in_park(city, p)) << k.instance.id;
      continue;
    }
    // A street's: on a sidewalk or in a lot, never on a carriageway; trees on residential streets only.
    EXPECT_TRUE((l.cover == Cover::Road && l.surface == RoadSurface::Sidewalk) || k.instance.lot >= 0) << k.instance.id;
    if (k.instance.kind == ModelKind::Tree) {
      EXPECT_EQ(k.instance.zone, ZoneType::Residential) << k.instance.id;
    }
  }
  // Garden trees: in residential lots, apart from every building.
  for (const ModelInstance& m : city.models) {
    if (m.kind != ModelKind::Tree) continue;
    EXPECT_EQ(m.zone, ZoneType::Residential);
    EXPECT_TRUE(city.lots[m.lot].cell.holds(m.polygon.outer));
    for (const Building& b : city.buildings) EXPECT_FALSE(geom::rings_meet(b.polygon.outer, m.polygon.outer));
  }
  // Every output, and validate's check of the clutter layer (park trees name no road).
  const auto dir = testing_util::temp_dir("living-outputs");
  StageClock clock(nullptr, kWriteStages);
  const GenerateResult result = write_city(living_sketch(""), city, dir, clock);
  EXPECT_TRUE(result.valid) << result.report["validation"].dump();
}

TEST(BuiltinModels, TheSketchChoosesWhichAndCountsFollow) {
  const Counts both = count(built(""));
  const Counts none = count(built(R"(, "builtin_models": [])"));
  const Counts trees = count(built(R"(, "builtin_models": ["tree"])"));
  const Counts lamps = count(built(R"(, "builtin_models": ["lamp"])"));
  EXPECT_EQ(none.street_trees + none.park_trees + none.lamps + none.lot_trees, 0);
  EXPECT_EQ(trees.lamps, 0);
  EXPECT_EQ(lamps.street_trees + lamps.park_trees + lamps.lot_trees, 0);
  EXPECT_GT(trees.park_trees, 0);
  EXPECT_GT(lamps.lamps, 0);
  // Lot trees stand before any clutter, park trees apart from streets; along a street lamps
  // and trees take spots from each other, so each alone has as many or more.
  EXPECT_EQ(trees.park_trees, both.park_trees);
  EXPECT_EQ(trees.lot_trees, both.lot_trees);
  EXPECT_GE(trees.street_trees, both.street_trees);
  EXPECT_GE(lamps.lamps, both.lamps);
  // With nothing built in, there is no library, as before.
  EXPECT_FALSE(built(R"(, "builtin_models": [])").library);
}

TEST(BuiltinModels, BadValuesAreOneLine) {
  for (const std::string bad : {R"("yes")", R"(true)", R"(["tree", "bush"])", R"(["lamp", "lamp"])", R"([3])"}) {
    try {
      parse_sketch(sketch_text(R"(, "builtin_models": )" + bad), "living.geojson");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const UserError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("living.geojson: \"exacity\".builtin_models: "), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(BuiltinModels, ALibrarysOwnTreesAndLampsTakeTheirPlace) {
  std::optional<ModelLibrary> library =
      load_model_library(std::filesystem::path(EXACITY_SOURCE_DIR) / "examples/models/library.json");
  const std::size_t before = library->models.size();
  Sketch sketch = parse_sketch(sketch_text(""), "living.geojson");
  add_builtin_models(library, sketch.builtin_trees, sketch.builtin_lamps);
  EXPECT_EQ(library->models.size(), before);  // it has a tree and a lamp
  std::optional<ModelLibrary> none;
  add_builtin_models(none, sketch.builtin_trees, sketch.builtin_lamps);
  ASSERT_TRUE(none);
  EXPECT_EQ(none->models.size(), 3u);
}

TEST(Facade, WindowsSitInRowsPerStoreyOverAShopFloor) {
  const render::FacadeStyle s = render::facade_style(ZoneType::Commercial, 5, 17, 10, 40);
  ASSERT_TRUE(s.shopfront);
  // Shop windows on the ground floor, none at the fascia above them, nor below ground.
  const float bay_centre = s.phase + s.bay * 0.5f;
  EXPECT_TRUE(render::in_window(s, s.phase + s.bay, 12));
  EXPECT_FALSE(render::in_window(s, s.phase + s.bay, 14.2f));
  EXPECT_FALSE(render::in_window(s, bay_centre, 9));
  // Above: each storey's window at the middle of its bay, wall between storeys and bays.
  for (int storey = 0; storey < 5; ++storey) {
    const float bottom = 14.5f + s.storey * storey;
    EXPECT_TRUE(render::in_window(s, bay_centre, bottom + s.storey * (s.sill + s.head) / 2)) << storey;
    EXPECT_FALSE(render::in_window(s, bay_centre, bottom + s.storey * s.sill * 0.5f)) << storey;
    EXPECT_FALSE(render::in_window(s, s.phase + 0.01f, bottom + s.storey * (s.sill + s.head) / 2)) << storey;
  }
  // None under the eaves' last 40 cm.
  EXPECT_FALSE(render::in_window(s, bay_centre, 39.8f));
}

// At night the light of a facade's lit windows, spread evenly over its wall for the rays a
// diffuse surface scatters (render/facade.h), is the windows' own light on average over
// the wall, storeys and shop floor apart: the same light leaves the wall, without the grain
// of bright dots that rays finding a pane now and then made on the street opposite.
TEST(Facade, LitWindowsLightSpreadOverTheWallIsTheirsOnAverage) {
  for (const ZoneType zone : {ZoneType::Residential, ZoneType::Commercial}) {
    render::FacadeStyle s = render::facade_style(zone, 5, 17, 0, 1000);
    s.lit = 1, s.light = {0.02f, 0.02f, 0.02f};
    const render::V3 normal{0, -1, 0};  // a wall along x, facing south
    // Its storeys over the shop floor, and the shop floor, each sampled on a fine grid
    // over 1,200 panes (20 storeys of 60 bays; 1,200 shop windows), to average their
    // brightness and colour.
    const float shops = s.shopfront ? 4.5f : 0;
    for (const auto& [bottom, top] : {std::pair{shops, shops + 20 * s.storey}, std::pair{0.0f, shops}}) {
      if (top <= bottom) continue;
      double windows[3] = {0, 0, 0}, spread[3] = {0, 0, 0};
      const float length = (bottom < shops ? 2400 : 60) * s.bay;
      for (float x = 0.01f; x < length; x += 0.071f)
        for (float z = bottom + 0.013f; z < top; z += 0.053f) {
          const render::V3 p{x, 0, z};
          const render::V3 pane = render::facade_material(s, render::Material{}, p, normal).emission,
                           wall = render::spread_window_light(s, p, normal);
          for (int c = 0; c < 3; ++c) windows[c] += pane[c], spread[c] += wall[c];
        }
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(spread[c], windows[c], 0.03 * windows[c]) << static_cast<int>(zone) << " from " << bottom << " m, channel " << c;
    }
    // None by day, on a roof, or under the floor.
    s.lit = 0;
    EXPECT_EQ(render::spread_window_light(s, {1, 0, 5}, normal).x, 0);
    s.lit = 1;
    EXPECT_EQ(render::spread_window_light(s, {1, 0, 5}, {0, 0, 1}).x, 0);
    EXPECT_EQ(render::spread_window_light(s, {1, 0, -1}, normal).x, 0);
  }
}

// Towers of one zone differ: some nearly all glass (a curtain wall), some punched windows
// in stone; walls between windows carry a band at each floor's slab. Before, every
// office had punched windows, glazing 0.33 to 0.5 of its wall, and walls were one plaster.
TEST(Facade, TowersOfAZoneDifferAndFloorsShowBands) {
  float least = 1, most = 0;
  for (int id = 0; id < 40; ++id) {
    const render::FacadeStyle s = render::facade_style(ZoneType::Commercial, 7, id, 0, 60);
    int glass = 0, points = 0;
    for (float z = 10; z < 50; z += 0.37f)
      for (float along = 0; along < 30; along += 0.23f) glass += render::in_window(s, along, z), ++points;
    const float share = static_cast<float>(glass) / static_cast<float>(points);
    least = std::min(least, share), most = std::max(most, share);
  }
  EXPECT_GT(most, 0.7f);
  EXPECT_LT(least, 0.4f);
  // A wall's albedo at each slab (the band) against mid-storey, beside the windows, on the
  // residential buildings that have bands: darker or lighter by more than the plaster's
  // noise.
  int banded = 0;
  const render::Material wall{render::Material::Diffuse, {0.5f, 0.5f, 0.5f}};
  const render::V3 south{0, -1, 0};
  for (int id = 0; id < 40; ++id) {
    const render::FacadeStyle s = render::facade_style(ZoneType::Residential, 7, id, 0, 30);
    double slab = 0, middle = 0;
    for (int storey = 1; storey < 6; ++storey)
      for (float along = 0; along < 20; along += 0.5f) {
        const float z = s.storey * static_cast<float>(storey), mid = z + 0.12f - s.storey * 0.5f;
        if (render::in_window(s, along, mid)) continue;
        slab += render::facade_material(s, wall, {along, 0, z + 0.12f}, south).albedo.y;
        middle += render::facade_material(s, wall, {along, 0, mid}, south).albedo.y;
      }
    banded += std::abs(slab / middle - 1) > 0.12;
  }
  EXPECT_GT(banded, 10);
  // Asphalt and paving albedos within field measurements of pavements in service
  // (docs/design.md, Rendering: facades and roofs).
  auto grey = [](const Albedo& a) { return 0.2126 * a[0] + 0.7152 * a[1] + 0.0722 * a[2]; };
  EXPECT_GE(grey(kAsphaltAlbedo), 0.10);
  EXPECT_LE(grey(kAsphaltAlbedo), 0.18);
  EXPECT_GE(grey(kSidewalkAlbedo), 0.25);
  EXPECT_LE(grey(kSidewalkAlbedo), 0.35);
}

TEST(Facade, RenderedWallsHaveDarkWindowRowsAtTheirStoreysAndParkTreesAreSeen) {
  const City city = built("");
  render::Sky sky(200, 40);
  render::RenderScene scene(city, sky.sun_direction(), render::SceneOptions{});
  // The tallest commercial building with punched windows (a curtain wall's spandrels are
  // glass too): its longest wall, scanned by rays at it from 0.3 m out.
  const Building* tall = nullptr;
  for (const Building& b : city.buildings)
    if (b.zone == ZoneType::Commercial && (!tall || b.eaves > tall->eaves) &&
        render::facade_style(b.zone, city.settings.seed, b.stable_id, 0, 1).kind == render::FacadeKind::Punched)
      tall = &b;
  ASSERT_TRUE(tall);
  ASSERT_GT(tall->eaves, 9);
  const geom::Ring& r = tall->polygon.outer;
  std::size_t e = 0;
  for (std::size_t i = 0; i < r.size(); ++i)
    if (geom::distance(r[i], r[(i + 1) % r.size()]) > geom::distance(r[e], r[(e + 1) % r.size()])) e = i;
  const geom::Vec2 a = r[e], b = r[(e + 1) % r.size()];
  const geom::Vec2 u = geom::unit_along(a, b), out{u.y, -u.x};  // counter-clockwise: outside on the right
  const double length = geom::distance(a, b);
  // Per height (5 cm steps), whether any point along the wall is glass (dark), and the mean
  // albedo of wall points.
  std::vector<int> dark_rows;
  double wall = 0, glass = 0;
  int walls = 0, glasses = 0;
  for (int k = 0; k * 0.05 < tall->eaves; ++k) {
    const double z = tall->floor + k * 0.05 + 0.025;
    bool dark = false;
    for (double t = 0.5; t < length - 0.5; t += 0.1) {
      const geom::Vec2 p = a + u * t + out * 0.3;
      render::Surface hit;
      if (!scene.intersect(scene.to_scene(p.x, p.y, z), {static_cast<float>(-out.x), static_cast<float>(-out.y), 0}, 1,
                           hit) ||
          hit.entity != render::entity_id(render::Entity::Building, static_cast<std::size_t>(tall->id)))
        continue;
      const float lum = (hit.material.albedo.x + hit.material.albedo.y + hit.material.albedo.z) / 3;
      if (hit.material.kind == render::Material::Glossy)
        dark = true, glass += lum, ++glasses;
      else
        wall += lum, ++walls;
    }
    if (dark) dark_rows.push_back(k);
  }
  ASSERT_GT(glasses, 0);
  ASSERT_GT(walls, 0);
  EXPECT_LT(glass / glasses, 0.5 * wall / walls);
  // Bands of dark rows: the shop floor's, then one per storey, evenly spaced.
  std::vector<std::pair<int, int>> bands;
  for (int k : dark_rows)
    if (bands.empty() || k > bands.back().second + 1)
      bands.push_back({k, k});
    else
      bands.back().second = k;
  ASSERT_GE(bands.size(), 2u);
  EXPECT_GT((bands[0].second - bands[0].first) * 0.05, 2.5);  // shop windows, 3 m tall
  EXPECT_LT(bands[0].first * 0.05, 0.5);
  // The first storey's windows start above the 4.5 m shop floor; storeys follow at one height.
  EXPECT_GT(bands[1].first * 0.05, 4.5);
  for (std::size_t i = 2; i < bands.size(); ++i) {
    const double step = (bands[i].first - bands[i - 1].first) * 0.05;
    EXPECT_NEAR(step, (bands[2].first - bands[1].first) * 0.05, 0.11) << i;
    EXPECT_GE(step, 3.3);
    EXPECT_LE(step, 4.3);
  }
  // From above, over the park: the id layer names a park tree.
  bool seen = false;
  for (const Clutter& k : city.clutter.items) {
    if (k.road >= 0) continue;
    render::Surface hit;
    if (scene.intersect(scene.to_scene(k.spot.x, k.spot.y, 200), {0, 0, -1}, INFINITY, hit))
      seen |= hit.entity == render::entity_id(render::Entity::Clutter, static_cast<std::size_t>(k.instance.id));
  }
  EXPECT_TRUE(seen);
}

TEST(Paving, SlabsHaveDarkerJointsAndShadesOfTheirOwn) {
  const render::Material grey{render::Material::Diffuse, {0.4f, 0.4f, 0.4f}};
  // Slab centres, and joints beside them, 0.6 m apart.
  std::set<float> shades;
  for (int i = 0; i < 20; ++i) {
    const float x = 0.6f * static_cast<float>(i);
    const float centre = render::paving_material(grey, {x + 0.3f, 0.3f, 0}).albedo.x;
    const float joint = render::paving_material(grey, {x + 0.01f, 0.3f, 0}).albedo.x;
    EXPECT_LT(joint, 0.8f * centre) << i;
    shades.insert(centre);
  }
  EXPECT_GT(shades.size(), 10u);
}
