// Exact road growth in cells: where a growing road stops, and how roads split a cell.
#include <gtest/gtest.h>

#include <cmath>

#include "generate/sketch/sketch.h"
#include "generate/layout/growth.h"
#include "geom/cell.h"
#include "geom/planar_map.h"
#include "tests/test_util.h"

using geom::Cell;
using geom::Growth;
using geom::Vec2;

namespace {

constexpr int kEdge = 0, kRoad = 1;

// The faces inside the outer ring and outside the holes as one cell, its edges of kind kEdge.
Cell cell_of(const geom::Ring& ring, const std::vector<geom::Ring>& holes = {}) {
  geom::PlanarMap map;
  map.add_ring(ring, 0);
  for (const geom::Ring& h : holes) map.add_ring(geom::Ring(h.rbegin(), h.rend()), 0);
  map.insert_batch();
  map.label_faces([](const geom::Windings& w) { return geom::winding_of(w, 0) != 0 ? 1 : 0; });
  auto cells = map.cells({-1, 0}, {kEdge, kEdge});
  EXPECT_EQ(cells.size(), 1u);
  return cells.at(0);
}

const geom::Ring kSquare{{0, 0}, {10, 0}, {10, 10}, {0, 10}};

// Every road of the plan but road i.
std::vector<geom::Path> other_roads(const exacity::RoadPlan& plan, std::size_t i) {
  std::vector<geom::Path> others;
  for (std::size_t j = 0; j < plan.roads.size(); ++j)
    if (j != i) others.push_back(plan.roads[j].path);
  return others;
}

}  // namespace

TEST(Growth, StopsExactlyAtTheEdgeItMeets) {
  Growth g(cell_of(kSquare), 1);
  g.begin({5, 5});
  EXPECT_EQ(g.extend({7, 6}), Growth::Met{});
  EXPECT_EQ(g.extend({13, 7.5}), (Growth::Met{Growth::Met::Edge, kEdge}));
  geom::Path road = g.end();
  ASSERT_EQ(road.size(), 3u);
  EXPECT_EQ(road.point(2), (Vec2{10, 6.75}));  // on x = 10, on the line through (7,6) and (13,7.5)
}

TEST(Growth, ReachingAnEdgeExactlyAtAVertex) {
  Growth g(cell_of(kSquare), 1);
  g.begin({5, 5});
  EXPECT_EQ(g.extend({20, 20}), (Growth::Met{Growth::Met::Edge, kEdge}));
  geom::Path road = g.end();
  EXPECT_EQ(road.point(1), (Vec2{10, 10}));
}

TEST(Growth, RunningOntoAnEdgeStopsWhereTheyFirstTouch) {
  // An L: from inside, a road along y = 5 reaches the reflex corner (5, 5) and would run on
  // along the edge (5,5)-(10,5).
  Growth g(cell_of({{0, 0}, {10, 0}, {10, 5}, {5, 5}, {5, 10}, {0, 10}}), 1);
  g.begin({1, 5});
  EXPECT_EQ(g.extend({20, 5}), (Growth::Met{Growth::Met::Edge, kEdge}));
  geom::Path road = g.end();
  ASSERT_EQ(road.size(), 2u);
  EXPECT_EQ(road.point(1), (Vec2{5, 5}));
}

TEST(Growth, LaterRoadsStopAtEarlierOnesAndAtTheirJunctions) {
  Growth g(cell_of(kSquare), 1);
  g.begin({5, 5});
  g.extend({50, 5});
  geom::Path east = g.end();
  g.begin({5, 5});
  g.extend({5, 50});
  geom::Path north = g.end();
  // Through the junction (5, 5) itself.
  g.begin({2, 2});
  EXPECT_EQ(g.extend({8, 8}), (Growth::Met{Growth::Met::OwnRoad, 0}));
  EXPECT_EQ(g.end().point(1), (Vec2{5, 5}));
  // Onto a road, running along it: stops where it first touches it.
  g.begin({1, 5});
  EXPECT_EQ(g.extend({9, 5}), (Growth::Met{Growth::Met::OwnRoad, 0}));
  EXPECT_EQ(g.end().point(1), (Vec2{5, 5}));
  // Its own earlier segment stops it too.
  g.begin({8, 2});
  EXPECT_EQ(g.extend({9, 3}), Growth::Met{});
  EXPECT_EQ(g.extend({7, 3}), Growth::Met{});
  EXPECT_EQ(g.extend({9, 1.5}), (Growth::Met{Growth::Met::OwnRoad, 0}));
  EXPECT_EQ(east.point(1), (Vec2{10, 5}));
  EXPECT_EQ(north.point(1), (Vec2{5, 10}));
}

