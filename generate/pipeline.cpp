#include "generate/pipeline.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>

#include "generate/parcels/blocks.h"
#include "generate/placement/building_settings.h"
#include "generate/placement/buildings.h"
#include "generate/placement/builtin_models.h"
#include "generate/export/cityjson_export.h"
#include "generate/export/clutter_layer.h"
#include "generate/errors.h"
#include "generate/export/gis_export.h"
#include "generate/export/gltf_export.h"
#include "generate/parcels/lots.h"
#include "generate/export/mesh_export.h"
#include "generate/placement/model_library.h"
#include "generate/layout/road_network.h"
#include "generate/export/statistics.h"
#include "generate/export/svg_map.h"
#include "generate/city/terrain.h"
#include "generate/export/validate.h"
#include "geom/kernel.h"
#include "generate/export/vector_layers.h"
#include "generate/city/city_map.h"
#include "geom/measure.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// Lots take their block's density (a grammar's).
std::vector<Lot> with_density(std::vector<Lot> lots, const std::vector<Block>& blocks) {
  for (Lot& lot : lots) lot.density = blocks[lot.block].density;
  return lots;
}

// Buildings on every lot. Lots no placer could build on are merged into a neighbour or,
// the last time, left open (merge_unbuilt_lots), and every lot is placed again, twice at
// most: with lot ids renumbered, every lot draws from its new stream.
Structures build_on_lots(City& city, const std::vector<PlannedLot>& planned) {
  constexpr int kMerges = 2;
  for (int merges = 0;; ++merges) {
    Structures s = place_buildings(city.lots, city.settings, city.model_library(), city.channels, city.heightmap());
    std::vector<char> built(city.lots.size(), 0);
    for (const Building& b : s.buildings) built[b.lot] = 1;
    for (const ModelInstance& m : s.models) built[m.lot] |= m.kind == ModelKind::Building;
    if (merges == kMerges || std::count(built.begin(), built.end(), 0) == 0) return s;
    city.lots = with_density(merge_unbuilt_lots(city.network.map, planned, city.lots, built, merges + 1 == kMerges,
                                                city.settings, city.unbuilt_lots),
                             city.blocks);
  }
}

}  // namespace

City build_city(const Sketch& sketch, StageClock& stages) {
  City city;
  city.settings = sketch;
  city.drawn = sketch;
  city.camera = sketch.camera;
  // The stage reads the sketch's images: the heightmap and the channels.
  city.terrain = stages.run("terrain", [&]() -> std::optional<Terrain> {
    city.channels = Channels::load(sketch.channels, sketch.channel_sharpness);
    if (!sketch.terrain) return std::nullopt;
    return Terrain::load(*sketch.terrain);
  });
  city.library = stages.run("model library", [&]() -> std::optional<ModelLibrary> {
    std::optional<ModelLibrary> library;
    if (!sketch.models.empty()) {
      library = load_model_library(sketch.models);
      library->check_channels(sketch.channels);
      // Nesting compares models slab by slab (docs/design.md, Placement: nesting).
      if (std::any_of(sketch.zone_settings.begin(), sketch.zone_settings.end(),
                      [](const auto& z) { return z.second.buildings.nesting; }))
        cut_slabs(*library);
    }
    check_lot_library(sketch, library ? &*library : nullptr);
    add_builtin_models(library, sketch.builtin_trees, sketch.builtin_lamps);
    return library;
  });
  CityMap city_map = stages.run("zone map", [&] { return build_city_map(city.settings, city.drawn, city.heightmap()); });
  city.network = stages.run("road network", [&] { return grow_road_network(std::move(city_map), city.settings, city.drawn.zones); });
  city.blocks = stages.run("blocks", [&] { return cut_blocks(city.network.map, city.settings, city.drawn.zones, city.network.uses); });
  std::vector<PlannedLot> planned;
  city.lots = stages.run("lots", [&] {
    planned = plan_lots(city.blocks, city.settings, city.model_library(), city.channels);
    return with_density(insert_lots(city.network.map, planned, city.settings), city.blocks);
  });
  Structures raised = stages.run("buildings", [&] {
    Structures s = build_on_lots(city, planned);
    check_export_size(s.models, city.model_library());
    return s;
  });
  city.buildings = std::move(raised.buildings);
  city.models = std::move(raised.models);
  stages.run("vector layers", [&] {
    merge_sliver_road_areas(city.network.map);
    city.ground = extract_ground(city.network.map, city.blocks, city.lots, city.drawn.zones);
    city.layers = layers_of(city.ground, city.buildings, city.models, city.model_library());
  });
  // After the ground, whose centre lines the clutter dresses and names (docs/design.md, Placement).
  city.clutter = stages.run("clutter", [&] {
    return place_clutter({city.network.map, city.ground, city.lots, city.buildings, city.models}, city.model_library(),
                         city.channels, city.settings, city.drawn.zones, city.heightmap());
  });
  return city;
}

