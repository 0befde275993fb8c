// The exact planar map: windings, labels kept on split, dissolving, strokes.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <thread>

#include "generate/cancel.h"
#include "geom/face_locator.h"
#include "geom/grid.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"
#include "geom/shared_ends.h"
#include "tests/test_util.h"

using geom::PlanarMap;
using geom::Polygon;
using geom::Ring;
using geom::Windings;
using testing_util::area;

namespace {

Ring square(double x0, double y0, double size) { return {{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}}; }

// Area per group after dissolving with group = label.
std::vector<double> group_areas(const PlanarMap& map, int groups) {
  std::vector<int> identity(groups);
  for (int i = 0; i < groups; ++i) identity[i] = i;
  std::vector<double> areas(groups, 0.0);
  auto polys = map.dissolve(identity, groups);
  for (int g = 0; g < groups; ++g)
    for (const Polygon& p : testing_util::polygons(polys[g])) areas[g] += area(p);
  return areas;
}

}  // namespace

TEST(PlanarMap, OverlappingSquaresWindOncePerRing) {
  PlanarMap map;
  map.add_ring(square(0, 0, 10), 0);
  map.add_ring(square(5, 5, 10), 1);
  map.insert_batch();
  map.label_faces([](const Windings& w) {
    EXPECT_LE(w.size(), 2u);
    for (auto [c, n] : w) EXPECT_EQ(n, 1) << "counter " << c;
    return (geom::winding_of(w, 0) != 0) + 2 * (geom::winding_of(w, 1) != 0);
  });
  auto a = group_areas(map, 4);
  EXPECT_EQ(a[1], 75);
  EXPECT_EQ(a[2], 75);
  EXPECT_EQ(a[3], 25);
}

// A cancelled insertion ends its sweep at the event under way (so a large map stops within
// a second of Cancel) and throws once the sweep has cleaned up (the sanitizer build checks
// that nothing leaks), into an empty map and into one that has edges already.
TEST(PlanarMap, CancelledInsertionStopsAtTheSweepsFirstEvent) {
  auto add_lattice = [](PlanarMap& map, double shift) {
    for (int i = 0; i < 60; ++i) {
      map.add_edge({shift, shift + i}, {shift + 60, shift + i}, 0);
      map.add_edge({shift + i + 0.5, shift}, {shift + i + 0.5, shift + 60}, 0);
    }
  };
  PlanarMap whole;
  add_lattice(whole, 0);
  whole.insert_batch();
  add_lattice(whole, 30.25);
  whole.insert_batch();
  const std::size_t first_edges = [&] {
    PlanarMap one;
    add_lattice(one, 0);
    one.insert_batch();
    return one.counts().edges;
  }();
  ASSERT_GT(first_edges, 7000u);  // 60 x 60 crossings

  std::atomic<bool> cancelled{false};
  const exacity::CancelScope scope(cancelled);
  PlanarMap empty;
  add_lattice(empty, 0);
  cancelled = true;
  EXPECT_THROW(empty.insert_batch(), exacity::Cancelled);
  EXPECT_LT(empty.counts().edges, 10u);

  cancelled = false;
  PlanarMap filled;
  add_lattice(filled, 0);
  filled.insert_batch();
  EXPECT_EQ(filled.counts().edges, first_edges);
  add_lattice(filled, 30.25);
  cancelled = true;
  EXPECT_THROW(filled.insert_batch(), exacity::Cancelled);
  EXPECT_LT(filled.counts().edges, whole.counts().edges / 2);
}

// Rings that share ends, end on each other's edges (T-junctions), run along part of each
// other's edges (both ways), cover one another exactly, overlap in a sliver 2^-20 m wide and
// cross properly: the cases validation's maps answer from orientations of the ends
// (geom/shared_ends.h; docs/design.md, Algorithms: The exact city map). With CGAL's answers
// and with those, each region has its windings and area, and is one face.
TEST(PlanarMap, EndsOnEdgesOverlapsAndSliversWindAsTheyLie) {
  const double sliver = std::ldexp(1.0, -20);
  const std::vector<Ring> rings{
      square(0, 0, 10),                                      // 0: a block
      {{0, 0}, {5, 0}, {5, 10}, {0, 10}},                    // 1: its left lot, corners on the block's edges
      {{5, 0}, {10, 0}, {10, 10}, {5, 10}},                  // 2: its right lot
      {{5, 0}, {10, 0}, {10, 5}, {10, 10}, {5, 10}, {5, 5}},  // 3: the right lot again, with vertices along its edges
      {{5 - sliver, 2}, {7, 2}, {7, 3}, {5 - sliver, 3}},    // 4: across the lots' shared edge, a sliver into the left one
      {{2, 6}, {5, 7}, {2, 8}},                              // 5: a corner on the left lot's edge, inside it
  };
  for (const bool by_orientation : {false, true}) {
    std::optional<geom::SharedEndsByOrientation> scope;
    if (by_orientation) scope.emplace();
    PlanarMap map;
    for (std::size_t r = 0; r < rings.size(); ++r) map.add_ring(rings[r], static_cast<int>(r));
    // The right lot's ring once more and as a clockwise hole: along the lots' shared edge
    // the other way (the ring around counter 6 and its hole cancel everywhere).
    map.add_ring({{5, 0}, {10, 0}, {10, 10}, {5, 10}}, 6);
    map.add_ring({{5, 10}, {10, 10}, {10, 0}, {5, 0}}, 6);
    map.insert_batch();
    std::map<int, int> faces;  // label -> faces with it
    map.label_faces([&](const Windings& w) {
      int label = 0;
      for (auto [c, n] : w) {
        EXPECT_EQ(n, 1) << "counter " << c;
        label |= 1 << c;
      }
      ++faces[label];
      return label;
    });
    EXPECT_EQ(faces, (std::map<int, int>{{0, 1}, {0b11, 1}, {0b100011, 1}, {0b10011, 1}, {0b11101, 1}, {0b1101, 1}}))
        << by_orientation;
    const std::vector<double> a = group_areas(map, 64);
    EXPECT_EQ(a[0b11], 47 - sliver);  // the left lot but the sliver and the triangle
    EXPECT_EQ(a[0b100011], 3);        // the triangle
    EXPECT_EQ(a[0b10011], sliver);    // the sliver
    EXPECT_EQ(a[0b11101], 2);         // the crossing ring in the right lot
    EXPECT_EQ(a[0b1101], 48);         // the right lot but that
  }
}