TEST(Growth, SplitCellGivesExactPartsWithRoadEdges) {
  Cell square = cell_of(kSquare);
  Growth g(square, 1);
  std::vector<geom::Path> roads;
  for (Vec2 far : {Vec2{50, 5}, Vec2{5, 50}, Vec2{-50, 5}, Vec2{5, -50}}) {
    g.begin({5, 5});
    g.extend(far);
    roads.push_back(g.end());
  }
  auto parts = geom::split_cell(square, roads, kRoad);
  ASSERT_EQ(parts.size(), 4u);
  for (const Cell& c : parts) {
    EXPECT_EQ(c.area(), 25);
    EXPECT_EQ(c.edges_of_kind(kRoad).size(), 2u);
    EXPECT_EQ(c.edges_of_kind(kEdge).size(), 2u);
  }
  // A part of a part: a road across it, both ways from inside, splits it exactly again.
  Growth again(parts[0], 1);
  Vec2 inside = *parts[0].point_inside_near(parts[0].centroid());
  std::vector<geom::Path> across;
  for (double dx : {100.0, -100.0}) {
    again.begin(inside);
    again.extend({inside.x + dx, inside.y + dx / 100});
    across.push_back(again.end());
  }
  auto quarter = geom::split_cell(parts[0], across, kRoad);
  ASSERT_EQ(quarter.size(), 2u);
  EXPECT_EQ(quarter[0].area() + quarter[1].area(), 25);
}

TEST(Growth, PointInsideNearFindsTheInsideOfANonConvexCell) {
  // A C shape whose centroid falls in the gap.
  Cell c = cell_of({{0, 0}, {10, 0}, {10, 2}, {2, 2}, {2, 8}, {10, 8}, {10, 10}, {0, 10}});
  Vec2 centre = c.centroid();
  EXPECT_FALSE(c.contains(centre));
  auto p = c.point_inside_near(centre);
  ASSERT_TRUE(p.has_value());
  EXPECT_TRUE(c.contains(*p));
  EXPECT_LT(std::hypot(p->x - centre.x, p->y - centre.y), 4);
}

TEST(Growth, StraightPathsAreExactlyStraight) {
  Growth g(cell_of(kSquare), 1);
  g.begin({0.1, 0.3});
  g.extend({1000.7, 300.9});
  EXPECT_TRUE(g.end().is_straight());
  g.begin({3, 3});
  g.extend({4, 4});
  g.extend({5, 4});
  EXPECT_FALSE(g.end().is_straight());
}

TEST(Inset, SquareAndLShapeLoseExactlyTheirSetbackBands) {
  auto square = geom::inset_cell(cell_of(kSquare), 2);
  ASSERT_EQ(square.size(), 1u);
  EXPECT_EQ(square[0].area(), 36);
  EXPECT_EQ(square[0].bounds().min_x, 2);
  EXPECT_EQ(square[0].bounds().max_y, 8);
  // An L of arms 4 wide: inset by 1, two 8 x 2 arms sharing a 2 x 2 corner.
  auto l = geom::inset_cell(cell_of({{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}}), 1);
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].area(), 28);
  EXPECT_TRUE(l[0].contains({2.5, 8.5}));
  EXPECT_FALSE(l[0].contains({3.5, 3.5}));
  // Too thin for its setback: nothing is left.
  EXPECT_TRUE(geom::inset_cell(cell_of({{0, 0}, {10, 0}, {10, 3}, {0, 3}}), 2).empty());
}

