// Small helpers shared by the test suites.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

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

// Where a test's files go: a folder of this build's under the system's temporary folder,
// so two builds' test runs on one machine (a CI clone beside a working copy) never write
// into each other's folders.
inline std::filesystem::path test_root() {
  return std::filesystem::temp_directory_path() /
         ("exacity-test-" + std::to_string(std::hash<std::string>{}(EXACITY_BUILD_DIR) % 1000000007));
}

// The folder `name` of the running test. The test's own name is part of it: ctest runs each
// test in its own process, two at a time, so two tests calling one helper (one fixture city)
// must not share, and clear, one folder.
inline std::filesystem::path test_dir(const std::string& name) {
  const auto* test = testing::UnitTest::GetInstance()->current_test_info();
  if (!test) return test_root() / name;
  // A hash, not the test's name: Slurm's sockets live in a test's folder, and a Unix socket's
  // path holds at most 108 bytes.
  const std::string test_name = std::string(test->test_suite_name()) + "." + test->name();
  return test_root() / ("t" + std::to_string(std::hash<std::string>{}(test_name) % 1000000007)) / name;
}

// A fresh empty folder of the running test's.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto dir = test_dir(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A cell from a ring: edges along `road_edges` (by index) have kind 1, the rest 0.
inline geom::Cell fronted_cell(const geom::Ring& ring, std::vector<int> road_edges) {
  geom::PlanarMap map;
  map.add_ring(ring, 0);
  // Thin road strips outside the chosen edges give those edges kind 1.
  for (int e : road_edges) {
    geom::Vec2 a = ring[e], b = ring[(e + 1) % ring.size()];
    double dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
    geom::Vec2 out{dy / len * 5, -dx / len * 5};
    map.add_ring({a, {a.x + out.x, a.y + out.y}, {b.x + out.x, b.y + out.y}, b}, 1);
  }
  map.insert_batch();
  map.label_faces([](const geom::Windings& w) {
    return geom::winding_of(w, 0) != 0 ? 1 : geom::winding_of(w, 1) != 0 ? 2 : 0;
  });
  auto cells = map.cells({-1, 0, -1}, {0, 0, 1});
  EXPECT_EQ(cells.size(), 1u);
  return cells.at(0);
}

}  // namespace testing_util