TEST(PlanarMap, ClockwiseRingWindsMinusOne) {
  PlanarMap map;
  Ring r = square(0, 0, 4);
  std::reverse(r.begin(), r.end());
  map.add_ring(r, 7);
  map.insert_batch();
  std::vector<int> seen;
  map.label_faces([&](const Windings& w) {
    seen.push_back(geom::winding_of(w, 7));
    return 0;
  });
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, (std::vector<int>{-1, 0}));
}

TEST(PlanarMap, PentagramCentreWindsTwice) {
  PlanarMap map;
  // A pentagram on integer points: its centre pentagon is wound twice.
  map.add_ring({{0, -10}, {6, 8}, {-10, -3}, {10, -3}, {-6, 8}}, 0);
  map.insert_batch();
  std::vector<int> seen;
  map.label_faces([&](const Windings& w) {
    int n = geom::winding_of(w, 0);
    seen.push_back(n);
    return n;
  });
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 2), 1);  // the centre
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 5);  // the points
}

TEST(PlanarMap, SplitFaceKeepsItsLabel) {
  PlanarMap map;
  map.add_ring(square(0, 0, 10), 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) != 0 ? 1 : 0; });
  auto before = map.counts();
  map.add_polyline({{0, 3}, {10, 7}}, 0);  // splits the square in two
  map.insert_batch();
  EXPECT_EQ(map.counts().faces, before.faces + 1);
  auto a = group_areas(map, 2);
  EXPECT_EQ(a[1], 100);
  auto polys = testing_util::polygons(map.dissolve({-1, 0}, 1)[0]);
  ASSERT_EQ(polys.size(), 1u);  // dissolved back into one square
}

TEST(PlanarMap, RelabelSeesOnlyLaterCountersAndEachFacesLabel) {
  PlanarMap map;
  map.add_ring(square(0, 0, 10), 0);
  map.add_ring(square(20, 0, 10), 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) != 0 ? 1 : 0; });
  // The two squares are two components of label 1: they become labels 2 and 3.
  std::vector<int> seen;
  map.relabel_components({-1, 0}, [&](int component, int label) {
    EXPECT_EQ(label, 1);
    seen.push_back(component);
    return 2 + component;
  });
  EXPECT_EQ(seen, (std::vector<int>{0, 1}));
  // A ring across both squares splits them; the pieces keep 2 and 3 and only counter 5 is seen.
  map.add_ring({{5, 2}, {25, 2}, {25, 8}, {5, 8}}, 5);
  map.insert_batch();
  map.relabel_faces(5, [](const Windings& w, int previous) {
    EXPECT_TRUE(previous >= 0 && previous <= 3) << previous;
    for (auto [counter, winding] : w) EXPECT_EQ(counter, 5);
    return geom::winding_of(w, 5) != 0 && previous >= 2 ? previous + 2 : previous;
  });
  auto a = group_areas(map, 6);
  EXPECT_EQ(a[2], 100 - 30);  // the left square less the ring's 5 x 6
  EXPECT_EQ(a[3], 100 - 30);
  EXPECT_EQ(a[4], 30);
  EXPECT_EQ(a[5], 30);
  EXPECT_EQ(a[1], 0);
}