TEST(ExtendTo, ARoadStoppedAtASurfaceRunsOnAlongItsLineToTheCentreLine) {
  // A road from (0, -30) heading up and to the right stopped at y = -10, the side of a
  // road whose centre line is y = 0: it runs on, on its own line, to meet y = 0 exactly.
  auto road = geom::Path::from({{0, -30}, {4, -10}});
  auto centre = geom::Path::from({{-100, 0}, {100, 0}});
  auto extended = geom::extend_to(road, {centre}, 40);
  ASSERT_EQ(extended.size(), 3u);
  EXPECT_EQ(extended.point(2), (Vec2{6, 0}));
  EXPECT_TRUE(extended.is_straight());
}

TEST(ExtendTo, ARoadPastTheEndOfACentreLineJoinsItsEnd) {
  // The centre line ends at x = 0; the road's line passes beyond that end, so the road
  // joins the end instead. Out of reach, it is left as it is.
  auto road = geom::Path::from({{10, -30}, {10, -10}});
  auto centre = geom::Path::from({{-100, 0}, {0, 0}});
  auto extended = geom::extend_to(road, {centre}, 40);
  ASSERT_EQ(extended.size(), 3u);
  EXPECT_EQ(extended.point(2), (Vec2{0, 0}));
  EXPECT_EQ(geom::extend_to(road, {centre}, 5).size(), 2u);
}

TEST(ShortestLink, JoinsTheNearestVertexToItsNearestPointOnTheOtherSet) {
  // The vertex (0, 2) of `from` is 2^0.5 from the slanted segment, whose nearest point
  // (1, 1) lies inside it; the link runs from `from` to `to`.
  auto from = geom::Path::from({{-10, 2}, {0, 2}});
  auto to = geom::Path::from({{0, 0}, {4, 4}});
  auto far = geom::Path::from({{50, 50}, {60, 50}});
  auto link = geom::shortest_link({from}, {far, to});
  ASSERT_TRUE(link);
  ASSERT_EQ(link->path.size(), 2u);
  EXPECT_EQ(link->path.point(0), (Vec2{0, 2}));
  EXPECT_EQ(link->path.point(1), (Vec2{1, 1}));
  EXPECT_DOUBLE_EQ(link->length, std::sqrt(2.0));
  // The same pair the other way round: the nearest vertex is now on the `from` side's
  // other set, and the link still starts on `from`.
  auto back = geom::shortest_link({far, to}, {from});
  EXPECT_EQ(back->path.point(0), (Vec2{1, 1}));
  EXPECT_EQ(back->path.point(1), (Vec2{0, 2}));
  // Past a segment's end the link goes to that end.
  auto beyond = geom::shortest_link({geom::Path::from({{-3, -4}, {-3, -9}})}, {to});
  EXPECT_EQ(beyond->path.point(1), (Vec2{0, 0}));
  EXPECT_DOUBLE_EQ(beyond->length, 5);
  // Sets that meet need no link; an empty set has none.
  auto meeting = geom::shortest_link({geom::Path::from({{2, 2}, {2, 9}})}, {to});
  ASSERT_TRUE(meeting);
  EXPECT_TRUE(meeting->path.empty());
  EXPECT_EQ(meeting->length, 0);
  EXPECT_FALSE(geom::shortest_link({}, {to}));
}

TEST(ExtendTo, ARoadMeetingASurfaceAtAShallowAngleTurnsToTheCentreLine) {
  // The road's line meets y = 0 only 300 m on, beyond reach: it turns to the centre line's
  // nearest point instead of ending on the surface, where no road would meet it.
  auto road = geom::Path::from({{-50, -3.5}, {0, -3}});
  auto centre = geom::Path::from({{-100, 0}, {100, 0}});
  auto extended = geom::extend_to(road, {centre}, 24);
  ASSERT_EQ(extended.size(), 3u);
  EXPECT_EQ(extended.point(2), (Vec2{0, 0}));
}

