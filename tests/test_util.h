// Small helpers shared by the test suites.
#pragma once

#include <filesystem>
#include <string>

#include "geom/planar_map.h"

namespace testing_util {

// Shoelace area in doubles: exact for the small integer coordinates the tests use.
inline double signed_area(const geom::Ring& r) {
  double a = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const geom::Vec2 &p = r[i], &q = r[(i + 1) % r.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return a / 2;
}

inline double area(const geom::Polygon& p) {
  double a = signed_area(p.outer);
  for (const auto& h : p.holes) a += signed_area(h);
  return a;
}

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
