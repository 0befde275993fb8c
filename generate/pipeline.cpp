#include "generate/pipeline.h"

#include <chrono>
#include <fstream>
#include <optional>

#include "generate/errors.h"
#include "generate/svg_map.h"
#include "generate/terrain.h"
#include "generate/validate.h"
#include "generate/vector_layers.h"
#include "generate/zone_map.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// Times stages into the report and tells the progress callback as each begins.
class Stages {
 public:
  Stages(const ProgressFn& progress, int count) : progress_(progress), count_(count) {}
  template <typename F>
  auto run(const std::string& name, F&& f) {
    if (progress_) progress_(++index_, count_, name);
    auto start = std::chrono::steady_clock::now();
    struct Record {
      Stages& s;
      const std::string& name;
      std::chrono::steady_clock::time_point start;
      ~Record() {
        s.seconds[name] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
    } record{*this, name, start};
    return f();
  }
  ordered_json seconds = ordered_json::object();

 private:
  const ProgressFn& progress_;
  int count_, index_ = 0;
};

}  // namespace

GenerateResult generate_city(const Sketch& sketch, const fs::path& dir, const ProgressFn& progress) {
  Stages stages(progress, 5);
  std::optional<Terrain> terrain = stages.run("terrain", [&]() -> std::optional<Terrain> {
    if (!sketch.terrain) return std::nullopt;
    return Terrain::load(*sketch.terrain);
  });
  ZoneMap zone_map = stages.run("zone map", [&] { return build_zone_map(sketch, terrain ? &*terrain : nullptr); });
  CityLayers layers = stages.run("vector layers", [&] { return extract_layers(zone_map, sketch); });
  stages.run("export", [&] {
    fs::create_directories(dir / "vector");
    fs::copy_file(sketch.path, dir / "sketch.geojson");
    for (const Layer* l : {&layers.zones, &layers.water, &layers.roads, &layers.road_areas})
      write_geojson(*l, sketch.crs, dir / "vector" / (l->name + ".geojson"));
    write_svg_map(layers, dir / "map.svg");
  });
  Validation validation = stages.run("validation", [&] { return validate_output(dir); });

  auto counts = zone_map.map.counts();
  ordered_json report{
      {"generator", "exacity"},
      {"version", kVersion},
      {"sketch", sketch.path.filename().string()},
      {"seed", sketch.seed},
      {"counts",
       {{"zones", layers.zones.features.size()},
        {"water", layers.water.features.size()},
        {"roads", layers.roads.features.size()},
        {"road_areas", layers.road_areas.features.size()},
        {"map", {{"vertices", counts.vertices}, {"edges", counts.edges}, {"faces", counts.faces}}}}},
      {"validation",
       {{"ok", validation.ok()}, {"problems", validation.problems}, {"widest_sliver_m", validation.widest_sliver}}},
      {"timings_s", stages.seconds},
  };
  std::ofstream out(dir / "report.json", std::ios::binary);
  out << report.dump(2) << "\n";
  if (!out) throw UserError((dir / "report.json").string() + ": write failed (disk full?)");
  return {report, validation.ok()};
}

}  // namespace exacity
