// Rounding the exact map to doubles: nearest rounding, snap rounding (no rounded edges
// cross), and untangling the rings rounding collapsed; and the snapped float build's noder.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include "geom/cell.h"
#include "geom/exact.h"
#include "geom/measure.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"
#include "geom/snap_noding.h"
#include "geom/untangle.h"
#include "tests/test_util.h"

using geom::Polygon;
using geom::Ring;
using geom::Vec2;

namespace {

using E = CGAL::Exact_predicates_exact_constructions_kernel;

// Two rounded edges meet only at an end both share, or are the same edge; no vertex (an
// edge's end, or an edge rounding collapsed to a point) lies inside another edge.
std::string crossing(const std::vector<std::pair<Vec2, Vec2>>& edges) {
  auto segment = [](Vec2 a, Vec2 b) { return E::Segment_2(E::Point_2(a.x, a.y), E::Point_2(b.x, b.y)); };
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = 0; j < edges.size(); ++j) {
      auto [a, b] = edges[i];
      auto [c, d] = edges[j];
      if (i == j || (a == c && b == d) || (a == d && b == c) || c == d) continue;
      const E::Segment_2 t = segment(c, d);
      if (a == b) {
        if (!(a == c) && !(a == d) && t.has_on(E::Point_2(a.x, a.y))) return "a collapsed edge lies inside edge " + std::to_string(j);
        continue;
      }
      if (j < i) continue;
      auto meet = CGAL::intersection(segment(a, b), t);
      if (!meet) continue;
      const E::Point_2* p = boost::get<E::Point_2>(&*meet);
      auto shared_end = [&](Vec2 v) { return (v == c || v == d) && *p == E::Point_2(v.x, v.y); };
      if (p && (shared_end(a) || shared_end(b))) continue;
      return "edges " + std::to_string(i) + " and " + std::to_string(j) + " meet off a shared end";
    }
  return "";
}

// Rings and polylines near degeneracy, far from the origin and turned: vertices shared,
// a few ulps apart, or on (or next to) an edge drawn before.
geom::PlanarMap near_degenerate_map(std::mt19937_64& rng, Vec2 origin, double angle) {
  std::uniform_real_distribution<double> coord(0, 300), unit(0, 1);
  std::uniform_int_distribution<int> how(0, 3), ulps(-3, 3);
  std::vector<Vec2> seen;
  auto nudge = [&](double v) {
    for (int k = ulps(rng); k != 0; k += k > 0 ? -1 : 1) v = std::nextafter(v, k > 0 ? INFINITY : -INFINITY);
    return v;
  };
  auto vertex = [&]() {
    Vec2 p{coord(rng), coord(rng)};
    const int h = how(rng);
    if (h > 0 && seen.size() >= 2) {
      Vec2 a = seen[rng() % seen.size()], b = seen[rng() % seen.size()];
      const double t = h == 1 ? 0 : unit(rng);
      p = {nudge(a.x + t * (b.x - a.x)), nudge(a.y + t * (b.y - a.y))};
    }
    seen.push_back(p);
    const double c = std::cos(angle), s = std::sin(angle);
    return Vec2{origin.x + c * p.x - s * p.y, origin.y + s * p.x + c * p.y};
  };
  geom::PlanarMap map;
  for (int r = 0; r < 4; ++r) {
    Ring ring;
    for (int i = 0; i < 3 + r; ++i) ring.push_back(vertex());
    map.add_ring(ring, r);
  }
  for (int l = 0; l < 2; ++l) map.add_polyline({vertex(), vertex(), vertex()}, 10 + l);
  map.insert_batch();
  return map;
}

std::vector<std::pair<Vec2, Vec2>> rounded_edges(const geom::PlanarMap& map) {
  std::vector<std::pair<Vec2, Vec2>> edges;
  map.for_each_edge([&](const std::vector<geom::CurveTag>&, Vec2 a, Vec2 b) { edges.push_back({a, b}); });
  return edges;
}

}  // namespace