TEST(PlanarMap, InsertWithinKeepsEachRingToItsRegion) {
  // Two squares sharing the edge x = 10, the left one cut in two faces by a polyline.
  PlanarMap map;
  map.add_ring(square(0, 0, 10), 0);
  map.add_ring(square(10, 0, 10), 1);
  map.add_polyline({{0, 5}, {10, 5}}, 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) != 0 ? 1 : geom::winding_of(w, 1) != 0 ? 2 : 0; });
  ASSERT_EQ(map.counts().faces, 4u);
  // Region 0 is the left square, region 1 the right one. Each ring crosses the shared edge
  // and reaches into the other square; the small one in region 0 touches nothing.
  map.add_ring_within(0, {{5, 2}, {15, 2}, {15, 8}, {5, 8}}, 10);
  map.add_ring_within(1, {{8, 3}, {14, 3}, {14, 9}, {8, 9}}, 11);
  map.add_ring_within(0, square(1, 6.5, 1), 12);
  // Two more in region 0: one across its left edge, one reaching it only through the
  // first, with a face that only their edges bound.
  map.add_ring_within(0, {{-1, 0.5}, {3, 0.5}, {3, 4}, {-1, 4}}, 13);
  map.add_ring_within(0, {{2, 2}, {4, 2}, {4, 3}, {2, 3}}, 14);
  std::vector<int> previous_seen;
  map.insert_within({-1, 0, 1}, [&](const Windings& w, int previous) {
    previous_seen.push_back(previous);
    if (w.empty()) return previous;
    return 3 + w.front().first - 10;
  });
  for (int p : previous_seen) EXPECT_TRUE(p == 1 || p == 2) << p;
  auto a = group_areas(map, 8);
  EXPECT_EQ(a[3], 30);  // x 5..10, y 2..8: only the part inside the left square
  EXPECT_EQ(a[4], 24);  // x 10..14, y 3..9
  EXPECT_EQ(a[5], 0);   // left out
  EXPECT_EQ(a[6], 10.5);  // x 0..3, y 0.5..4, the first ring around it winning
  EXPECT_EQ(a[7], 1);     // x 3..4, y 2..3
  EXPECT_EQ(a[1], 100 - 30 - 10.5 - 1);
  EXPECT_EQ(a[2], 76);
  // The left square's first ring is cut by the polyline (two faces), the right one's is
  // one, the last two make three; nothing outside the squares was cut.
  EXPECT_EQ(map.counts().faces, 10u);
  auto lot = testing_util::polygons(map.dissolve({-1, -1, -1, 0}, 1)[0]);
  ASSERT_EQ(lot.size(), 1u);
  EXPECT_EQ(area(lot[0]), 30);
  // The added edges bound nothing.
  map.relabel_faces(INT_MIN, [](const Windings& w, int previous) {
    for (auto [counter, winding] : w) EXPECT_LT(counter, 10);
    return previous;
  });
}

TEST(PlanarMap, AMapOfACellAloneKnowsWhatLiesAcrossItsEdgesFromTheirKinds) {
  // A 10 x 10 cell with a road along its foot (kind 7) and nothing along its other sides
  // (kind -1), as the city's map traces it.
  PlanarMap city;
  city.add_ring(square(0, 0, 10), 0);
  city.add_ring({{0, -4}, {10, -4}, {10, 0}, {0, 0}}, 1);
  city.insert_batch();
  city.label_faces([](const Windings& w) { return geom::winding_of(w, 0) != 0 ? 1 : geom::winding_of(w, 1) != 0 ? 2 : 0; });
  const std::vector<geom::Cell> traced = city.cells({-1, 0, -1}, {-1, -1, 7});
  ASSERT_EQ(traced.size(), 1u);
  // Alone, labels 0 (outside), 1 (a road across), 2 (inside); its left half made label 3.
  PlanarMap alone = PlanarMap::of_cell(traced[0], 2, 0, [](int kind) { return kind == 7 ? 1 : 0; });
  alone.add_ring_within(0, {{0, 0}, {5, 0}, {5, 10}, {0, 10}}, 5);
  alone.insert_within({-1, -1, 0}, [](const Windings& w, int previous) { return w.empty() ? previous : 3; });
  std::vector<int> groups;
  const std::vector<geom::Cell> halves = alone.cells({-1, -1, 0, 1}, {100, 200, 300, 400}, &groups);
  ASSERT_EQ(halves.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    // Each half's foot is across the road; its other outer sides are across the outside,
    // and its middle side across the other half.
    const geom::Cell& half = halves[i];
    EXPECT_EQ(half.area(), 50);
    EXPECT_EQ(half.edge_kinds(), (std::vector<int>{100, 200, groups[i] == 0 ? 400 : 300}));
    const auto foot = half.edges_of_kind(200);
    ASSERT_EQ(foot.size(), 1u);
    EXPECT_EQ(foot[0].first.y, 0);
    EXPECT_EQ(foot[0].second.y, 0);
  }
}

