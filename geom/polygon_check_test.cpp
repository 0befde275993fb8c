// point_side: where a point lies against a ring or a polygon with holes, decided exactly on
// the doubles as written (what validate checks street clutter with).
#include <gtest/gtest.h>

#include "geom/polygon_check.h"
#include "geom/polygon_slabs.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

namespace geom {
namespace {

TEST(PointSide, InsideOnAndOutsideARingExactly) {
  const Ring square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  EXPECT_EQ(point_side(square, {5, 5}), 1);
  EXPECT_EQ(point_side(square, {10, 5}), 0);
  EXPECT_EQ(point_side(square, {0, 0}), 0);
  EXPECT_EQ(point_side(square, {-1e-300, 5}), -1);  // a hair outside the edge still counts
  EXPECT_EQ(point_side(square, {1e-300, 5}), 1);
  // Near a slanted edge: the doubles 0.1 and 0.3 are not a tenth and three tenths, and three
  // times the double 0.1 is a little more than the double 0.3, so (0.1, 0.3) lies just right
  // of the edge from the origin to (1, 3): outside.
  const Ring slanted{{0, 0}, {1, 3}, {-5, 3}};
  EXPECT_EQ(point_side(slanted, {0.1, 0.3}), -1);
  EXPECT_EQ(point_side(slanted, {0.5, 1.5}), 0);  // exactly on it
}

TEST(PointSide, AHoleIsOutsideItsPolygonAndItsEdgeOnTheBoundary) {
  const Polygon frame{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{3, 3}, {3, 7}, {7, 7}, {7, 3}}}};
  EXPECT_EQ(point_side(frame, {1, 1}), 1);
  EXPECT_EQ(point_side(frame, {5, 5}), -1);
  EXPECT_EQ(point_side(frame, {3, 5}), 0);
  EXPECT_EQ(point_side(frame, {11, 5}), -1);
}

// point_side skips, by comparing coordinates, the edges whose box does not hold the point:
// the same answers as CGAL::bounded_side_2 on random simple rings of a small grid (shared
// heights, upright and level edges, points on vertices and edges), and off it by a hair.
TEST(PointSide, AnswersAsCgalsBoundedSideOnRandomRings) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::mt19937 random(37);
  std::uniform_int_distribution<int> coordinate(0, 6), corners(3, 7);
  int rings = 0;
  while (rings < 300) {
    Ring ring;
    const int n = corners(random);
    for (int k = 0; k < n; ++k) ring.push_back({static_cast<double>(coordinate(random)), static_cast<double>(coordinate(random))});
    if (!ring_is_simple(ring)) continue;
    ++rings;
    std::vector<K::Point_2> points;
    for (Vec2 v : ring) points.emplace_back(v.x, v.y);
    for (int i = -1; i <= 13; ++i)
      for (int j = -1; j <= 13; ++j)
        for (double hair : {0.0, 1e-300, -1e-15}) {
          const Vec2 p{i / 2.0 + hair, j / 2.0 - hair};
          const CGAL::Bounded_side side = CGAL::bounded_side_2(points.begin(), points.end(), K::Point_2(p.x, p.y), K());
          const int expected = side == CGAL::ON_BOUNDARY ? 0 : side == CGAL::ON_BOUNDED_SIDE ? 1 : -1;
          // bounded_side_2 counts the region of a clockwise ring as bounded too.
          ASSERT_EQ(point_side(ring, p), expected) << "ring " << rings << " point (" << p.x << ", " << p.y << ")";
        }
  }
}

// ring_is_simple asks rings of up to 64 vertices pair of edges by pair, not by CGAL's sweep:
// the same answer on random rings of 3 to 16 vertices on a small grid (repeated vertices, edges
// folding back, touching and running along others), and with a corner moved by 1e-9 or
// 1e-300 off the grid (slivers, nearly collinear turns).
TEST(RingIsSimple, SmallRingsAnswerAsCgalsSweep) {
  std::mt19937 random(37);
  std::uniform_int_distribution<int> coordinate(0, 4), corners(3, 16);
  int simple = 0, not_simple = 0;
  for (int t = 0; t < 200000; ++t) {
    Ring ring;
    const int n = corners(random);
    for (int k = 0; k < n; ++k) ring.push_back({static_cast<double>(coordinate(random)), static_cast<double>(coordinate(random))});
    if (t % 3 == 1) ring[t % n].x += 1e-9;
    if (t % 3 == 2) ring[t % n].y -= 1e-300;
    const bool expected = cgal_ring_is_simple(ring);
    ASSERT_EQ(ring_is_simple(ring), expected) << "ring " << t;
    (expected ? simple : not_simple) += 1;
  }
  // Both answers were asked often (small rings on a 5 x 5 grid are mostly not simple).
  EXPECT_GT(simple, 1000);
  EXPECT_GT(not_simple, 1000);
  // Rings of up to 64 vertices around a centre, in the order of their angle (mostly simple;
  // vertices on one ray from the centre, repeated or nudged by 1e-9, make them not).
  simple = not_simple = 0;
  std::uniform_int_distribution<int> wide(0, 40), many(17, 70);
  for (int t = 0; t < 20000; ++t) {
    Ring ring;
    const int n = many(random);
    for (int k = 0; k < n; ++k) ring.push_back({static_cast<double>(wide(random)), static_cast<double>(wide(random))});
    std::sort(ring.begin(), ring.end(), [](Vec2 a, Vec2 b) {
      return std::atan2(a.y - 20.5, a.x - 20.5) < std::atan2(b.y - 20.5, b.x - 20.5);
    });
    if (t % 3 == 1) ring[t % n].x += 1e-9;
    const bool expected = cgal_ring_is_simple(ring);
    ASSERT_EQ(ring_is_simple(ring), expected) << "ring " << t << " of " << n;
    (expected ? simple : not_simple) += 1;
  }
  EXPECT_GT(simple, 1000);
  EXPECT_GT(not_simple, 1000);
}

// PolygonSlabs answers as point_side, whose edges it sorts by slabs of the box: random rings
// of many vertices on a grid (edges spanning slabs, ending on their lines, level ones), a
// hole, points on the grid, between and off the box.
TEST(PointSide, SlabsAnswerAsPointSide) {
  std::mt19937 random(37);
  std::uniform_real_distribution<double> angle(0, 6.283185307179586);
  for (int n : {5, 40, 300}) {
    // A star-shaped ring: vertices by angle, each at a random radius, on a grid of 0.25.
    std::vector<double> angles(n);
    for (double& a : angles) a = angle(random);
    std::sort(angles.begin(), angles.end());
    Ring outer;
    for (double a : angles) {
      const double r = 4 + std::uniform_int_distribution<int>(0, 16)(random) / 4.0;
      const Vec2 v{std::round(r * std::cos(a) * 4) / 4, std::round(r * std::sin(a) * 4) / 4};
      if (outer.empty() || !(outer.back() == v)) outer.push_back(v);
    }
    if (!ring_is_simple(outer)) continue;
    const Polygon polygon{outer, {{{-1, -1}, {-1, 1}, {1, 1}, {1, -1}}}};
    const PolygonSlabs slabs(polygon);
    for (int i = -40; i <= 40; ++i)
      for (int j = -40; j <= 40; ++j) {
        const Vec2 p{i / 4.0, j / 4.0 + (i % 3 == 0 ? 1e-13 : 0)};
        ASSERT_EQ(slabs.side(p), point_side(polygon, p)) << n << " vertices, (" << p.x << ", " << p.y << ")";
      }
  }
}

}  // namespace
}  // namespace geom