TEST(Rounding, ToTheNearestDoubleTiesToEven) {
  using Q = std::decay_t<decltype(CGAL::exact(geom::exact::FT(0)))>;
  std::mt19937_64 rng(7);
  for (double base : {0.3, 131.13, 70.71067811865478, -3.5e6, 1e9, -7e9}) {
    const double up = std::nextafter(base, INFINITY);
    for (int k = 0; k <= 16; ++k) {
      const Q v = Q(base) + (Q(up) - Q(base)) * Q(k) / Q(16);  // k/16 of the way to the next double
      const bool base_is_even = (std::bit_cast<std::uint64_t>(base) & 1) == 0;  // a tie goes to the even one
      const double nearest = k < 8 ? base : k > 8 ? up : base_is_even ? base : up;
      EXPECT_EQ(geom::exact::nearest_double(v), nearest) << base << " + " << k << "/16 of a step";
    }
  }
  // Rationals of every size, subnormals included, and ties between two doubles: the same
  // double as comparing with the halfway rational between the two around.
  std::uniform_int_distribution<int> exponent(-1130, 960);
  std::uniform_int_distribution<long> numerator(-(1L << 60), 1L << 60), denominator(1, (1L << 40) - 1);
  for (int i = 0; i < 20000; ++i) {
    const int e = exponent(rng);
    const Q scale = Q(std::ldexp(1.0, e / 2)) * Q(std::ldexp(1.0, e - e / 2));
    Q v = Q(static_cast<double>(numerator(rng))) / Q(static_cast<double>(denominator(rng))) * scale;
    if (i % 4 == 0) {  // halfway between a double and the next
      const double d = geom::exact::nearest_double_by_halfway(v);
      v = (Q(d) + Q(std::nextafter(d, INFINITY))) / 2;
    }
    EXPECT_EQ(geom::exact::nearest_double(v), geom::exact::nearest_double_by_halfway(v)) << v;
  }
  EXPECT_EQ(geom::exact::nearest_double(Q(Q(std::numeric_limits<double>::denorm_min()) / 2)), 0.0);
  EXPECT_EQ(geom::exact::nearest_double(Q(Q(std::numeric_limits<double>::denorm_min()) * 3 / 2)),
            2 * std::numeric_limits<double>::denorm_min());
}

// An exact zero has no sign: a point made from -0.0 (or read from text that says "-0",
// as a plan's tasks write the lots they planned) rounds and writes as one made from +0.0,
// so a cell's text, which seeds its lot's buildings, follows its value, not its making.
// (examples/voronoi.geojson's plan merged to other buildings on two lots with a corner at
// y = 0 than generate built.)
TEST(Rounding, ZeroRoundsUnsignedHoweverThePointWasMade) {
  const Vec2 minus = geom::exact::to_plain(geom::exact::Point(-0.0, 2.0));
  EXPECT_FALSE(std::signbit(minus.x));
  EXPECT_FALSE(std::signbit(geom::exact::to_plain(geom::exact::Point(2.0, -0.0)).y));
  const std::string plus_text = "ring 4 0x0p+0 0x0p+0 1 0x1p+3 0x0p+0 2 0x1p+3 0x1p+2 2 0x0p+0 0x1p+2 2 ";
  std::string minus_text = plus_text;
  minus_text.replace(minus_text.find(" 0x0p+0 1"), 9, " -0x0p+0 1");
  const geom::Cell plus = geom::cell_from_exact_text(plus_text), made_minus = geom::cell_from_exact_text(minus_text);
  EXPECT_EQ(geom::exact_text(plus), plus_text);
  EXPECT_EQ(geom::exact_text(made_minus), plus_text);
  ASSERT_TRUE(made_minus.as_written());
  EXPECT_EQ(geom::exact_text(*made_minus.as_written()), plus_text);
  for (const Vec2 v : made_minus.to_plain().outer) EXPECT_FALSE(std::signbit(v.x) || std::signbit(v.y));
}

