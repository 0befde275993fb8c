// Where a ring lies against another, from orientations alone: the same answers as a planar
// map of the two (geom::interiors_overlap) on small rings full of shared vertices, shared
// and collinear edges, and touching corners.
#include "generate/export/ring_sides.h"

#include <gtest/gtest.h>

#include <random>

#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::Ring;

Ring square(double x, double y, double side) { return {{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}}; }

TEST(RingSides, InsideTouchingSharingAndCrossing) {
  const Ring a = square(0, 0, 4);
  EXPECT_TRUE(ring_in_polygon(square(1, 1, 2), {a, {}}));    // inside, apart from the edges
  EXPECT_TRUE(ring_in_polygon(square(0, 0, 2), {a, {}}));    // in a corner, along two edges
  EXPECT_TRUE(ring_in_polygon(a, {a, {}}));                  // the same ring
  EXPECT_TRUE(ring_in_polygon({{0, 0}, {4, 0}, {2, 2}}, {a, {}}));  // along an edge, a vertex inside
  EXPECT_FALSE(ring_in_polygon(square(3, 3, 2), {a, {}}));   // crossing
  EXPECT_FALSE(ring_in_polygon(square(4, 0, 1), {a, {}}));   // outside along an edge
  EXPECT_FALSE(ring_in_polygon(square(-1, -1, 6), {a, {}}));  // around it
  // From one corner to the opposite one: every vertex on the boundary, the diagonal's pieces
  // inside, but the ring leaves it.
  EXPECT_FALSE(ring_in_polygon({{0, 0}, {4, 4}, {-1, 4}}, {a, {}}));
  // A hair over the edge: exact.
  EXPECT_FALSE(ring_in_polygon(square(2, 2, 2 + 1e-12), {a, {}}));
  // A hole: the ring must keep out of it, touching allowed.
  const geom::Polygon holed{a, {{{1, 1}, {1, 3}, {3, 3}, {3, 1}}}};
  EXPECT_TRUE(ring_in_polygon(square(0, 0, 1), holed));
  EXPECT_TRUE(ring_in_polygon({{0, 0}, {4, 0}, {3, 1}, {1, 1}}, holed));  // along the hole's edge
  EXPECT_FALSE(ring_in_polygon(square(0, 0, 2), holed));
  EXPECT_FALSE(ring_in_polygon(square(1.5, 1.5, 1), holed));

  EXPECT_TRUE(interiors_apart(a, square(4, 0, 2)));   // a shared wall
  EXPECT_TRUE(interiors_apart(a, square(4, 4, 2)));   // a shared corner
  EXPECT_TRUE(interiors_apart(a, square(9, 9, 1)));   // apart
  EXPECT_FALSE(interiors_apart(a, a));                // the same
  EXPECT_FALSE(interiors_apart(a, square(1, 1, 1)));  // inside, no edge meeting
  EXPECT_FALSE(interiors_apart(a, square(2, 2, 4)));  // crossing
  EXPECT_FALSE(interiors_apart(a, square(4 - 1e-12, 0, 2)));

  EXPECT_TRUE(segments_run_along({0, 0}, {4, 0}, {3, 0}, {9, 0}));
  EXPECT_TRUE(segments_run_along({0, 0}, {0, 4}, {0, 1}, {0, 2}));
  EXPECT_FALSE(segments_run_along({0, 0}, {4, 0}, {4, 0}, {9, 0}));  // end to end
  EXPECT_FALSE(segments_run_along({0, 0}, {4, 4}, {1, 1}, {2, 2 + 1e-12}));
}

// Random triangles and quadrilaterals on a 4 x 4 grid, against a planar map of the two.
TEST(RingSides, TheMapsAnswersOnRingsFullOfDegeneracies) {
  std::mt19937 random(37);
  std::uniform_int_distribution<int> coordinate(0, 4), corners(3, 4);
  auto ring = [&] {
    for (;;) {
      Ring r;
      for (int k = corners(random); k > 0; --k) r.push_back({double(coordinate(random)), double(coordinate(random))});
      const int turn = geom::ring_orientation(r);
      if (turn == -1) std::reverse(r.begin(), r.end());
      if (turn != 0) return r;
    }
  };
  const Ring frame = square(-1, -1, 6);
  int apart = 0, within = 0;
  for (int n = 0; n < 4000; ++n) {
    const Ring a = ring(), b = ring();
    const bool overlap = geom::interiors_overlap({a, {}}, {b, {}});
    ASSERT_EQ(interiors_apart(a, b), !overlap) << n;
    // b lies in a when it leaves no interior outside it: in the frame with a as its hole.
    const Ring hole(a.rbegin(), a.rend());
    const bool in = !geom::interiors_overlap({b, {}}, {frame, {hole}});
    ASSERT_EQ(ring_in_polygon(b, {a, {}}), in) << n;
    // And within a polygon with a hole: the frame around b's region's complement.
    ASSERT_EQ(ring_in_polygon(b, {frame, {hole}}), !overlap) << n;
    apart += !overlap, within += in;
  }
  // Both answers came up often.
  EXPECT_GT(apart, 100);
  EXPECT_GT(within, 20);
}