// A cell cut from a larger one along a road's centre line (as a grammar's piece is) has that
// line as its edge: a grown road reaching it is on the line already, and must not run on to
// the next line ahead, across the neighbouring land.
TEST(GrowthLayout, ARoadMeetingACentreLineEdgeStopsOnIt) {
  using namespace exacity;
  Sketch sketch;
  sketch.zone_settings[ZoneType::Residential] = default_zone_settings(ZoneType::Residential);
  const Cell whole = cell_of({{0, 0}, {600, 0}, {600, 300}, {0, 300}});
  const geom::Path centre = geom::Path::from({{300, -1}, {300, 301}}), next = geom::Path::from({{320, -1}, {320, 301}});
  SketchLines lines{{{centre, next}, 12}};
  std::vector<Cell> halves = geom::split_cell(whole, {centre}, GrowthEdge::sketch_road(0));
  ASSERT_EQ(halves.size(), 2u);
  const Cell& west = halves[0].centroid().x < 300 ? halves[0] : halves[1];
  const auto layout = make_growth_layout(sketch, lines, [](Vec2) { return std::optional<ZoneType>(ZoneType::Residential); });
  const RoadPlan plan = layout->plan({west, 7});
  int on_centre = 0;
  for (const LaidRoad& r : plan.roads) {
    for (Vec2 v : r.path.to_plain()) EXPECT_LE(v.x, 300) << "a road crosses the centre line";
    on_centre += geom::ends_on(r.path, {centre});
  }
  EXPECT_GT(on_centre, 0) << "no road reached the centre line: the test saw nothing";
  EXPECT_EQ(plan.piece_reaches_sketch, std::vector<char>{1});
}

// A road surface is tagged with one sketch road, but the centre line beyond it may be
// another's: a junction's surface names the first road that meets there (docs/design.md,
// Ids), and a mitred junction between two streets of unlike widths meeting almost straight
// on runs a long way down the narrower one (Kotka's Muuralankuja, 200 m from the street it
// names). Here the region's east edge is tagged road 0, whose line is 700 m off, while road
// 1's line runs 4 m beyond it. A road reaching that edge must run on to road 1's line; left
// on the edge it would end in the open, and its piece reach no sketch road.
TEST(GrowthLayout, ARoadMeetingASurfaceNamedForAFarRoadRunsOnToTheNearestCentreLine) {
  using namespace exacity;
  Sketch sketch;
  sketch.zone_settings[ZoneType::Residential] = default_zone_settings(ZoneType::Residential);
  const Cell whole = cell_of({{0, 0}, {600, 0}, {600, 300}, {0, 300}});
  const geom::Path surface = geom::Path::from({{300, -1}, {300, 301}});
  const geom::Path named = geom::Path::from({{1000, -1}, {1000, 301}}), near = geom::Path::from({{304, -1}, {304, 301}});
  SketchLines lines{{{named}, 8}, {{near}, 7}};
  std::vector<Cell> halves = geom::split_cell(whole, {surface}, GrowthEdge::sketch_road(0));
  ASSERT_EQ(halves.size(), 2u);
  const Cell& west = halves[0].centroid().x < 300 ? halves[0] : halves[1];
  const auto layout = make_growth_layout(sketch, lines, [](Vec2) { return std::optional<ZoneType>(ZoneType::Residential); });
  const RoadPlan plan = layout->plan({west, 7});
  ASSERT_GT(plan.roads.size(), 1u);
  int on_near = 0;
  for (std::size_t i = 0; i < plan.roads.size(); ++i) {
    // Each road grows from its cell's seed, which its sibling roads share; where it stopped
    // is its last point.
    const geom::Path& road = plan.roads[i].path;
    const std::vector<geom::Path> others = other_roads(plan, i);
    const Vec2 end = road.point(road.size() - 1);
    const bool on_region_edge = end.x == 0 || end.y == 0 || end.y == 300;
    on_near += geom::ends_on(road, {near});
    EXPECT_TRUE(on_region_edge || geom::ends_on(road, {near}) || geom::ends_on(road, others))
        << "road " << i << " ends in the open at (" << end.x << ", " << end.y << ")";
  }
  EXPECT_GT(on_near, 0) << "no road reached the surface: the test saw nothing";
  EXPECT_EQ(plan.piece_reaches_sketch, std::vector<char>{1});

  // With no centre line in reach at all, no road may stop on that edge: the region's roads
  // can reach no sketch road, so it gets none.
  SketchLines far_only{{{named}, 8}};
  const auto stranded = make_growth_layout(sketch, far_only, [](Vec2) { return std::optional<ZoneType>(ZoneType::Residential); });
  const RoadPlan none = stranded->plan({west, 7});
  EXPECT_TRUE(none.roads.empty()) << none.roads.size() << " roads, one ending at (" << none.roads[0].path.point(1).x << ", "
                                  << none.roads[0].path.point(1).y << ")";
  EXPECT_EQ(none.piece_reaches_sketch, std::vector<char>{0});
}

