// What a slab of a mesh covers from above: shadows and a cross-section's loops, holes
// filled, and no answer where the section does not close or a point is left out.
#include "geom/filled_outline.h"

#include <gtest/gtest.h>

#include "geom/measure.h"
#include "geom/polygon_check.h"

namespace geom {
namespace {

// The edges of the ring, in its order.
std::vector<std::pair<Vec2, Vec2>> loop(const Ring& r) {
  std::vector<std::pair<Vec2, Vec2>> edges;
  for (std::size_t k = 0; k < r.size(); ++k) edges.push_back({r[k], r[(k + 1) % r.size()]});
  return edges;
}

TEST(FilledOutline, ASectionLoopCoversWhatItWindsAround) {
  for (bool clockwise : {false, true}) {  // a mesh wound inside out winds the other way
    Ring square{{0, 0}, {3, 0}, {3, 8}, {0, 8}};
    if (clockwise) std::reverse(square.begin(), square.end());
    const auto rings = filled_outline({}, loop(square), {{1, 1}, {3, 8}});
    ASSERT_TRUE(rings.has_value());
    ASSERT_EQ(rings->size(), 1u);
    EXPECT_EQ(signed_area((*rings)[0]), 24);
  }
}

TEST(FilledOutline, ShadowsAndSectionsUniteAndHolesAreFilled) {
  // Four bars, two triangles each, around a 2 x 2 hole in a 6 x 6 square; a pillar's loop apart.
  std::vector<std::array<Vec2, 3>> frame;
  auto bar = [&](double x0, double y0, double x1, double y1) {
    frame.push_back({Vec2{x0, y0}, Vec2{x1, y0}, Vec2{x1, y1}});
    frame.push_back({Vec2{x0, y0}, Vec2{x1, y1}, Vec2{x0, y1}});
  };
  bar(0, 0, 6, 2), bar(0, 4, 6, 6), bar(0, 0, 2, 6), bar(4, 0, 6, 6);
  const auto rings = filled_outline(frame, loop({{10, 0}, {12, 0}, {12, 2}, {10, 2}}), {});
  ASSERT_TRUE(rings.has_value());
  ASSERT_EQ(rings->size(), 2u);
  double area = 0;
  for (const Ring& r : *rings) {
    EXPECT_EQ(ring_orientation(r), 1);
    area += signed_area(r);
  }
  EXPECT_EQ(area, 36 + 4) << "the hole filled";
}

TEST(FilledOutline, NoAnswerForAnOpenSectionOrAPointLeftOut) {
  const Ring square{{0, 0}, {3, 0}, {3, 8}, {0, 8}};
  auto open = loop(square);
  open.pop_back();
  EXPECT_FALSE(filled_outline({}, open, {}).has_value());
  EXPECT_FALSE(filled_outline({}, loop(square), {{3.5, 1}}).has_value());
  EXPECT_TRUE(filled_outline({}, loop(square), {{3, 1}}).has_value()) << "on the edge is covered";
}

}  // namespace
}  // namespace geom