TEST(PlanarMap, OutlinesPutTheirVerticesOnTheMapsEdgesAndNameThoseANeighbourLacks) {
  // Two 10 x 10 regions side by side (labels 1 and 2), each cut alone by a ring across the
  // edge they share: A's ring meets it at y = 3 and 6, B's at y = 4 and 5.
  PlanarMap city;
  city.add_ring(square(0, 0, 10), 0);
  city.add_ring(square(10, 0, 10), 1);
  city.insert_batch();
  city.label_faces([](const Windings& w) { return geom::winding_of(w, 0) != 0 ? 1 : geom::winding_of(w, 1) != 0 ? 2 : 0; });
  const std::vector<int> region_of_label{-1, 0, 1};
  const std::vector<geom::Cell> cells = city.cells(region_of_label, {0, 0, 0});
  ASSERT_EQ(cells.size(), 2u);
  auto alone = [](const geom::Cell& cell, const Ring& ring) {
    PlanarMap map = PlanarMap::of_cell(cell, 1, 0, [](int) { return 0; });
    map.add_ring_within(0, ring, 5);
    map.insert_within({-1, 0, -1}, [](const Windings& w, int previous) { return w.empty() ? previous : 2; });
    map.snap_round();
    return map;
  };
  const PlanarMap a = alone(cells[0], {{5, 3}, {15, 3}, {15, 6}, {5, 6}});
  const PlanarMap b = alone(cells[1], {{8, 4}, {15, 4}, {15, 5}, {8, 5}});
  // Each outline: its cell's edges split where its ring met them, each piece's kind the
  // index of the cell's edge it lies on.
  const std::vector<geom::Cell> outlines{a.outline_as_cut(), b.outline_as_cut()};
  for (const geom::Cell& outline : outlines) {
    const geom::KindedRing ring = outline.kinded_rings().front();
    EXPECT_EQ(ring.points.size(), 6u);
    EXPECT_EQ(std::set<int>(ring.kinds.begin(), ring.kinds.end()), (std::set<int>{0, 1, 2, 3}));
    EXPECT_EQ(outline.area(), 100);
  }
  const std::vector<std::vector<geom::VertexOnEdge>> beyond = city.add_outlines(region_of_label, outlines);
  EXPECT_EQ(city.counts().vertices, 6u + 4u);
  EXPECT_EQ(city.counts().faces, 3u);
  // A's edge runs up x = 10 (the region on its left), B's down it.
  ASSERT_EQ(beyond.size(), 2u);
  ASSERT_EQ(beyond[0].size(), 2u);
  EXPECT_EQ(beyond[0][0].from, (geom::Vec2{10, 3}));
  EXPECT_EQ(beyond[0][0].to, (geom::Vec2{10, 6}));
  EXPECT_EQ(beyond[0][0].at, (geom::Vec2{10, 4}));
  EXPECT_EQ(beyond[0][1].at, (geom::Vec2{10, 5}));
  ASSERT_EQ(beyond[1].size(), 2u);
  EXPECT_EQ(beyond[1][0].from, (geom::Vec2{10, 10}));
  EXPECT_EQ(beyond[1][0].to, (geom::Vec2{10, 5}));
  EXPECT_EQ(beyond[1][0].at, (geom::Vec2{10, 6}));
  EXPECT_EQ(beyond[1][1].from, (geom::Vec2{10, 4}));
  EXPECT_EQ(beyond[1][1].to, (geom::Vec2{10, 0}));
  EXPECT_EQ(beyond[1][1].at, (geom::Vec2{10, 3}));
  // A's lot, as written, takes B's two vertices on its edge along x = 10, in order.
  const std::vector<geom::Cell> lots = a.cells({-1, -1, 0}, {0, 0, 0});
  ASSERT_EQ(lots.size(), 1u);
  const std::optional<geom::Cell> written = lots[0].as_written();
  ASSERT_TRUE(written);
  const std::optional<geom::Cell> taken = geom::with_vertices_on_edges(*written, beyond[0]);
  ASSERT_TRUE(taken);
  const Ring ring = taken->kinded_rings().front().points;
  const auto at = std::find(ring.begin(), ring.end(), geom::Vec2{10, 3});
  ASSERT_NE(at, ring.end());
  std::vector<geom::Vec2> along;
  for (std::size_t k = 0; k < 4; ++k) along.push_back(ring[(at - ring.begin() + k) % ring.size()]);
  EXPECT_EQ(along, (std::vector<geom::Vec2>{{10, 3}, {10, 4}, {10, 5}, {10, 6}}));
  EXPECT_EQ(taken->area(), 15);
  EXPECT_FALSE(geom::with_vertices_on_edges(*written, beyond[1]));  // none on its edges
}

TEST(PlanarMap, InsertWithinLabelsAsOneSweepWould) {
  // Random rectangles across the edges of a square region cut in two by its diagonal:
  // inserted region by region, every face gets the label a sweep of the whole map and
  // relabelling would give it.
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    std::uniform_int_distribution<int> at(5, 95);
    std::vector<Ring> rings;
    for (int i = 0; i < 10; ++i) {
      int a = at(rng), b = at(rng), c = at(rng);
      int lo = std::min(b, c), hi = std::max(b, c) + 1;
      rings.push_back(i % 2 ? Ring{{-5, double(lo)}, {double(a), double(lo)}, {double(a), double(hi)}, {-5, double(hi)}}
                            : Ring{{double(lo), double(a)}, {double(hi), double(a)}, {double(hi), 105}, {double(lo), 105}});
    }
    auto label_of = [](const Windings& w, int previous) { return w.empty() || previous != 1 ? previous : 2 + w.front().first - 10; };
    std::vector<double> areas[2];
    for (int way = 0; way < 2; ++way) {
      PlanarMap map;
      map.add_ring(square(0, 0, 100), 0);
      map.add_polyline({{0, 0}, {100, 100}}, 0);
      map.insert_batch();
      map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) != 0 ? 1 : 0; });
      for (std::size_t i = 0; i < rings.size(); ++i) {
        if (way == 0) map.add_ring_within(0, rings[i], 10 + static_cast<int>(i));
        else map.add_ring(rings[i], 10 + static_cast<int>(i));
      }
      if (way == 0) {
        map.insert_within({-1, 0}, label_of);
      } else {
        map.insert_batch();
        map.relabel_faces(10, label_of);
      }
      areas[way] = group_areas(map, 12);
    }
    for (int l = 1; l < 12; ++l) EXPECT_NEAR(areas[0][l], areas[1][l], 1e-9) << "round " << round << " label " << l;
  }
}

