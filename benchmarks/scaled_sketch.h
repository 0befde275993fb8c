// A sketch file read as JSON with every feature's coordinates multiplied by K (roads keep
// their widths): the benchmarks' way to make a small example a large city.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace exacity::bench {

inline void scale_coordinates(nlohmann::ordered_json& coordinates, double k) {
  if (coordinates.is_number()) return void(coordinates = coordinates.get<double>() * k);
  for (nlohmann::ordered_json& c : coordinates) scale_coordinates(c, k);
}

inline nlohmann::ordered_json scaled_sketch(const std::string& path, double k) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::ordered_json doc = nlohmann::ordered_json::parse(text.str());
  for (nlohmann::ordered_json& f : doc["features"]) scale_coordinates(f["geometry"]["coordinates"], k);
  return doc;
}

}  // namespace exacity::bench