namespace {

geom::Ring circle(double r, int n) {
  geom::Ring out;
  for (int i = 0; i < n; ++i) out.push_back({r * std::cos(2 * M_PI * i / n), r * std::sin(2 * M_PI * i / n)});
  return out;
}

double length_of(const geom::Polyline& line) {
  double length = 0;
  for (std::size_t i = 1; i < line.size(); ++i) length += geom::distance(line[i - 1], line[i]);
  return length;
}

}  // namespace

// Narrow zones: a cell grown again from beside its road edge, or a seed the zone's narrow
// arm or ring left against an edge, started its roads a centimetre inside the boundary, and
// the branches out to it were stubs of centimetres (a 60 m residential L: roads of 2 to
// 40 cm). Every grown road is at least the zone's min_block_width long, starts at a junction
// of its seed and ends on the region's edge or another road: no stub, no dead end.
TEST(GrowthLayout, NoRoadIsShorterThanABlockIsWideNorEndsInTheOpen) {
  using namespace exacity;
  Sketch sketch;
  sketch.zone_settings[ZoneType::Residential] = default_zone_settings(ZoneType::Residential);
  const double least = sketch.zone_settings[ZoneType::Residential].blocks.min_block_width;
  std::vector<Vec2> spiral, outer_side;
  for (int k = 0; k < 120; ++k) {
    const double a = k * 0.06, r = 120 + a * 50;
    spiral.push_back({r * std::cos(a), r * std::sin(a)});
    outer_side.push_back({(r + 40) * std::cos(a), (r + 40) * std::sin(a)});
  }
  spiral.insert(spiral.end(), outer_side.rbegin(), outer_side.rend());
  const std::vector<std::pair<const char*, Cell>> zones{
      {"60 m L", cell_of({{700, 700}, {3000, 700}, {3000, 760}, {760, 760}, {760, 2500}, {700, 2500}})},
      {"20 m L", cell_of({{0, 0}, {1200, 0}, {1200, 20}, {20, 20}, {20, 900}, {0, 900}})},
      {"30 m ring", cell_of(circle(800, 64), {circle(770, 64)})},
      {"40 m spiral", cell_of(spiral)},
  };
  const auto layout = make_growth_layout(sketch, {}, [](Vec2) { return std::optional<ZoneType>(ZoneType::Residential); });
  for (const auto& [name, cell] : zones) {
    std::vector<geom::Path> boundary;
    for (const geom::KindedRing& r : cell.kinded_rings()) {
      geom::Polyline closed(r.points.begin(), r.points.end());
      closed.push_back(r.points.front());
      boundary.push_back(geom::Path::from(closed));
    }
    for (std::uint64_t stream : {1, 2, 3, 4}) {
      SCOPED_TRACE(std::string(name) + ", stream " + std::to_string(stream));
      const RoadPlan plan = layout->plan({cell, stream});
      ASSERT_GT(plan.roads.size(), 2u);
      for (std::size_t i = 0; i < plan.roads.size(); ++i) {
        const geom::Path& road = plan.roads[i].path;
        const std::vector<geom::Path> others = other_roads(plan, i);
        const Vec2 end = road.point(road.size() - 1);
        EXPECT_GE(length_of(road.to_plain()), least) << "road " << i << " ends at (" << end.x << ", " << end.y << ")";
        EXPECT_TRUE(geom::ends_on(road.reversed(), others)) << "road " << i << " starts alone";
        EXPECT_TRUE(geom::ends_on(road, boundary) || geom::ends_on(road, others))
            << "road " << i << " ends in the open at (" << end.x << ", " << end.y << ")";
      }
    }
  }
}