TEST(PlanarMap, DissolveSplitsARingThatTouchesItself) {
  PlanarMap map;
  map.add_ring(square(0, 0, 10), 0);
  Ring hole{{0, 5}, {4, 3}, {4, 7}};  // touches the outer ring at (0, 5)
  std::reverse(hole.begin(), hole.end());
  map.add_ring(hole, 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) == 1 ? 1 : 0; });
  auto polys = testing_util::polygons(map.dissolve({-1, 0}, 1)[0]);
  ASSERT_EQ(polys.size(), 1u);
  const Polygon& p = polys[0];
  ASSERT_EQ(p.holes.size(), 1u);
  EXPECT_TRUE(geom::ring_is_simple(p.outer));
  EXPECT_TRUE(geom::ring_is_simple(p.holes[0]));
  EXPECT_EQ(geom::ring_orientation(p.outer), 1);
  EXPECT_EQ(geom::ring_orientation(p.holes[0]), -1);
  EXPECT_EQ(area(p), 100 - 8);
}

TEST(PlanarMap, SquaresTouchingAtACornerStayTwoPolygons) {
  PlanarMap map;
  map.add_ring(square(0, 0, 1), 0);
  map.add_ring(square(1, 1, 1), 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) ? 1 : 0; });
  auto polys = testing_util::polygons(map.dissolve({-1, 0}, 1)[0]);
  EXPECT_EQ(polys.size(), 2u);
}

TEST(PlanarMap, PolylinePiecesComeInOrderWithTheirSides) {
  PlanarMap map;
  map.add_ring(square(2, -1, 2), 0);
  map.add_ring(square(6, -1, 2), 0);
  map.add_polyline({{10, 0}, {0, 0}}, 3);  // right to left through both squares
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) ? 1 : 0; });
  auto pieces = map.polyline_pieces()[3];
  ASSERT_EQ(pieces.size(), 5u);
  double xs[] = {10, 8, 6, 4, 2, 0};
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    EXPECT_EQ(pieces[i].from.x, xs[i]);
    EXPECT_EQ(pieces[i].to.x, xs[i + 1]);
    int inside = i % 2 == 1;
    EXPECT_EQ(pieces[i].left_label, inside);
    EXPECT_EQ(pieces[i].right_label, inside);
  }
}

TEST(Stroke, RightAngleBendIsMitred) {
  PlanarMap map;
  map.add_stroke({{0, 0}, {100, 0}, {100, 100}}, 5, 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) > 0 ? 1 : 0; });
  auto polys = testing_util::polygons(map.dissolve({-1, 0}, 1)[0]);
  ASSERT_EQ(polys.size(), 1u);
  // Two 100 x 10 bars, their 5 x 5 overlap counted once, and the 5 x 5 mitre corner.
  EXPECT_EQ(area(polys[0]), 2000);
  EXPECT_TRUE(polys[0].holes.empty());
  bool has_mitre_corner = false;
  for (auto p : polys[0].outer) has_mitre_corner |= p == geom::Vec2{105, -5};
  EXPECT_TRUE(has_mitre_corner);
}

TEST(Stroke, HairpinIsBevelledNotSpiked) {
  PlanarMap map;
  map.add_stroke({{0, 0}, {100, 0}, {0, 4}}, 5, 0);  // a turn of about 177.7 degrees
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) > 0 ? 1 : 0; });
  auto polys = testing_util::polygons(map.dissolve({-1, 0}, 1)[0]);
  ASSERT_EQ(polys.size(), 1u);
  for (auto p : polys[0].outer) EXPECT_LE(p.x, 100 + 4 * 5) << "mitre past the limit";
  EXPECT_TRUE(geom::ring_is_simple(polys[0].outer));
}

TEST(Stroke, OffsetsLieOnTheGrid) {
  PlanarMap map;
  map.add_stroke({{0.1, 0.2}, {33.3, 17.7}}, 3.3, 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) > 0 ? 1 : 0; });
  auto polys = testing_util::polygons(map.dissolve({-1, 0}, 1)[0]);
  ASSERT_EQ(polys.size(), 1u);
  for (auto p : polys[0].outer) {
    EXPECT_EQ(p.x * 1024, std::nearbyint(p.x * 1024));
    EXPECT_EQ(p.y * 1024, std::nearbyint(p.y * 1024));
  }
}

