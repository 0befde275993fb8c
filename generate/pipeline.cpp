#include "generate/pipeline.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "generate/cancellable_invoke.h"
#include "generate/city_report.h"
#include "generate/parcels/blocks.h"
#include "generate/placement/buildings.h"
#include "generate/placement/builtin_models.h"
#include "generate/placement/mapped_buildings.h"
#include "generate/export/cityjson_export.h"
#include "generate/export/clutter_layer.h"
#include "generate/errors.h"
#include "generate/export/gis_export.h"
#include "generate/gis/projection.h"
#include "generate/export/gltf_export.h"
#include "generate/parcels/lots.h"
#include "generate/export/mesh_export.h"
#include "generate/placement/model_library.h"
#include "generate/layout/road_network.h"
#include "generate/export/svg_map.h"
#include "generate/city/terrain.h"
#include "generate/export/validate.h"
#include "generate/export/validate_window.h"
#include "generate/regenerate.h"
#include "geom/kernel.h"
#include "generate/export/vector_layers.h"
#include "generate/city/city_map.h"

// tcmalloc's C interface, weak so that a build without tcmalloc (the sanitizers') links.
extern "C" void MallocExtension_ReleaseFreeMemory() __attribute__((weak));

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

double peak_resident_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

namespace {

// Gives the pages of what was just freed back to the system (tcmalloc keeps them, and the
// exact map's small blocks are not pages the exports' large buffers can reuse); none
// without tcmalloc.
void release_freed_memory() {
  if (MallocExtension_ReleaseFreeMemory) MallocExtension_ReleaseFreeMemory();
}

// Lots take their block's density (a grammar's).
std::vector<Lot> with_density(std::vector<Lot> lots, const std::vector<Block>& blocks) {
  for (Lot& lot : lots) lot.density = blocks[lot.block].density;
  return lots;
}

// Buildings on every lot. Lots no placer could build on are merged into a neighbour or,
// the last time, left open (CityLots::merge_unbuilt_lots), and every lot is placed again,
// twice at most: with lot ids renumbered, every lot draws from its new stream.
// Lots a mapped building stands on (`held`, as the lots end) count as built; only where their
// zone sets lot_coverage are they built on, around the mapped footprints (place_buildings).
Structures build_on_lots(City& city, CityLots& lots, const std::vector<Building>& mapped, HeldLots& held) {
  constexpr int kMerges = 2;
  for (int merges = 0;; ++merges) {
    held = lots_holding(city.lots, mapped);
    Structures s = place_buildings(city.lots, city.settings, city.model_library(), city.channels, city.heightmap(),
                                   city.regions ? &city.regions->placements : nullptr, &held);
    std::vector<char> built(city.lots.size(), 0);
    for (const Building& b : s.buildings) built[b.lot] = 1;
    for (const ModelInstance& m : s.models) built[m.lot] |= m.kind == ModelKind::Building;
    city.mapped.held_lots = city.mapped.held_lots_built_on = 0;
    for (std::size_t i = 0; i < built.size(); ++i) {
      city.mapped.held_lots += held.held[i];
      city.mapped.held_lots_built_on += held.held[i] && built[i];
      built[i] |= held.held[i];
    }
    city.held_lots = held.held;
    city.held_m2 = held.standing_m2;
    if (merges == kMerges || std::count(built.begin(), built.end(), 0) == 0) return s;
    lots.merge_unbuilt_lots(built, merges + 1 == kMerges);
    city.unbuilt_lots = lots.unbuilt();
    city.lots = with_density(lots.lots(), city.blocks);
  }
}

}  // namespace