// The sanitizers make each trial about five times as slow: they run a quarter of them, every
// origin and angle still met.
#ifdef __SANITIZE_ADDRESS__
constexpr int kSnapTrials = 60;
#else
constexpr int kSnapTrials = 240;
#endif
TEST(Rounding, SnapRoundedEdgesNeverCross) {
  // Without snap rounding these maps round into crossing edges; with it, none does.
  std::mt19937_64 rng(20261123);
  int crossed_without = 0, vertices_added = 0;
  const Vec2 origins[] = {{1e5, 0}, {1e9, 3.5e6}, {-7e9, 1e9}, {0, 0}};
  const double angles[] = {M_PI / 4, M_PI / 6, 1e-9};
  for (int trial = 0; trial < kSnapTrials; ++trial) {
    const Vec2 origin = origins[trial % 4];
    const double angle = angles[trial % 3];
    std::mt19937_64 again = rng;
    geom::PlanarMap plain = near_degenerate_map(rng, origin, angle);
    crossed_without += !crossing(rounded_edges(plain)).empty();
    geom::PlanarMap snapped = near_degenerate_map(again, origin, angle);
    vertices_added += static_cast<int>(snapped.snap_round());
    EXPECT_EQ(crossing(rounded_edges(snapped)), "") << "trial " << trial;
  }
  EXPECT_GT(crossed_without, 0) << "the maps are not near enough to degeneracy to test anything";
  EXPECT_GT(vertices_added, 0);
}

TEST(Rounding, SnapRoundingLeavesAMapOfDoublesAlone) {
  geom::PlanarMap map;
  map.add_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, 0);
  map.add_ring({{5, 5}, {15, 5}, {15, 15}, {5, 15}}, 1);
  map.insert_batch();
  const auto before = map.counts();
  EXPECT_EQ(map.snap_round(), 0u);
  EXPECT_EQ(map.counts().vertices, before.vertices);
}

TEST(Rounding, ASliverThatRoundsToASpikeLeavesTheCellAsWritten) {
  // A wedge 1e-13 m wide 1,000 m down reaches into a square from below: it crosses the
  // square's bottom edge at two points a quarter of a double's step either side of (5, 0),
  // which both round to it. The square less the wedge then rounds to a ring that runs up
  // to the wedge's tip and straight back (in Helsinki's centre, a lot of 10,830 m² lost).
  geom::PlanarMap map;
  map.add_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, 0);
  map.add_ring({{5 - 5e-14, -1000}, {5 + 5e-14, -1000}, {5, 5}}, 1);
  map.insert_batch();
  map.snap_round();
  map.label_faces([](const geom::Windings& w) { return geom::winding_of(w, 0) == 0 ? -1 : geom::winding_of(w, 1) == 0 ? 0 : 1; });
  const std::vector<geom::Cell> cells = map.cells({0, -1}, {0, 7});  // the wedge's edges of kind 7
  ASSERT_EQ(cells.size(), 1u);
  ASSERT_TRUE(geom::vertex_repeats({cells[0].kinded_rings()[0].points})) << "the exact ring should round to a spike";
  const std::optional<geom::Cell> written = cells[0].as_written();
  ASSERT_TRUE(written);
  const std::vector<geom::KindedRing> rings = written->kinded_rings();
  ASSERT_EQ(rings.size(), 1u);
  EXPECT_FALSE(geom::vertex_repeats({rings[0].points}));
  EXPECT_EQ(std::count(rings[0].points.begin(), rings[0].points.end(), Vec2{5, 5}), 0);
  EXPECT_EQ(written->area(), 100);
  EXPECT_EQ(geom::area(written->to_plain()), 100);
  EXPECT_EQ(rings[0].kinds, std::vector<int>(rings[0].points.size(), 0));  // the square's own edges are left
}

TEST(Rounding, AMapTracedBeforeABatchTracesAfterItAsOneNeverTraced) {
  // A map keeps its vertices' roundings across tracings (cells, dissolve) until its edges
  // change; a tracing after a later batch and snap rounding must round the vertices the map
  // has then, as a map built the same way and traced once does.
  auto add_first = [](geom::PlanarMap& map) {
    map.add_ring({{0, 0}, {10, 0.1}, {10.3, 10}, {0.2, 9.7}}, 0);
    map.add_ring({{5.1, -3}, {13, 4.3}, {6.7, 12.9}}, 1);
  };
  auto add_second = [](geom::PlanarMap& map) { map.add_ring({{-2, 4.9}, {14.1, 3.3}, {12, 6.1}, {-1.3, 7.7}}, 2); };
  auto label = [](geom::PlanarMap& map) {
    map.label_faces([](const geom::Windings& w) { return geom::winding_of(w, 0) == 0 ? -1 : geom::winding_of(w, 1) == 0 ? 0 : 1; });
  };
  auto traced = [](const geom::PlanarMap& map) {  // every ring, outer then holes
    std::vector<Ring> out;
    auto add = [&](const Polygon& p) {
      out.push_back(p.outer);
      out.insert(out.end(), p.holes.begin(), p.holes.end());
    };
    for (const geom::Cell& c : map.cells({0, 1}, {0, 0})) add(c.to_plain());
    for (const auto& group : map.dissolve({0, 0}, 1))
      for (const geom::Dissolved& d : group) add(d.polygon);
    return out;
  };
  geom::PlanarMap twice, once;
  add_first(twice);
  twice.insert_batch();
  label(twice);
  const std::vector<Ring> before = traced(twice);
  add_second(twice);
  twice.insert_batch();
  twice.snap_round();
  label(twice);
  add_first(once);
  once.insert_batch();
  add_second(once);
  once.insert_batch();
  once.snap_round();
  label(once);
  const std::vector<Ring> after = traced(twice);
  EXPECT_NE(after, before);  // the second ring cut the faces: new vertices, off the grid
  EXPECT_EQ(after, traced(once));
}