TEST(PolygonCheck, SimpleAndOriented) {
  EXPECT_TRUE(geom::ring_is_simple(square(0, 0, 1)));
  EXPECT_EQ(geom::ring_orientation(square(0, 0, 1)), 1);
  EXPECT_FALSE(geom::ring_is_simple({{0, 0}, {2, 2}, {2, 0}, {0, 2}}));  // bow tie
  EXPECT_FALSE(geom::ring_is_simple({{0, 0}, {1, 0}, {1, 1}, {1, 0}, {0, 1}}));  // repeated vertex
  EXPECT_EQ(geom::ring_orientation({{0, 0}, {1, 1}, {2, 2}}), 0);
  // Two points a hair apart still count as distinct: the check is exact.
  EXPECT_TRUE(geom::ring_is_simple({{0, 0}, {1, 0}, {1, 1e-300}}));
}

TEST(PolygonCheck, InteriorsOverlapOnlyWhereTheyShareArea) {
  const geom::Polygon a{square(0, 0, 2), {}};
  EXPECT_FALSE(geom::interiors_overlap(a, {square(2, 0, 2), {}}));      // a shared wall
  EXPECT_FALSE(geom::interiors_overlap(a, {square(2, 2, 1), {}}));      // a shared corner
  EXPECT_FALSE(geom::interiors_overlap(a, {square(5, 5, 1), {}}));      // apart
  EXPECT_TRUE(geom::interiors_overlap(a, a));                           // the same
  EXPECT_TRUE(geom::interiors_overlap(a, {square(0.5, 0.5, 1), {}}));   // inside, no edge meeting
  EXPECT_TRUE(geom::interiors_overlap(a, {square(1, 1, 2), {}}));       // crossing
  // A hair's breadth over the wall is an overlap: the test is exact.
  EXPECT_TRUE(geom::interiors_overlap(a, {square(2 - 1e-12, 0, 2), {}}));
  // In a courtyard: no overlap.
  geom::Polygon block{square(0, 0, 10), {square(3, 3, 4)}};
  std::reverse(block.holes[0].begin(), block.holes[0].end());
  EXPECT_FALSE(geom::interiors_overlap(block, {square(4, 4, 2), {}}));
  EXPECT_TRUE(geom::interiors_overlap(block, {square(2, 2, 2), {}}));
}

namespace {

// Streets of half width `hw` leaving q = (0, 0) at the given angles (degrees), `length` long.
std::vector<geom::JunctionArm> arms_at(const std::vector<double>& degrees, double hw, double length = 400) {
  std::vector<geom::JunctionArm> arms;
  for (double d : degrees)
    arms.push_back({geom::snap(geom::Vec2{length * std::cos(d * M_PI / 180), length * std::sin(d * M_PI / 180)}), hw});
  return arms;
}

// The junction (counter 1) of those streets with their strokes (counter 0): the junction's
// polygons, and the area of the junction outside every stroke.
struct JunctionCut {
  bool drawn = false;
  std::vector<Polygon> junction;
  double outside_strokes = 0;
};

JunctionCut junction_of(const std::vector<geom::JunctionArm>& arms) {
  PlanarMap map;
  JunctionCut cut;
  cut.drawn = map.add_junction({0, 0}, arms, 1);
  for (const auto& arm : arms) map.add_stroke({{0, 0}, arm.toward}, arm.half_width, 0);
  map.insert_batch();
  // 0: neither, 1: stroke only, 2: junction inside a stroke, 3: junction outside them.
  map.label_faces([](const Windings& w) {
    const bool stroke = geom::winding_of(w, 0) != 0, junction = geom::winding_of(w, 1) != 0;
    return junction ? (stroke ? 2 : 3) : stroke ? 1 : 0;
  });
  auto groups = map.dissolve({-1, -1, 0, 0}, 1);
  cut.junction = testing_util::polygons(groups[0]);
  for (const Polygon& p : testing_util::polygons(map.dissolve({-1, -1, -1, 0}, 1)[0])) cut.outside_strokes += area(p);
  return cut;
}

}  // namespace

TEST(Junction, RightAngleTAndCrossAreTheSquareWhereTheStreetsMeet) {
  for (const auto& degrees : std::vector<std::vector<double>>{{0, 90}, {0, 90, 180}, {0, 90, 180, 270}}) {
    JunctionCut j = junction_of(arms_at(degrees, 5));
    ASSERT_TRUE(j.drawn);
    ASSERT_EQ(j.junction.size(), 1u);
    EXPECT_EQ(area(j.junction[0]), 100) << degrees.size() << " streets";
  }
  // The L's outer corner is the mitre, outside both strokes: 5 x 5.
  EXPECT_EQ(junction_of(arms_at({0, 90}, 5)).outside_strokes, 25);
}