GenerateResult generate_city(const Sketch& sketch, const fs::path& dir, const ProgressFn& progress) {
  StageClock stages(progress, kCityStages + kWriteStages);
  City city = build_city(sketch, stages);
  return write_city(sketch, city, dir, stages);
}

namespace {

// report.json's road_network: regions and levels grown, roads and segments per class,
// junctions per degree (1: a dead end at a region's edge), how the sketch's roads met.
ordered_json road_network_report(const RoadNetwork& network, const DrawnFeatures& sketch) {
  ordered_json segments = ordered_json::object(), roads_by_class = ordered_json::object();
  for (const MapRoad& r : network.map.roads) {
    std::string c(name(r.road_class));
    roads_by_class[c] = roads_by_class.value(c, 0) + 1;
    for (const auto& line : r.lines) segments[c] = segments.value(c, 0) + static_cast<int>(line.size()) - 1;
  }
  ordered_json junctions = ordered_json::object();
  for (auto [degree, count] : network.map.map.polyline_degrees())
    if (degree != 2) junctions[std::to_string(degree)] = count;
  ordered_json dead_ends = ordered_json::array();
  for (const DeadEnd& d : sketch.dead_ends) dead_ends.push_back({{"feature", d.feature}, {"at", {d.at.x, d.at.y}}});
  return {{"regions", network.stats.regions},
          {"levels", network.stats.levels},
          {"roads", roads_by_class},
          {"segments", segments},
          {"junctions_by_degree", junctions},
          {"cells_without_access", network.stats.cells_without_access},
          {"links", network.stats.links},
          {"dropped_roads", network.stats.dropped_roads},
          {"sketch_junctions", {{"mitred", network.map.mitred_junctions}, {"discs", network.map.disc_junctions}}},
          {"joined_ends", sketch.joined_ends},
          {"dead_ends", dead_ends}};
}

// Whether a drawn zone holds p as the sketch reads it: its outer ring winds around p and no
// hole does.
bool zone_holds(const ZoneFeature& zone, geom::Vec2 p) {
  for (const geom::Polygon& polygon : zone.polygons) {
    if (geom::winding_number(polygon.outer, p) == 0) continue;
    if (std::none_of(polygon.holes.begin(), polygon.holes.end(), [&](const geom::Ring& h) { return geom::winding_number(h, p) != 0; }))
      return true;
  }
  return false;
}

// The drawn zone a cell lies in (the later of two zones drawn over each other), or -1.
int zone_feature_of(const geom::Cell& cell, const DrawnFeatures& sketch) {
  const std::optional<geom::Vec2> p = cell.point_inside_near(cell.centroid());
  if (!p) return -1;
  for (int z = static_cast<int>(sketch.zones.size()) - 1; z >= 0; --z)
    if (zone_holds(sketch.zones[z], *p)) return z;
  return -1;
}

// report.json's empty_zones: each drawn residential, commercial or industrial zone that got
// no lot, and why, so a zone never stays empty without a word.
ordered_json empty_zones_report(const City& city) {
  const DrawnFeatures& sketch = city.drawn;
  std::vector<char> has_land(sketch.zones.size(), 0), has_lot(sketch.zones.size(), 0), has_street(sketch.zones.size(), 0);
  for (const FaceLabel& label : city.network.map.labels)
    if (label.cover == Cover::Zone && label.zone >= 0) has_land[label.zone] = 1;
  for (const Lot& lot : city.lots)
    if (const int z = zone_feature_of(lot.cell, sketch); z >= 0) has_lot[z] = 1;
  for (const Block& block : city.blocks)
    if (!block.green && !block.roads.empty())
      if (const int z = zone_feature_of(block.cell, sketch); z >= 0) has_street[z] = 1;
  ordered_json empty = ordered_json::array();
  for (std::size_t z = 0; z < sketch.zones.size(); ++z) {
    const ZoneFeature& zone = sketch.zones[z];
    if (has_lot[z] || !grows_roads(zone.type)) continue;
    ordered_json entry{{"feature", zone.index},
                       {"zone", name(zone.type)},
                       {"why", !has_land[z]    ? "no land of its own: zones drawn later, water or roads cover all of it"
                               : has_street[z] ? "its blocks along streets are too small or narrow for a lot"
                                               : "no street reaches its land: draw a road to it, or lay it out by growth"}};
    if (!zone.grid_cell.empty()) entry["grid_cell"] = zone.grid_cell;  // where a grid map's region begins
    if (!zone.source.empty()) entry["source"] = zone.source;  // a feature read from another format
    empty.push_back(std::move(entry));
  }
  return empty;
}

// report.json's placement_fallbacks: zone types whose lots ask for grid filling but whose
// lots are built with extruded footprints in rows, as the library has no building for them.
ordered_json placement_fallbacks_report(const City& city) {
  ordered_json fallbacks = ordered_json::array();
  for (const auto& [zone, settings] : city.settings.zone_settings) {
    // The default placer falls back without a word: extruded footprints are what it asks for then.
    if (settings.buildings.placement == &placer_types().front() || !grows_roads(zone)) continue;
    const ModelLibrary* library = city.model_library();
    if (library && !library->choices(zone, ModelKind::Building).empty()) continue;
    fallbacks.push_back({{"zone", name(zone)},
                         {"why", library && !library->file.empty() ? "the model library has no building for this zone type"
                                         : "the sketch names no model library (\"exacity\".models, or --models)"}});
  }
  return fallbacks;
}

// report.json's counts: features per layer, the map's size and the 3D exports'.
ordered_json counts_report(const City& city, const MeshCounts& mesh, const GltfCounts& gltf) {
  const CityLayers& layers = city.layers;
  int green = 0;
  for (const Block& b : city.blocks) green += b.green;
  auto counts = city.network.map.map.counts();
  // The buildings layer holds every structure: buildings, and models of other kinds (trees).
  ordered_json by_kind = ordered_json::object();
  for (const VectorFeature& f : layers.buildings.features) {
    const std::string kind = f.properties.value("kind", std::string("building"));
    by_kind[kind] = by_kind.value(kind, 0) + 1;
  }
  return {{"zones", layers.zones.features.size()},
          {"water", layers.water.features.size()},
          {"roads", layers.roads.features.size()},
          {"road_areas", layers.road_areas.features.size()},
          {"blocks", city.blocks.size() - green},
          {"green_spaces", green},
          {"lots", layers.lots.features.size()},
          {"buildings", layers.buildings.features.size()},
          {"buildings_by_kind", by_kind},
          {"clutter", city.clutter.items.size()},
          {"map", {{"vertices", counts.vertices}, {"edges", counts.edges}, {"faces", counts.faces}}},
          {"mesh", {{"vertices", mesh.vertices}, {"faces", mesh.faces}}},
          {"gltf", {{"meshes", gltf.meshes}, {"instances", gltf.instances}, {"triangles", gltf.triangles}}}};
}

// report.json's clutter: what stands by kind, and the spots that found no place by kind and
// why, so no spot is dropped without a word (docs/design.md, Placement).
ordered_json clutter_report(const ClutterTally& tally) {
  ordered_json placed = ordered_json::object(), missed = ordered_json::array();
  for (const auto& [kind, n] : tally.placed) placed[kind] = n;
  for (const auto& [key, n] : tally.missed) missed.push_back({{"kind", key.first}, {"why", key.second}, {"spots", n}});
  return {{"placed", placed}, {"not_placed", missed}};
}

// The vector layers, a copy of the sketch and the SVG map.
void export_vectors(const Sketch& sketch, const City& city, const fs::path& dir) {
  const CityLayers& layers = city.layers;
  fs::create_directories(dir / "vector");
  if (sketch.geojson.empty()) {
    fs::copy_file(sketch.path, dir / "sketch.geojson");
  } else {
    std::ofstream copy(dir / "sketch.geojson", std::ios::binary);
    copy << sketch.geojson;
    if (!copy) throw UserError((dir / "sketch.geojson").string() + ": write failed (disk full?)");
  }
  for (const Layer* l : {&layers.zones, &layers.water, &layers.roads, &layers.road_areas, &layers.blocks, &layers.lots,
                         &layers.buildings})
    write_geojson(*l, city.settings.crs, dir / "vector" / (l->name + ".geojson"));
  write_point_geojson(clutter_layer(city.clutter.items, city.model_library()), city.settings.crs,
                      dir / "vector" / "clutter.geojson");
  write_svg_map(city.ground, city.buildings, city.models, dir / "map.svg", city.clutter.items);
}

// CityJSON, glTF, OBJ and PLY, from one set of building meshes and one set of ground layers.
MeshCounts export_3d(const City& city, const fs::path& dir, GltfCounts& gltf) {
  const ModelLibrary* library = city.model_library();
  std::vector<Mesh> meshes = structure_meshes(city.buildings, city.models, library);
  const std::vector<GroundLayer> ground = ground_layers(city.ground, city.heightmap());
  write_cityjson(city.ground, city.buildings, city.models, meshes, library, city.heightmap(), ground, city.settings.crs,
                 dir / "city.city.json", city.clutter.items);
  std::vector<ModelInstance> clutter;
  for (const Clutter& c : city.clutter.items) clutter.push_back(c.instance);
  gltf = write_gltf(city.ground, ground, city.buildings, city.models, meshes, library, dir / "city.glb", clutter);
  return write_meshes(city.buildings, city.models, meshes, ground, dir / "city.obj", dir / "city.ply");
}

}  // namespace