// The exact tests the zoning map's proof places polygons with (validate.cpp, far_zoning).
TEST(RingSides, SegmentAgainstABoxAndWindingNumbers) {
  const geom::Box box{0, 0, 2, 2};
  EXPECT_TRUE(segment_meets_box({-1, 1}, {3, 1}, box));    // through it
  EXPECT_TRUE(segment_meets_box({2, 2}, {3, 5}, box));     // from a corner
  EXPECT_TRUE(segment_meets_box({-1, 3}, {3, -1}, box));   // a diagonal across it
  EXPECT_TRUE(segment_meets_box({0, 4}, {4, 0}, box));     // touching the corner (2, 2)
  EXPECT_FALSE(segment_meets_box({0, 4 + 1e-12}, {4, 0}, box));  // the boxes meet; the segment passes a hair beyond
  EXPECT_FALSE(segment_meets_box({3, -1}, {3, 5}, box));   // beside it
  EXPECT_TRUE(segment_meets_box({1, 1}, {1.5, 1.5}, box)); // inside

  const Ring a = square(0, 0, 4);
  EXPECT_EQ(exact_winding_number(a, {1, 1}), 1);
  EXPECT_EQ(exact_winding_number(a, {5, 1}), 0);
  EXPECT_EQ(exact_winding_number(a, {1, -1}), 0);
  EXPECT_EQ(exact_winding_number(Ring(a.rbegin(), a.rend()), {1, 1}), -1);
  Ring twice = a;
  twice.insert(twice.end(), a.begin(), a.end());
  EXPECT_EQ(exact_winding_number(twice, {2, 2}), 2);
  // At a vertex's height: counted once.
  EXPECT_EQ(exact_winding_number({{0, 0}, {4, 2}, {0, 4}}, {1, 2}), 1);
  EXPECT_EQ(exact_winding_number({{0, 0}, {4, 2}, {0, 4}}, {-1, 2}), 0);
  // A bow tie: one lobe each way.
  const Ring bow{{0, 0}, {4, 4}, {4, 0}, {0, 4}};
  EXPECT_EQ(exact_winding_number(bow, {1, 2}), 1);
  EXPECT_EQ(exact_winding_number(bow, {3, 2}), -1);
}

// The exact test the roads' proof meets segments with (validate.cpp, roads_meet_at_vertices).
TEST(RingSides, HowTwoSegmentsMeet) {
  using M = SegmentMeeting;
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {0, 1}, {4, 1}), M::Apart);      // parallel
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {4, 0}, {6, 3}), M::Apart);      // a shared end
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {4, 0}, {6, 0}), M::Apart);      // on one line, end to end
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {6, 0}, {4, 0}), M::Apart);
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {4, 0}, {0, 0}), M::Same);       // the same, either way
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {0, 0}, {4, 0}), M::Same);
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {2, -1}, {2, 1}), M::Otherwise);  // crossing
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {2, 0}, {2, 1}), M::Otherwise);   // an end inside the other
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {2, 0}, {6, 0}), M::Otherwise);   // along each other in part
  EXPECT_EQ(segment_meeting({0, 0}, {4, 0}, {0, 0}, {2, 0}), M::Otherwise);   // a shared end, and along
  EXPECT_EQ(segment_meeting({0, 0}, {4, 4}, {0, 4}, {2, 2 + 1e-12}), M::Apart);  // a hair short
  EXPECT_EQ(segment_meeting({0, 0}, {4, 4}, {0, 4}, {2, 2}), M::Otherwise);
  EXPECT_EQ(segment_meeting({0, 0}, {4, 4}, {0, 4}, {2, 2 - 1e-12}), M::Otherwise);  // a hair over
}

}  // namespace
}  // namespace exacity
