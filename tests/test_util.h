// Small helpers shared by the test suites.
#pragma once

#include <filesystem>
#include <string>

#include "geom/measure.h"
#include "geom/planar_map.h"

namespace testing_util {

using geom::area;
using geom::signed_area;

// The polygons of one dissolved group.
inline std::vector<geom::Polygon> polygons(const std::vector<geom::Dissolved>& group) {
  std::vector<geom::Polygon> out;
  for (const auto& d : group) out.push_back(d.polygon);
  return out;
}

// A fresh empty folder under the system's temporary folder.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("exacity-test-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace testing_util
