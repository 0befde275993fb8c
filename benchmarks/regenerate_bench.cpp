// Regenerating after a one-zone edit against building the edited sketch whole: seconds per
// stage both ways, as the server's generation runs them (build_city, write_city into a
// temporary folder without the 3D files, which the server writes when first downloaded, the
// 3D view's tiles: the answer, what the page shows; then validation), the answer and the
// whole update apart, and how many regions, blocks, lots and meshes were
// reused. Each stage's CPU seconds (all threads) are printed beside its wall seconds, since
// on a shared machine the wall clock measures the other users too.
// Then, per layer file of vector/, how many features the edit changed: lines of the
// regenerated city's file that are not in the first city's.
// Measures; asserts nothing (tests/regenerate_test.cpp holds the two cities equal).
//
//   build/release/benchmarks/exacity_regenerate SKETCH [--scale K] [--zone NAME] [--move DX DY] [--keep DIR]
//
// The sketch's coordinates are multiplied by K (roads keep their widths); the edit moves the
// first corner of the zone whose "name" is NAME (the first zone when none is given) by DX, DY
// metres. With --keep, the three runs' folders are kept as DIR/first, DIR/whole and DIR/again
// (to compare the regenerated run's files with the whole one's).
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "benchmarks/scaled_sketch.h"
#include "benchmarks/stage_cpu.h"
#include "generate/errors.h"
#include "generate/pipeline.h"
#include "generate/regenerate.h"
#include "serve/city_tiles.h"

using namespace exacity;
using nlohmann::ordered_json;

namespace {

struct Run {
  City city;
  ordered_json seconds{}, cpu = ordered_json::object();
  double total = 0, total_cpu = 0;
  double answer = 0, answer_cpu = 0;  // up to the answer: the stages before validation
  std::map<std::string, std::set<std::string>> features{};  // per file of vector/, its features' lines
};

// The features of each layer file, one a line, without the comma after it.
std::map<std::string, std::set<std::string>> feature_lines(const std::filesystem::path& vector_dir) {
  std::map<std::string, std::set<std::string>> out;
  for (const auto& entry : std::filesystem::directory_iterator(vector_dir)) {
    std::ifstream in(entry.path());
    std::set<std::string>& lines = out[entry.path().filename().string()];
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("{\"type\":\"Feature\"", 0) != 0) continue;
      if (line.back() == ',') line.pop_back();
      if (line.size() > 2 && line.compare(line.size() - 2, 2, "]}") == 0) line.resize(line.size() - 2);
      lines.insert(line);
    }
  }
  return out;
}

std::string keep_dir;  // --keep

