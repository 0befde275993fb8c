// The compiler's optimizer checked where it once was wrong: this file is compiled at -O3
// with the flags the Release build adds (tests/CMakeLists.txt), so a g++ that drops a
// rounding there fails here, not silently in the Release program's outputs.
#include <array>
#include <vector>

#include <gtest/gtest.h>

namespace {

using Float3 = std::array<float, 3>;

struct Placed {
  double x, y, floor;
};

// The glTF writer's pattern (generate/export/gltf_export.cpp: Frame, add_model_nodes): a
// position made single precision about an origin, then kept in a node's doubles.
__attribute__((noinline)) std::vector<std::vector<double>> node_translations(const std::vector<Placed>& placed,
                                                                              double origin_x, double origin_y) {
  std::vector<std::vector<double>> nodes;
  for (const Placed& p : placed) {
    const Float3 at{static_cast<float>(p.x - origin_x), static_cast<float>(p.floor), static_cast<float>(origin_y - p.y)};
    std::vector<double> translation;
    translation = {at[0], at[1], at[2]};
    nodes.push_back(translation);
  }
  return nodes;
}

bool single_precision(double v) { return static_cast<double>(static_cast<float>(v)) == v; }

// g++ 12.2 at -O2 and -O3 vectorized the first two coordinates and lost their rounding to
// float (the town's city.glb held 2,480 model positions as unrounded doubles in the Release
// build only); -fno-tree-slp-vectorize, which the Release build adds, keeps it.
TEST(Compiler, APositionRoundedToFloatStaysRoundedInDoubles) {
  const std::vector<Placed> placed{{-5.0693359375123, 188.29, 1.1}, {24.737304687512, 184.88, 0.3}};
  for (const std::vector<double>& t : node_translations(placed, 750, 450))
    for (double v : t) EXPECT_TRUE(single_precision(v)) << v;
}

}  // namespace