City build_city(const Sketch& sketch, StageClock& stages, std::shared_ptr<RegionCache> cache, ExactWork exact) {
  City city;
  if (cache) cache->next_build(sketch);
  city.regions = std::move(cache);
  RegionCache* const regions = city.regions.get();
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
                      [](const auto& z) { return z.second.buildings.placement->nests(); }))
        cut_slabs(*library);
    }
    check_lot_library(sketch, library ? &*library : nullptr);
    add_builtin_models(library, sketch.builtin_trees, sketch.builtin_lamps);
    return library;
  });
  CityMap city_map = stages.run("zone map", [&] {
    give_way_to_mapped_buildings(city.drawn, city.mapped);
    return build_city_map(city.settings, city.drawn, city.heightmap());
  });
  city.network = stages.run("road network", [&] { return grow_road_network(std::move(city_map), city.settings, city.drawn.zones,
                                                                               regions ? &regions->road_plans : nullptr); });
  city.blocks = stages.run("blocks", [&] { return cut_blocks(city.network.map, city.settings, city.drawn.zones, city.network.uses); });
  CityLots lots;  // each block's lots in a map of the block alone, until the buildings stand
  city.lots = stages.run("lots", [&] {
    const std::vector<PlannedLot> planned = plan_lots(city.blocks, city.settings, city.model_library(), city.channels,
                                                      regions ? &regions->lot_plans : nullptr);
    lots = CityLots(city.blocks, planned, city.settings, regions ? &regions->block_lots : nullptr);
    return with_density(lots.lots(), city.blocks);
  });
  Structures raised = stages.run("buildings", [&] {
    std::vector<Building> mapped = mapped_footprints(city.drawn.buildings, city.network.map, city.mapped);
    attach_building_parts(mapped, city.drawn.building_parts, city.mapped);
    HeldLots held;
    Structures s = build_on_lots(city, lots, mapped, held);
    check_export_size(s.models, city.model_library());
    // After every generated structure, so that their ids are as without mapped buildings.
    raise_mapped_buildings(mapped, city.drawn.buildings, city.drawn.building_parts, held, city.lots, city.network.map, city.drawn.zones, city.settings,
                           city.channels, city.heightmap(), static_cast<int>(s.buildings.size() + s.models.size()),
                           city.mapped);
    s.buildings.insert(s.buildings.end(), std::make_move_iterator(mapped.begin()), std::make_move_iterator(mapped.end()));
    give_stable_ids(s.buildings, s.models);
    city.lot_land = lot_land(lots.pieces(), city.blocks, lots.joined());
    // The lots are final: the city's map takes the vertices they put on the blocks' edges,
    // which the ground's zones, road areas and blocks share with them.
    lots.put_into(city.network.map);
    city.lots = with_density(lots.lots(), city.blocks);  // some with their neighbours' vertices
    return s;
  });
  city.buildings = std::move(raised.buildings);
  city.models = std::move(raised.models);
  lots = CityLots();  // the blocks' exact lots: only the lots and buildings read them
  StandingMap standing;  // what the clutter asks of the map and the lots
  stages.run("ground", [&] {
    give_covered_roads_their_carriageway(city.network.map);
    merge_sliver_road_areas(city.network.map);
    // The map's last change was the labels above: what is read of it, the blocks and the
    // lots from here on is taken now, so that they can be freed before the clutter; at once,
    // as each only reads the map (the face locator took a fifth of the stage).
    invoke_cancellable([&] { city.ground = extract_ground(city.network.map, city.blocks, city.lots, city.drawn.zones); },
                       [&] { city.exact_report = exact_work_report(city); },
                       [&] { standing = standing_map(city.network.map, city.lots); });
  });
  if (exact == ExactWork::Freed) {
    city.network = {}, city.blocks = {}, city.lots = {}, city.held_lots = {}, city.held_m2 = {};
    release_freed_memory();
  }
  // After the ground, whose centre lines the clutter dresses and names (docs/design.md, Placement).
  city.clutter = stages.run("clutter", [&] {
    return place_clutter({standing, city.ground, city.buildings, city.models}, city.model_library(), city.channels,
                         city.settings, city.drawn.zones, city.heightmap());
  });
  standing = {};
  // After the clutter, which does not read them: the layers are not held through its peak.
  stages.run("vector layers", [&] { city.layers = layers_of(city.ground, city.buildings, city.models, city.model_library()); });
  return city;
}

GenerateResult generate_city(const Sketch& sketch, const fs::path& dir, const ProgressFn& progress) {
  StageClock stages(progress, kCityStages + kWriteStages);
  City city = build_city(sketch, stages);
  return write_city(sketch, std::move(city), dir, stages);
}

namespace {

// The vector formats of kCityFormats always written and those `options` ask for (from the
// city's layers and `clutter`), a copy of the sketch and the SVG map, each file written at
// once with the others.
void export_vectors(const Sketch& sketch, const City& city, const Layer& clutter, const fs::path& dir,
                    const ExportOptions& options) {
  fs::create_directories(dir / "vector");
  const std::vector<const Layer*> layers = vector_files(city.layers, clutter);
  const FormatInput in{.dir = dir, .layers = &layers, .crs = &city.settings.crs};
  std::vector<std::function<void()>> files{
      [&] {
        if (sketch.geojson.empty()) {
          fs::copy_file(sketch.path, dir / "sketch.geojson");
        } else {
          std::ofstream copy(dir / "sketch.geojson", std::ios::binary);
          copy << sketch.geojson;
          if (!copy) throw UserError((dir / "sketch.geojson").string() + ": write failed (disk full?)");
        }
      },
      [&] { write_svg_map(city.ground, city.buildings, city.models, dir / "map.svg", city.clutter.items); }};
  for (const CityFormat& f : kCityFormats)
    if (f.kind == FormatKind::Vector) files.push_back([&in, &f] { f.write(in); });
  for_each_cancellable(files.size(), [&](std::size_t i) { files[i](); });
  // Through OGR one after another: GDAL's drivers share its state.
  for (const CityFormat& f : kCityFormats)
    if (f.kind == FormatKind::OptionalVector &&
        std::find(options.vector_formats.begin(), options.vector_formats.end(), f.name) != options.vector_formats.end())
      f.write(in);
}

}  // namespace