GenerateResult write_city(const Sketch& sketch, const City& city, const fs::path& dir, StageClock& stages,
                          const ExportOptions& options) {
  const CitySettings& settings = city.settings;
  bool city_osm = false;
  stages.run("export", [&] {
    export_vectors(sketch, city, dir);
    write_vector_formats(dir, options.vector_formats, settings.crs);
    city_osm = write_city_osm(city, dir / "city.osm");
  });
  GltfCounts gltf;
  MeshCounts mesh = stages.run("3d export", [&] { return export_3d(city, dir, gltf); });
  const bool validated = geom::kernel_validates_its_output();
  Validation validation;
  if (validated) validation = stages.run("validation", [&] { return validate_output(dir); });
  ordered_json report{
      {"generator", "exacity"},
      {"version", kVersion},
      {"kernel", geom::kernel_name()},
      {"sketch", settings.path.filename().string()},
      // Where the sketch's relative paths (heightmap, models) resolve, for `exacity render`.
      {"sketch_path", fs::absolute(settings.path).lexically_normal().string()},
      {"seed", settings.seed},
      {"counts", counts_report(city, mesh, gltf)},
      {"exports",
       {{"vector_formats", options.vector_formats.empty() ? std::vector<std::string>{"geojson"} : options.vector_formats},
        {"city_osm", city_osm ? "city.osm" : "not written: the sketch has no CRS (EPSG) to place it on Earth"}}},
      {"road_network", road_network_report(city.network, city.drawn)},
      {"unbuilt_lots", {{"merged", city.unbuilt_lots.merged}, {"left_open", city.unbuilt_lots.left_open}}},
      {"empty_zones", empty_zones_report(city)},
      {"placement_fallbacks", placement_fallbacks_report(city)},
      {"clutter", clutter_report(city.clutter.tally)},
      {"statistics", city_statistics(city.layers, &settings, &city.drawn)},
      {"validation",
       validated ? ordered_json{{"ok", validation.ok()}, {"problems", validation.problems},
                                {"widest_sliver_m", validation.widest_sliver}}
                 : ordered_json{{"skipped", std::string("this build's kernel (") + geom::kernel_name() +
                                                ") cannot check its own output: run the exact build's exacity validate"}}},
      {"timings_s", stages.seconds},
  };
  std::ofstream out(dir / "report.json", std::ios::binary);
  out << report.dump(2) << "\n";
  if (!out) throw UserError((dir / "report.json").string() + ": write failed (disk full?)");
  return {report, validation.ok()};
}

}  // namespace exacity