TEST(Junction, TwoToSixStreetsAtAwkwardAnglesAreOneSimplePolygonAroundTheNode) {
  const std::vector<std::vector<double>> cases = {
      {0, 5}, {0, 175}, {0, 90}, {0, 5, 180}, {10, 185, 275}, {0, 5, 90, 175}, {0, 90, 95, 270},
      {0, 5, 90, 175, 270}, {0, 60, 65, 180, 185, 300}, {0, 55, 175, 180, 260, 265}};
  for (const auto& degrees : cases) {
    for (double hw : {2.0, 6.0}) {
      SCOPED_TRACE(::testing::Message() << degrees.size() << " streets, the second at " << degrees[1] << ", hw " << hw);
      // Mixed widths: every other street half as wide.
      auto arms = arms_at(degrees, hw);
      for (std::size_t i = 1; i < arms.size(); i += 2) arms[i].half_width = hw / 2;
      JunctionCut j = junction_of(arms);
      ASSERT_TRUE(j.drawn);
      ASSERT_EQ(j.junction.size(), 1u);
      EXPECT_TRUE(j.junction[0].holes.empty());
      EXPECT_TRUE(geom::ring_is_simple(j.junction[0].outer));
      // The node is inside, or on a street's cut (a wide street's flat end, where a
      // narrow one tapers on from it).
      const geom::Ring& ring = j.junction[0].outer;
      bool on_edge = false;
      for (std::size_t i = 0; i < ring.size(); ++i)
        on_edge |= geom::distance_to_segment({0, 0}, ring[i], ring[(i + 1) % ring.size()]) == 0;
      EXPECT_TRUE(on_edge || geom::odd_crossings(ring, {0, 0}));
      // Outside the strokes it fills only the outer corners of bends: each within the
      // mitre limit of the node.
      for (auto p : j.junction[0].outer) EXPECT_LE(std::hypot(p.x, p.y), 4 * hw + 1e-9 + hw / std::tan(2.5 * M_PI / 180));
      EXPECT_LT(j.outside_strokes, degrees.size() * 16 * hw * hw);
    }
  }
}

TEST(Junction, StreetsRunningStraightOnNeedNone) {
  PlanarMap map;
  EXPECT_FALSE(map.add_junction({0, 0}, arms_at({0, 180}, 5), 1));
  EXPECT_FALSE(map.add_junction({0, 0}, arms_at({30}, 5), 1));
}

TEST(Junction, SidesPartingPastTheStreetsAreNotDrawn) {
  // 5 degrees apart, 20 m long, 12 m wide: their sides part about 137 m out.
  PlanarMap map;
  EXPECT_FALSE(map.add_junction({0, 0}, arms_at({0, 5}, 6, 20), 1));
  // The same first segments on streets that run on 200 m beyond them.
  auto longer = arms_at({0, 5}, 6, 20);
  for (auto& arm : longer) arm.length = 220;
  EXPECT_TRUE(map.add_junction({0, 0}, longer, 1));
}

TEST(PlanarMap, LabelAtAnswersForTheMapAsItNowIs) {
  // label_at keeps a point location between queries; edges inserted after one are seen.
  PlanarMap map;
  map.add_ring(square(0, 0, 10), 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return geom::winding_of(w, 0) != 0 ? 1 : 0; });
  EXPECT_EQ(map.label_at({7.5, 7.5}), 1);
  EXPECT_EQ(map.label_at({20, 20}), 0);
  EXPECT_EQ(map.label_at({10, 5}), -1);  // on an edge
  map.add_ring(square(5, 5, 10), 1);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return (geom::winding_of(w, 0) != 0) + 2 * (geom::winding_of(w, 1) != 0); });
  EXPECT_EQ(map.label_at({7.5, 7.5}), 3);
  EXPECT_EQ(map.label_at({12.5, 12.5}), 2);
  EXPECT_EQ(map.label_at({2.5, 2.5}), 1);
  EXPECT_EQ(map.label_at({20, 20}), 0);
  EXPECT_EQ(map.label_at({10, 7.5}), -1);
}

