// The street lamps of a generated city as another renderer's lights: each lamp's point light
// (render/night.h: where it hangs, its intensity straight down, the share of it sent sideways
// and up, the reach its light fades out at) as JSON on standard output, in the city's
// coordinates (city.glb's). The Cycles comparison's night view (benchmarks/cycles/) gives
// Cycles these. Measures nothing.
//
//   build/release/benchmarks/exacity_lamps OUT
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "generate/pipeline.h"
#include "generate/sketch/sketch.h"
#include "render/night.h"
#include "render/scene.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: exacity_lamps OUT (an output folder of exacity generate)\n");
    return 2;
  }
  const fs::path out = argv[1];
  auto text = [](const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream all;
    all << in.rdbuf();
    return all.str();
  };
  const nlohmann::json report = nlohmann::json::parse(text(out / "report.json"), nullptr, false);
  if (report.is_discarded() || !report.contains("sketch_path")) {
    std::fprintf(stderr, "%s: not an output folder of exacity generate\n", out.string().c_str());
    return 2;
  }
  // The city exacity render rebuilds: the same sketch, its relative paths where it was.
  const exacity::Sketch sketch =
      exacity::parse_sketch(text(out / "sketch.geojson"), report["sketch_path"].get<std::string>());
  exacity::StageClock clock(nullptr, 0);
  const exacity::City city = exacity::build_city(sketch, clock);
  nlohmann::json lamps = nlohmann::json::array();
  for (const render::Lamp& l : render::city_lamps(city, render::kLampIntensity))
    lamps.push_back({l.position.x, l.position.y, l.position.z, l.intensity});
  std::printf("%s\n", nlohmann::json{{"uplight", render::kUplight}, {"reach_m", render::kReach}, {"lamps", lamps}}
                          .dump()
                          .c_str());
  return 0;
}
