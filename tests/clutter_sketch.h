// The small city the clutter tests share: four streets in a residential square, two main
// roads crossing (a junction of major roads) and two local roads meeting them, with a
// library of boxes standing in for a house, a lamp, a stop sign and a traffic light.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/test_util.h"

namespace clutter_sketch {

namespace fs = std::filesystem;

// An upright box w x d x h (m), Z-up, standing on z = 0, centred on the origin.
inline std::string box_obj(double w, double d, double h) {
  std::string s;
  for (int k = 0; k < 8; ++k)
    s += "v " + std::to_string((k & 1 ? 0.5 : -0.5) * w) + " " + std::to_string((k & 2 ? 0.5 : -0.5) * d) + " " +
         std::to_string(k & 4 ? h : 0) + "\n";
  return s + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 2 4 8 6\nf 4 3 7 8\nf 3 1 5 7\n";
}

inline void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// The four streets in a residential square 400 x 300 m; `exacity` is the sketch's settings
// after "seed" (Exacity's own trees and lamps off, so only the library's stand), `library` the
// manifest's "models" list.
inline fs::path four_streets(const std::string& name, const std::string& exacity, const std::string& library) {
  const fs::path dir = testing_util::temp_dir("clutter-" + name);
  write(dir / "lamp.obj", box_obj(0.2, 0.2, 5));
  write(dir / "sign.obj", box_obj(0.1, 0.1, 2.5));
  write(dir / "light.obj", box_obj(0.3, 0.3, 3.5));
  write(dir / "house.obj", box_obj(8, 8, 6));
  write(dir / "library.json", R"({"models": [)" + library + "]}");
  write(dir / "sketch.geojson", R"({"type": "FeatureCollection",
    "exacity": {"seed": 3, "models": "library.json", "builtin_models": [],
                "zones": {"residential": {"layout": "streets"}})" +
                                    exacity + R"(},
    "features": [
      {"type": "Feature", "properties": {"zone": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[-200, -150], [200, -150], [200, 150], [-200, 150], [-200, -150]]]}},
      {"type": "Feature", "properties": {"road": "main"},
       "geometry": {"type": "LineString", "coordinates": [[-200, 0], [-100, 0], [0, 0], [100, 0], [200, 0]]}},
      {"type": "Feature", "properties": {"road": "main"},
       "geometry": {"type": "LineString", "coordinates": [[0, -150], [0, 0], [0, 150]]}},
      {"type": "Feature", "properties": {"road": "local"},
       "geometry": {"type": "LineString", "coordinates": [[100, 0], [100, 150]]}},
      {"type": "Feature", "properties": {"road": "local"},
       "geometry": {"type": "LineString", "coordinates": [[-100, 0], [-100, -150]]}}]})");
  return dir / "sketch.geojson";
}

inline const char* kLamp = R"({"file": "lamp.obj", "kind": "lamp", "up": "z", "scale": [1, 1], "spacing": 20})";
inline const char* kSign = R"({"file": "sign.obj", "kind": "sign", "up": "z", "scale": [1, 1]})";
inline const char* kLight = R"({"file": "light.obj", "kind": "traffic_light", "up": "z", "scale": [1, 1]})";
inline const char* kHouse = R"({"file": "house.obj", "zones": ["residential"], "up": "z", "scale": [1, 1]})";

inline std::string all_of_the_library() { return std::string(kHouse) + "," + kLamp + "," + kSign + "," + kLight; }

}  // namespace clutter_sketch