namespace {

// Whether p lies on the segment a-b (whole and half coordinates: exact in doubles).
bool on_segment(geom::Vec2 p, geom::Vec2 a, geom::Vec2 b) {
  const double cross = (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y);
  return cross == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Random rings (quadrilaterals, triangles, squares in squares) and loose polylines on whole
// coordinates, ring k labelling its inside with bit k, and a lattice of half steps over
// them: each point's label worked out from the rings in doubles (-1 on any ring or line).
struct LocateCase {
  PlanarMap map;
  std::vector<geom::Vec2> points;
  std::vector<int> expected;

  explicit LocateCase(unsigned seed) {
    std::mt19937 rng(seed);
    auto coord = [&](int lo, int hi) { return static_cast<double>(std::uniform_int_distribution<int>(lo, hi)(rng)); };
    std::vector<Ring> rings;
    std::vector<geom::Polyline> lines;
    while (rings.size() < 10) {
      const double x = coord(0, 16), y = coord(0, 16);
      switch (rings.size() % 3) {
        case 0: rings.push_back({{x, y}, {x + coord(1, 4), y}, {x + coord(1, 4), y + coord(1, 4)}, {x, y + coord(1, 4)}}); break;
        case 1: {
          const Ring t{{x, y}, {coord(0, 20), coord(0, 20)}, {coord(0, 20), coord(0, 20)}};
          if (geom::ring_orientation(t) != 0) rings.push_back(t);
          break;
        }
        default: rings.push_back(square(x, y, 4)), rings.push_back(square(x + 1, y + 1, 2));
      }
    }
    for (int i = 0; i < 4; ++i) lines.push_back({{coord(0, 20), coord(0, 20)}, {coord(0, 20), coord(0, 20)}, {coord(0, 20), coord(0, 20)}});
    lines.push_back({{coord(0, 20), 2}, {lines.back()[0].x, 18}});  // vertical
    lines.push_back({{-1e7, -0.5}, {1e7, 20.5}});                     // longer than any square of an index
    for (std::size_t k = 0; k < rings.size(); ++k) map.add_ring(rings[k], static_cast<int>(k));
    for (std::size_t i = 0; i < lines.size(); ++i) map.add_polyline(lines[i], static_cast<int>(i));
    map.insert_batch();
    map.label_faces([](const Windings& w) {
      int label = 0;
      for (const auto& [counter, n] : w) label |= n != 0 ? 1 << counter : 0;
      return label;
    });
    for (double y = -1; y <= 21; y += 0.5)
      for (double x = -1; x <= 21; x += 0.5) {
        const geom::Vec2 p{x, y};
        int label = 0;
        for (std::size_t k = 0; k < rings.size(); ++k) {
          for (std::size_t i = 0; i < rings[k].size(); ++i)
            if (on_segment(p, rings[k][i], rings[k][(i + 1) % rings[k].size()])) label = -1;
          if (label >= 0 && geom::winding_number(rings[k], p) != 0) label |= 1 << k;
        }
        for (const geom::Polyline& l : lines)
          for (std::size_t i = 0; i + 1 < l.size(); ++i)
            if (on_segment(p, l[i], l[i + 1])) label = -1;
        points.push_back(p);
        expected.push_back(label);
      }
  }
};

}  // namespace

TEST(PlanarMap, LabelAtIsExact) {
  // Points inside faces, on edges and vertices, straight below vertices and crossings,
  // inside holes and beside dangling lines.
  for (unsigned seed = 1; seed <= 20; ++seed) {
    LocateCase c(seed);
    for (std::size_t i = 0; i < c.points.size(); ++i)
      ASSERT_EQ(c.map.label_at(c.points[i]), c.expected[i]) << "seed " << seed << ", point " << c.points[i].x << ", " << c.points[i].y;
  }
}

TEST(FaceLocator, AnswersAsTheMapItWasMadeFrom) {
  // The clutter asks the locator, once the map is freed, what it asked label_at: the same
  // face or -1 at every point, on the lattice, at every vertex, straight below and above
  // each, and at each edge's rounded middle (on the edge or beside it); before snap
  // rounding (crossings at rational points) and after.
  for (unsigned seed = 1; seed <= 20; ++seed) {
    LocateCase c(seed);
    for (bool rounded : {false, true}) {
      if (rounded) c.map.snap_round();
      const geom::FaceLocator faces = c.map.face_locator();
      std::vector<geom::Vec2> points = c.points;
      c.map.for_each_edge([&](const std::vector<geom::CurveTag>&, geom::Vec2 a, geom::Vec2 b) {
        for (geom::Vec2 p : {a, b})
          points.insert(points.end(), {p, {p.x, p.y - 0.25}, {p.x, p.y + 0.25}, {p.x, std::nextafter(p.y, -1e9)}});
        points.push_back({(a.x + b.x) / 2, (a.y + b.y) / 2});
      });
      int on_edges = 0;
      for (geom::Vec2 p : points) {
        const int label = c.map.label_at(p);
        on_edges += label < 0;
        ASSERT_EQ(faces.label_at(p), label) << "seed " << seed << (rounded ? ", rounded" : "") << ", point " << p.x << ", " << p.y;
      }
      EXPECT_GT(on_edges, 100);
    }
  }
  EXPECT_EQ(geom::FaceLocator().label_at({1, 2}), -1);
}

TEST(PlanarMap, LabelAtFromManyThreadsAtOnce) {
  // The clutter locates its spots from every thread; the first queries after a batch race
  // to find the map's point location built.
  for (unsigned seed = 1; seed <= 5; ++seed) {
    LocateCase c(seed);
    const std::size_t n = c.points.size();
    std::vector<std::vector<int>> found(8, std::vector<int>(n));
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < found.size(); ++t)
      threads.emplace_back([&, t] {
        for (std::size_t k = 0; k < n; ++k) {
          const std::size_t j = (k + t * n / found.size()) % n, i = t % 2 ? n - 1 - j : j;  // each its own order
          found[t][i] = c.map.label_at(c.points[i]);
        }
      });
    for (std::thread& t : threads) t.join();
    for (std::size_t t = 0; t < found.size(); ++t) EXPECT_EQ(found[t], c.expected) << "seed " << seed << ", thread " << t;
  }
}