TEST(Untangle, RingsWithoutRepeatsComeBackUnchanged) {
  const Ring outer{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, hole{{2, 2}, {2, 8}, {8, 8}, {8, 2}};
  auto out = geom::untangle({outer, hole});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].outer, outer);
  ASSERT_EQ(out[0].holes.size(), 1u);
  EXPECT_EQ(out[0].holes[0], hole);
}

TEST(Untangle, APinchedRingBecomesTwoPolygons) {
  auto out = geom::untangle({{{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}}});
  ASSERT_EQ(out.size(), 2u);
  for (const Polygon& p : out) {
    EXPECT_EQ(geom::ring_orientation(p.outer), 1);
    EXPECT_EQ(testing_util::area(p), 1);
  }
}

TEST(Untangle, AnEdgeRunBothWaysCancels) {
  auto out = geom::untangle({{{0, 0}, {4, 0}, {4, 4}, {2, 4}, {2, 6}, {2, 4}, {0, 4}}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(geom::ring_orientation(out[0].outer), 1);
  EXPECT_EQ(out[0].outer.size(), 5u);  // (2, 4) stays: a vertex on a straight edge
  EXPECT_EQ(testing_util::area(out[0]), 16);
}

TEST(Untangle, AHoleThatCameToShareAnEdgeWithTheOuterRingOpensIt) {
  // The outer ring carries the hole's corners (snap rounding put them there).
  auto out = geom::untangle({{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 8}, {0, 2}}, {{0, 2}, {0, 8}, {5, 8}, {5, 2}}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].holes.empty());
  EXPECT_EQ(geom::ring_orientation(out[0].outer), 1);
  EXPECT_EQ(testing_util::area(out[0]), 70);
}

TEST(Untangle, AHoleTouchingTheOuterRingAtAVertexStaysAHole) {
  auto out = geom::untangle({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{0, 0}, {5, 8}, {8, 5}}});
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].holes.size(), 1u);
  EXPECT_EQ(geom::ring_orientation(out[0].holes[0]), -1);
  EXPECT_EQ(testing_util::area(out[0]), 100 - 19.5);
}

TEST(Untangle, ARingThatCollapsedToALineIsGone) {
  EXPECT_TRUE(geom::untangle({{{0, 0}, {1, 1}, {2, 2}, {1, 1}}}).empty());
}

// The practitioner float build's noder (geom/snap_noding.h), in doubles on a grid of 1/8.
TEST(SnapNoding, CrossingSegmentsMeetAtTheirCrossingsPixel) {
  const double step = 0.125;
  const std::vector<geom::Polyline> lines =
      geom::snap_round_segments({{{0, 0}, {10, 1}}, {{3, -5}, {3.01, 5}}}, step);
  ASSERT_EQ(lines.size(), 2u);
  // They cross near (3.0, 0.3); both run through the centre of that pixel.
  const geom::Vec2 meet{3.0, 0.25};
  EXPECT_EQ(lines[0], (geom::Polyline{{0, 0}, meet, {10, 1}}));
  EXPECT_EQ(lines[1], (geom::Polyline{{3, -5}, meet, {3, 5}}));
}

