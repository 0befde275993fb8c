// End-to-end scale run: one sketch through every stage, printing a table of seconds and
// counts per stage and the peak memory. Measures; asserts nothing.
//
//   build/release/benchmarks/exacity_scale [SKETCH] [--threads N] [--until blocks|lots] [--models LIBRARY]
//                                          [--3d-export RUNS]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>

#include <tbb/global_control.h>
#include <unistd.h>

#include "benchmarks/heap_peaks.h"
#include "benchmarks/stage_cpu.h"
#include "generate/errors.h"
#include "generate/parcels/blocks.h"
#include "generate/parcels/lots.h"
#include "generate/pipeline.h"
#include "generate/layout/road_network.h"
#include "generate/city/city_map.h"

using namespace exacity;
namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void row(const char* stage, double s, double cpu, double system_s, long faults, double heap_mib,
         const std::string& counts) {
  std::printf("| %-14s | %8.3f | %8.3f | %8.3f | %9ld | %8.0f | %s\n", stage, s, cpu, system_s, faults, heap_mib,
              counts.c_str());
}
void row(const char* stage, double s, const std::string& counts) { std::printf("| %-14s | %8.3f | %s\n", stage, s, counts.c_str()); }

struct ScaleOptions {
  fs::path sketch_path = fs::path(EXACITY_SOURCE_DIR) / "benchmarks" / "city_10km.geojson", models;
  int threads = 1;
  std::string until;
  int three_d_runs = 0;  // --3d-export: the city built once, then only its 3D export, this many times
};

ScaleOptions parse_options(int argc, char** argv) {
  ScaleOptions o;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) o.threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--until") && i + 1 < argc) o.until = argv[++i];
    else if (!std::strcmp(argv[i], "--models") && i + 1 < argc) o.models = argv[++i];
    else if (!std::strcmp(argv[i], "--3d-export") && i + 1 < argc) o.three_d_runs = std::atoi(argv[++i]);
    else o.sketch_path = argv[i];
  }
  return o;
}

// The road-network target: roads and blocks alone (and lots, to profile that stage).
void run_road_stages(const Sketch& sketch, bool with_lots) {
  std::printf("| stage          |  seconds | counts\n|----------------|----------|-------\n");
  auto t = std::chrono::steady_clock::now();
  std::optional<Terrain> terrain;
  if (sketch.terrain) terrain = Terrain::load(*sketch.terrain);
  CityMap zones = build_city_map(sketch, sketch, terrain ? &*terrain : nullptr);
  row("zone map", seconds_since(t), std::to_string(zones.map.counts().faces) + " faces");
  t = std::chrono::steady_clock::now();
  RoadNetwork net = grow_road_network(std::move(zones), sketch, sketch.zones);
  double roads_s = seconds_since(t);
  row("road network", roads_s,
      std::to_string(net.map.roads.size()) + " roads, " + std::to_string(net.stats.levels) + " levels, " +
          std::to_string(net.map.map.counts().edges) + " map edges");
  t = std::chrono::steady_clock::now();
  std::vector<Block> blocks = cut_blocks(net.map, sketch, sketch.zones);
  double blocks_s = seconds_since(t);
  row("blocks", blocks_s, std::to_string(blocks.size()) + " blocks");
  if (with_lots) {
    t = std::chrono::steady_clock::now();
    CityLots city_lots(blocks, plan_lots(blocks, sketch, nullptr, Channels{}), sketch);
    city_lots.put_into(net.map);
    const std::vector<Lot> lots = city_lots.lots();
    row("lots", seconds_since(t), std::to_string(lots.size()) + " lots");
  }
  std::printf("\nroads and blocks: %.3f s; peak memory %.0f MiB\n", roads_s + blocks_s, peak_resident_mib());
}

// The city built once, then its 3D export (write_3d_files, as the "3d export" stage runs
// it) `runs` times into one folder: the runs' spread says how much of a change in that
// stage's seconds is the machine's.
void run_3d_export(const Sketch& sketch, int runs) {
  const fs::path out = fs::temp_directory_path() / ("exacity-scale." + std::to_string(::getpid()));
  fs::remove_all(out);
  fs::create_directories(out);
  StageClock clock(nullptr, kCityStages);
  const City city = build_city(sketch, clock);
  std::printf("| run |  seconds | CPU s    | sys s    | faults    | counts\n"
              "|-----|----------|----------|----------|-----------|-------\n");
  for (int r = 0; r < runs; ++r) {
    const auto t = std::chrono::steady_clock::now();
    const double cpu = bench::cpu_seconds();
    const bench::KernelUse k = bench::kernel_use();
    const ThreeDCounts counts = write_3d_files(city, out);
    const bench::KernelUse k2 = bench::kernel_use();
    std::printf("| %3d | %8.3f | %8.3f | %8.3f | %9ld | %zu mesh faces; glTF %zu triangles, %zu instances\n", r + 1,
                seconds_since(t), bench::cpu_seconds() - cpu, k2.system_s - k.system_s, k2.faults - k.faults,
                counts.mesh.faces, counts.gltf.triangles, counts.gltf.instances);
    std::fflush(stdout);
  }
  std::printf("\noutputs in %s\n", out.string().c_str());
}