// From one set of building meshes and one set of ground layers. The meshes and the ground's
// layers are made at once, then the three writers run at once: each writes its own files
// (so no byte depends on the thread count) and holds little of them (CityJSON's objects and
// the GLB's parts in scratch files, OBJ and PLY a few pieces at a time), where each once
// held much of its file and all three at once raised the 10 km city's peak by 750 MiB.
ThreeDCounts write_3d_files(const City& city, const fs::path& dir, const ThreeDFiles& files) {
  const ModelLibrary* library = city.model_library();
  std::vector<Mesh> meshes;
  std::vector<GroundLayer> ground;
  invoke_cancellable(
      [&] { meshes = files.through_cache ? city_meshes(city) : structure_meshes(city.buildings, city.models, library); },
      [&] { ground = files.through_cache ? city_ground_layers(city) : ground_layers(city.ground, city.heightmap(), nullptr); });
  const MeshedCity meshed{.ground = city.ground,
                          .ground_layers = ground,
                          .buildings = city.buildings,
                          .models = city.models,
                          .meshes = meshes,
                          .clutter = city.clutter.items,
                          .library = library,
                          .terrain = city.heightmap(),
                          .crs = city.settings.crs,
                          .seed = city.settings.seed};
  ThreeDCounts counts;
  const FormatInput in{.dir = dir, .meshed = &meshed, .cityjson_seq = files.cityjson_seq, .counts = &counts};
  std::vector<const CityFormat*> writers;
  for (const CityFormat& f : kCityFormats)
    if (f.kind == FormatKind::ThreeD) writers.push_back(&f);
  for_each_cancellable(writers.size(), [&](std::size_t i) { writers[i]->write(in); });
  return counts;
}

namespace {

Validation validation_stage(const City& city, const fs::path& dir, StageClock& stages) {
  return stages.run("validation", [&] {
    return city.regions ? validate_output(dir, city.regions->validated) : validate_output(dir);
  });
}

// Writes `city`; with `released` (the city itself, which no one reads afterwards), frees
// what only the stages before the exports read (the exact map, the blocks and lots: the
// exports read the typed ground, the structures, the clutter and the layers), and the
// layers before the 3D export.
GenerateResult write(const Sketch& sketch, const City& city, City* released, const fs::path& dir, StageClock& stages,
                     const ExportOptions& options) {
  // The report first, from the whole city: city.osm is written when the sketch has a CRS.
  const bool city_osm = epsg_of(city.settings.crs).has_value();
  ordered_json report = city_report(sketch, city, options.vector_formats, city_osm);
  if (released) {
    released->network = {}, released->blocks = {}, released->lots = {}, released->lot_land = {};
    released->held_lots = {}, released->held_m2 = {};
    release_freed_memory();
  }
  stages.run("export", [&] {
    const Layer clutter = clutter_layer(city.clutter.items, city.ground, city.model_library());
    export_vectors(sketch, city, clutter, dir, options);
    if (write_city_osm(city, dir / "city.osm", options.osm_first_id) != city_osm)
      throw std::logic_error("city.osm written against the report");
  });
  WrittenCity written;
  if (options.three_d)
    written.three_d = stages.run("3d export", [&] {
      if (released) {
        released->layers = {};
        release_freed_memory();
      }
      ThreeDFiles files;
      files.cityjson_seq = options.cityjson_seq;
      return write_3d_files(city, dir, files);
    });
  release_freed_memory();  // the meshes' pages, before validation reads the files
  if (options.validate && geom::kernel_validates_its_output()) written.validation = validation_stage(city, dir, stages);
  written.validation_later = !options.validate && geom::kernel_validates_its_output();
  complete_report(report, city, written, stages.seconds);
  report["peak_memory_mib"] = stages.peak_mib;
  write_report(report, dir);
  return {report, !written.validation || written.validation->ok()};
}

}  // namespace

GenerateResult validate_written(const City& city, const fs::path& dir, ordered_json report, StageClock& stages) {
  WrittenCity written;
  written.validation = validation_stage(city, dir, stages);
  report_validation(report, written);
  report["timings_s"] = stages.seconds;
  report["peak_memory_mib"] = stages.peak_mib;
  write_report(report, dir);
  return {report, written.validation->ok()};
}

GenerateResult write_city(const Sketch& sketch, const City& city, const fs::path& dir, StageClock& stages,
                          const ExportOptions& options) {
  return write(sketch, city, nullptr, dir, stages, options);
}

GenerateResult write_city(const Sketch& sketch, City&& city, const fs::path& dir, StageClock& stages,
                          const ExportOptions& options) {
  return write(sketch, city, &city, dir, stages, options);
}

}  // namespace exacity