TEST(SnapNoding, AnEndASegmentPassesNearBecomesItsVertex) {
  const double step = 0.125;
  // The second segment ends a hair off the first, as a road's computed end lands beside
  // the edge it stopped at; the first is split there, the ends snapped to the grid.
  const std::vector<geom::Polyline> lines =
      geom::snap_round_segments({{{0, 0}, {8, 0}}, {{4.01, 3}, {4.01, 0.03}}, {{1, 1}, {1, 1.01}}}, step);
  EXPECT_EQ(lines[0], (geom::Polyline{{0, 0}, {4, 0}, {8, 0}}));
  EXPECT_EQ(lines[1], (geom::Polyline{{4, 3}, {4, 0}}));
  EXPECT_TRUE(lines[2].empty());  // snapped to one point
}

TEST(SnapNoding, SegmentsPassingBesideAnotherPixelStayWhole) {
  const double step = 0.125;
  // Three steps apart: past the reach within which an end is moved onto a segment.
  const std::vector<geom::Polyline> lines = geom::snap_round_segments({{{0, 0}, {8, 0}}, {{4, 1}, {4, 0.375}}}, step);
  EXPECT_EQ(lines[0], (geom::Polyline{{0, 0}, {8, 0}}));
  EXPECT_EQ(lines[1], (geom::Polyline{{4, 1}, {4, 0.375}}));
}

TEST(SnapNoding, ASegmentTwoPixelsBesideAnEndIsRoutedThroughIt) {
  const double step = 0.125;
  // A road computed to stop at an edge, against a version of it routed through other hot
  // pixels, lands two pixels beside this one: the edge is split at the road's end. An end
  // as near the edge's own end is not taken: two ends are apart there.
  const std::vector<geom::Polyline> lines =
      geom::snap_round_segments({{{0, 0}, {8, 0}}, {{4, 3}, {4, 0.25}}, {{8.25, 1}, {8.25, 0.25}}}, step);
  EXPECT_EQ(lines[0], (geom::Polyline{{0, 0}, {4, 0.25}, {8, 0}}));
  EXPECT_EQ(lines[1], (geom::Polyline{{4, 3}, {4, 0.25}}));
  EXPECT_EQ(lines[2], (geom::Polyline{{8.25, 1}, {8.25, 0.25}}));
}

TEST(SnapNoding, AnEndAPixelPastACrossingIsTheCrossing) {
  const double step = 0.125;
  // The second segment stops a pixel past the first, as a road computed to stop at another
  // lands after snapping: the first is routed through its end, with no tail beyond it.
  const std::vector<geom::Polyline> lines =
      geom::snap_round_segments({{{0, 0}, {8, 0}}, {{4, 3}, {4, -0.125}}}, step);
  EXPECT_EQ(lines[0], (geom::Polyline{{0, 0}, {4, -0.125}, {8, 0}}));
  EXPECT_EQ(lines[1], (geom::Polyline{{4, 3}, {4, -0.125}}));
}

TEST(SnapNoding, AnEndNearAnArrangementVertexMovesOntoIt) {
  const double step = 0.125;
  // The first segment is an edge the arrangement has (monotone); the second starts two
  // pixels from its end, as a road computed from where an earlier batch's road stopped.
  const std::vector<geom::Polyline> lines =
      geom::snap_round_segments({{{0, 0}, {4, 0}}, {{4.25, 0.125}, {4.25, 3}}}, step, {true, false});
  EXPECT_EQ(lines[0], (geom::Polyline{{0, 0}, {4, 0}}));
  EXPECT_EQ(lines[1], (geom::Polyline{{4, 0}, {4.25, 3}}));
}

TEST(SnapNoding, AnArrangementEdgeKeepsItsEndsOffTheGrid) {
  const double step = 0.125;
  // A steep edge the arrangement has, less than a step wide, ends off the grid (a crossing
  // CGAL's sweep constructed); snapped, it would become vertical and run the other way in
  // (x, y) order. A new segment's end within reach moves onto its vertex as it is.
  const std::vector<geom::Polyline> lines =
      geom::snap_round_segments({{{2.01, 3}, {2.07, 1}}, {{2.2, 1.1}, {5, 1}}}, step, {true, false});
  EXPECT_EQ(lines[0], (geom::Polyline{{2.01, 3}, {2.07, 1}}));
  EXPECT_EQ(lines[1], (geom::Polyline{{2.07, 1}, {5, 1}}));
}
