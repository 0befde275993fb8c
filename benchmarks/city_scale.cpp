// End-to-end scale run: one sketch through every stage, printing a table of seconds and
// counts per stage and the peak memory. Measures; asserts nothing.
//
//   build/release/benchmarks/exacity_scale [SKETCH] [--threads N] [--until blocks]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>

#include <tbb/global_control.h>

#include "generate/blocks.h"
#include "generate/buildings.h"
#include "generate/lots.h"
#include "generate/cityjson_export.h"
#include "generate/mesh_export.h"
#include "generate/road_network.h"
#include "generate/svg_map.h"
#include "generate/validate.h"
#include "generate/vector_layers.h"
#include "generate/zone_map.h"

using namespace exacity;
namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void row(const char* stage, double s, const std::string& counts) { std::printf("| %-14s | %8.3f | %s\n", stage, s, counts.c_str()); }

}  // namespace

int main(int argc, char** argv) {
  fs::path sketch_path = fs::path(EXACITY_SOURCE_DIR) / "benchmarks" / "city_10km.geojson";
  int threads = 1;
  std::string until;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--until") && i + 1 < argc) until = argv[++i];
    else sketch_path = argv[i];
  }
  auto peak = [] {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024.0;
  };
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::printf("sketch %s, %d thread(s)\n\n| stage          |  seconds | counts\n|----------------|----------|-------\n",
              sketch_path.string().c_str(), threads);

  auto t = std::chrono::steady_clock::now();
  Sketch sketch = load_sketch(sketch_path);
  row("sketch", seconds_since(t), std::to_string(sketch.zones.size()) + " zones, " + std::to_string(sketch.roads.size()) + " roads");

  t = std::chrono::steady_clock::now();
  std::optional<Terrain> terrain;
  if (sketch.terrain) terrain = Terrain::load(*sketch.terrain);
  ZoneMap zones = build_zone_map(sketch, terrain ? &*terrain : nullptr);
  row("zone map", seconds_since(t), std::to_string(zones.map.counts().faces) + " faces");

  t = std::chrono::steady_clock::now();
  RoadNetwork net = grow_road_network(std::move(zones), sketch);
  double roads_s = seconds_since(t);
  row("road network", roads_s,
      std::to_string(net.map.roads.size()) + " roads, " + std::to_string(net.stats.levels) + " levels, " +
          std::to_string(net.map.map.counts().edges) + " map edges");

  t = std::chrono::steady_clock::now();
  std::vector<Block> blocks = cut_blocks(net.map, sketch);
  double blocks_s = seconds_since(t);
  row("blocks", blocks_s, std::to_string(blocks.size()) + " blocks");
  if (until == "blocks") {
    std::printf("\nroads and blocks: %.3f s; peak memory %.0f MiB\n", roads_s + blocks_s, peak());
    return 0;
  }

  t = std::chrono::steady_clock::now();
  std::vector<Lot> lots = plan_lots(blocks, sketch);
  insert_lots(net.map, blocks, lots, sketch);
  row("lots", seconds_since(t), std::to_string(lots.size()) + " lots");

  t = std::chrono::steady_clock::now();
  std::vector<Building> buildings = place_buildings(net.map, lots, sketch, nullptr, nullptr);
  row("buildings", seconds_since(t), std::to_string(buildings.size()) + " footprints");

  t = std::chrono::steady_clock::now();
  CityLayers layers = extract_layers(net.map, blocks, lots, buildings, sketch);
  row("vector layers", seconds_since(t), std::to_string(layers.roads.features.size()) + " road pieces");

  fs::path out = fs::temp_directory_path() / "exacity-scale";
  fs::remove_all(out);
  fs::create_directories(out / "vector");
  t = std::chrono::steady_clock::now();
  fs::copy_file(sketch.path, out / "sketch.geojson");
  for (const Layer* l : {&layers.zones, &layers.water, &layers.roads, &layers.road_areas, &layers.blocks, &layers.lots, &layers.buildings})
    write_geojson(*l, sketch.crs, out / "vector" / (l->name + ".geojson"));
  write_svg_map(layers, out / "map.svg");
  row("export", seconds_since(t), out.string());

  t = std::chrono::steady_clock::now();
  std::vector<Mesh> meshes = building_meshes(buildings, nullptr);
  write_cityjson(layers, buildings, meshes, nullptr, nullptr, sketch, out / "city.city.json");
  MeshCounts mesh = write_meshes(buildings, meshes, out / "city.obj", out / "city.ply");
  row("3d export", seconds_since(t), std::to_string(mesh.faces) + " faces in city.obj and city.ply, city.city.json");

  t = std::chrono::steady_clock::now();
  Validation v = validate_output(out);
  row("validation", seconds_since(t), v.ok() ? "valid" : "INVALID: " + v.problems[0]);

  std::printf("\nroads and blocks: %.3f s; peak memory %.0f MiB\n", roads_s + blocks_s, peak());
  return 0;
}