// The counts column of the full run's row for one stage.
std::string stage_counts(const std::string& stage, double seconds, const GenerateResult& result) {
  const auto& report = result.report;
  const auto& c = report["counts"];
  return stage == "road network" ? std::to_string(c["roads"].get<int>()) + " roads"
         : stage == "blocks"      ? std::to_string(c["blocks"].get<int>()) + " blocks"
         : stage == "lots"        ? std::to_string(c["lots"].get<int>()) + " lots, " +
                                 std::to_string(static_cast<long>(c["lots"].get<double>() / seconds)) + " lots/s"
         : stage == "buildings" ? std::to_string(c["buildings"].get<int>()) + " buildings, " +
                                      std::to_string(static_cast<long>(c["buildings"].get<double>() / seconds)) +
                                      " buildings/s"
         : stage == "3d export" ? std::to_string(c["mesh"]["faces"].get<long>()) + " mesh faces; glTF " +
                                      std::to_string(c["gltf"]["triangles"].get<long>()) + " triangles, " +
                                      std::to_string(c["gltf"]["instances"].get<long>()) + " instances"
         : stage == "validation" ? (result.valid ? "valid" : "INVALID: " + report["validation"]["problems"][0].get<std::string>())
                                 : "";
}

// Everything, as `exacity generate` runs it.
void run_every_stage(const Sketch& sketch) {
  // One folder per run, so that two runs side by side do not write over each other.
  fs::path out = fs::temp_directory_path() / ("exacity-scale." + std::to_string(::getpid()));
  fs::remove_all(out);
  fs::create_directories(out);
  auto t = std::chrono::steady_clock::now();
  bench::StageCpu cpu;
  bench::HeapPeaks heap;
  const double cpu_start = bench::cpu_seconds();
  GenerateResult result = generate_city(sketch, out, [&](int, int, const std::string& stage) {
    cpu.next(stage);
    heap.next(stage);
  });
  cpu.next("");
  heap.stop();
  const double total = seconds_since(t), total_cpu = bench::cpu_seconds() - cpu_start;
  const auto& report = result.report;
  const auto& s = report["timings_s"];
  // heap MiB: the stage's peak of live heap (tcmalloc's count, sampled; 0 without tcmalloc).
  std::printf("| stage          |  seconds | CPU s    | sys s    | faults    | heap MiB | counts\n"
              "|----------------|----------|----------|----------|-----------|----------|-------\n");
  for (const auto& [stage, seconds] : s.items()) {
    std::string counts = stage_counts(stage, seconds.get<double>(), result);
    row(stage.c_str(), seconds.get<double>(), cpu.seconds.value(stage, 0.0), cpu.system_s.value(stage, 0.0),
        cpu.faults.value(stage, 0L), heap.peak_mib[stage], counts);
  }
  const double validation = s["validation"].get<double>();
  std::printf("\nsketch to every export: %.3f s (+ validation %.3f s); CPU %.3f s in all; peak memory %.0f MiB; outputs in %s\n",
              total - validation, validation, total_cpu, peak_resident_mib(), out.string().c_str());
}

}  // namespace

void run(const ScaleOptions& o);

constexpr const char* kUsage =
    "usage: exacity_scale [SKETCH] [--threads N] [--until blocks|lots] [--models LIBRARY] [--3d-export RUNS]\n"
    "  runs SKETCH (default benchmarks/city_10km.geojson) through every stage, or until the blocks or lots,\n"
    "  and prints each stage's seconds and counts and the peak memory; with --3d-export, builds the city once\n"
    "  and times its 3D export RUNS times\n";

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return std::printf("%s", kUsage), 0;
  const ScaleOptions o = parse_options(argc, argv);
  try {
    run(o);
  } catch (const UserError& e) {
    std::fprintf(stderr, "exacity_scale: error: %s\n", e.what());
    return 2;
  }
  return 0;
}

void run(const ScaleOptions& o) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, o.threads);
  Sketch sketch = load_sketch(o.sketch_path);
  if (!o.models.empty()) sketch.models = fs::absolute(o.models);
  std::printf("sketch %s%s%s, %d thread(s)\n\n", o.sketch_path.string().c_str(), sketch.models.empty() ? "" : ", models ",
              sketch.models.string().c_str(), o.threads);
  if (o.until == "blocks" || o.until == "lots") run_road_stages(sketch, o.until == "lots");
  else if (o.three_d_runs > 0) run_3d_export(sketch, o.three_d_runs);
  else run_every_stage(sketch);
}