Run build(const ordered_json& doc, const std::string& path, std::shared_ptr<RegionCache> cache, const City* previous,
          const char* name) {
  bench::StageCpu cpu;
  StageClock clock([&](int, int, const std::string& name) { cpu.next(name); }, kCityStages + kWriteStages);
  const double cpu_start = bench::cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  Sketch sketch = parse_sketch(doc.dump(), path);
  // The copy write_city makes is of the scaled sketch, which validation reads (else it copies SKETCH's file).
  if (sketch.geojson.empty()) sketch.geojson = doc.dump();
  Run run{.city = previous ? regenerate(*previous, sketch, clock) : build_city(sketch, clock, std::move(cache))};
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("exacity_regenerate." + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  GenerateResult written =
      write_city(sketch, run.city, dir, clock, ExportOptions::before_answer());
  clock.run("tiles", [&] { serve::write_city_tiles(run.city, dir / "tiles"); });
  run.answer_cpu = bench::cpu_seconds() - cpu_start;
  run.answer = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  validate_written(run.city, dir, std::move(written.report), clock);
  cpu.next("");
  run.cpu = cpu.seconds;
  run.total_cpu = bench::cpu_seconds() - cpu_start;
  run.features = feature_lines(dir / "vector");
  if (!keep_dir.empty()) {
    std::filesystem::create_directories(keep_dir);
    std::filesystem::remove_all(std::filesystem::path(keep_dir) / name);
    std::filesystem::copy(dir, std::filesystem::path(keep_dir) / name, std::filesystem::copy_options::recursive);
  }
  std::filesystem::remove_all(dir);
  run.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.seconds = clock.seconds;
  return run;
}

double monotonic_seconds() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SKETCH [--scale K] [--zone NAME] [--move DX DY] [--keep DIR]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  double k = 1, dx = 10, dy = 10;
  std::string zone_name;
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--scale") && i + 1 < argc) k = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--zone") && i + 1 < argc) zone_name = argv[++i];
    else if (!std::strcmp(argv[i], "--move") && i + 2 < argc) dx = std::stod(argv[++i]), dy = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--keep") && i + 1 < argc) keep_dir = argv[++i];
  }
  try {
    const ordered_json doc = bench::scaled_sketch(path, k);
    ordered_json edited = doc;
    bool moved = false;
    for (ordered_json& f : edited["features"]) {
      const ordered_json& p = f["properties"];
      if (moved || !p.contains("zone") || (!zone_name.empty() && p.value("name", "") != zone_name)) continue;
      ordered_json& outer = f["geometry"]["type"] == "MultiPolygon" ? f["geometry"]["coordinates"][0][0] : f["geometry"]["coordinates"][0];
      for (ordered_json* corner : {&outer.front(), &outer.back()}) {
        (*corner)[0] = (*corner)[0].get<double>() + dx;
        (*corner)[1] = (*corner)[1].get<double>() + dy;
      }
      moved = true;
    }
    if (!moved) throw UserError(path + ": no zone named \"" + zone_name + "\"");

    const Run first = build(doc, path, std::make_shared<RegionCache>(), nullptr, "first");
    const Run whole = build(edited, path, nullptr, nullptr, "whole");
    const double again_start = monotonic_seconds();
    const Run again = build(edited, path, nullptr, &first.city, "again");
    // For `perf record -k CLOCK_MONOTONIC` and `perf report --time START,END`: the regenerated run alone.
    std::printf("regenerated run: CLOCK_MONOTONIC %.6f to %.6f s\n", again_start, monotonic_seconds());
    std::printf("| stage          | whole s | regenerated s | whole CPU s | regenerated CPU s |\n"
                "|----------------|---------|---------------|-------------|-------------------|\n");
    for (const auto& [stage, s] : whole.seconds.items())
      std::printf("| %-14s | %7.3f | %13.3f | %11.3f | %17.3f |\n", stage.c_str(), s.get<double>(),
                  again.seconds.value(stage, 0.0), whole.cpu.value(stage, 0.0), again.cpu.value(stage, 0.0));
    std::printf("| %-14s | %7.3f | %13.3f | %11.3f | %17.3f |\n", "answer", whole.answer, again.answer, whole.answer_cpu,
                again.answer_cpu);
    std::printf("| %-14s | %7.3f | %13.3f | %11.3f | %17.3f |\n", "all", whole.total, again.total, whole.total_cpu,
                again.total_cpu);
    const RegionCache& c = *again.city.regions;
    std::printf("reused: %d of %d region plans, %d of %d block plans, %d of %d lot placements, %d of %d meshes\n",
                c.road_plans.hits(), c.road_plans.hits() + c.road_plans.misses(), c.lot_plans.hits(),
                c.lot_plans.hits() + c.lot_plans.misses(), c.placements.hits(), c.placements.hits() + c.placements.misses(),
                c.meshes.hits(), c.meshes.hits() + c.meshes.misses());
    std::printf("block lots reused: %d of %d (blocks and their merges), ground pieces %d of %d, tiles %d of %d\n"
                "features the edit changed (lines not in the first city's):",
                c.block_lots.hits(), c.block_lots.hits() + c.block_lots.misses(), c.ground_pieces.hits(),
                c.ground_pieces.hits() + c.ground_pieces.misses(), c.tiles.hits(), c.tiles.hits() + c.tiles.misses());
    for (const auto& [file, lines] : again.features) {
      const std::set<std::string>& before = first.features.at(file);
      std::size_t changed = 0;
      for (const std::string& line : lines) changed += !before.count(line);
      std::printf(" %s %zu of %zu;", file.c_str(), changed, lines.size());
    }
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
