#include "geom/box_index.h"

#include <gtest/gtest.h>

#include <random>

namespace {

// The index answers what a pass over every box would, whatever the bucket: small and long
// boxes, boxes added again as they grow, and boxes past the grid.
TEST(BoxIndex, FindsTheBoxesAPassOverAllFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(-500, 500), size(0, 30);
  for (double bucket : {0.0, 1.0, 25.0, 1000.0}) {
    geom::BoxIndex index(bucket);
    std::vector<geom::Box> boxes;
    auto add = [&](int id, geom::Box b) {
      if (static_cast<int>(boxes.size()) <= id) boxes.resize(id + 1, geom::Box::none());
      boxes[id].add(b);
      index.add(id, b);
    };
    for (int i = 0; i < 400; ++i) {
      const double x = at(rng), y = at(rng);
      add(i, {x, y, x + size(rng), y + size(rng)});
    }
    add(400, {-1e6, 0, 1e6, 1});     // over more buckets than the grid keeps
    add(401, {1e16, 1e16, 1e16, 1e16});  // past the grid
    add(7, {100, 100, 101, 101});    // grows
    auto check = [&](const geom::Box& query) {
      std::vector<int> expected;
      for (int id = 0; id < static_cast<int>(boxes.size()); ++id)
        if (boxes[id].meets(query)) expected.push_back(id);
      EXPECT_EQ(index.meeting(query), expected) << "bucket " << bucket;
    };
    for (int q = 0; q < 300; ++q) {
      const double x = at(rng), y = at(rng), s = q % 3 == 0 ? 0 : size(rng) * 3;
      check({x, y, x + s, y + s});
    }
    check({100.5, 100.5, 100.5, 100.5});
    check({1e16, 1e16, 1e16, 1e16});
    check({-1e7, -1e7, 1e7, 1e7});
  }
}

}  // namespace
