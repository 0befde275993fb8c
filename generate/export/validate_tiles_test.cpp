// A ring as a tile's map holds it: the same winding number at every point of the tile, its
// own edges wherever they meet the tile, stand-ins only outside it.
#include "generate/export/validate_tiles.h"

#include <gtest/gtest.h>

#include <random>

namespace exacity {
namespace {

using geom::Box;
using geom::Vec2;

double cross(Vec2 a, Vec2 b, Vec2 q) { return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x); }

// The winding number of q around closed chains of edges (q on none of them).
int winding(const std::vector<std::pair<Vec2, Vec2>>& edges, Vec2 q) {
  int w = 0;
  for (const auto& [a, b] : edges) {
    if (a.y <= q.y && b.y > q.y && cross(a, b, q) > 0) ++w;
    if (b.y <= q.y && a.y > q.y && cross(a, b, q) < 0) --w;
  }
  return w;
}

std::vector<std::pair<Vec2, Vec2>> ring_edges(const geom::Ring& ring) {
  std::vector<std::pair<Vec2, Vec2>> edges;
  for (std::size_t i = 0; i < ring.size(); ++i) edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
  return edges;
}

std::vector<std::pair<Vec2, Vec2>> tile_edges(const std::vector<TileEdge>& edges) {
  std::vector<std::pair<Vec2, Vec2>> out;
  for (const TileEdge& e : edges) out.push_back({e.a, e.b});
  return out;
}

// Whether the segment enters the open box (Liang-Barsky on small numbers, exact enough here).
bool enters(Vec2 a, Vec2 b, const Box& box) {
  double t0 = 0, t1 = 1;
  const double dx = b.x - a.x, dy = b.y - a.y;
  auto clip = [&](double p, double q) {  // p t < q keeps the open side
    if (p == 0) return q > 0;
    const double t = q / p;
    if (p < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    return true;
  };
  if (!clip(-dx, a.x - box.min_x) || !clip(dx, box.max_x - a.x) || !clip(-dy, a.y - box.min_y) ||
      !clip(dy, box.max_y - a.y))
    return false;
  return t0 < t1;
}

TEST(ValidateTiles, ARingKeepsItsWindingsInTheTileAndItsEdgesThatMeetIt) {
  const Box tile{0, 0, 10, 6};
  std::mt19937 random(37);
  std::uniform_int_distribution<int> coordinate(-25, 35), size(3, 40);
  std::uniform_real_distribution<double> inside(0.01, 0.99);
  int stood_in = 0, far = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    geom::Ring ring;
    const int n = size(random);
    // Rings of every kind: wide and self-crossing, or winding around the tile several times.
    for (int k = 0; k < n; ++k) {
      if (trial % 3 == 0) {
        const double angle = 6.283185307179586 * 3 * k / n;
        const double radius = 12 + coordinate(random) % 8;
        ring.push_back({std::round(5 + radius * std::cos(angle)), std::round(3 + radius * std::sin(angle))});
      } else {
        ring.push_back({static_cast<double>(coordinate(random)), static_cast<double>(coordinate(random))});
      }
    }
    std::vector<TileEdge> edges;
    ring_near_tile(ring, tile, edges);
    bool any_far = true;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
      Box box = Box::none();
      box.add(a), box.add(b);
      if (!box.meets(tile)) continue;
      any_far = false;
      const bool kept = std::any_of(edges.begin(), edges.end(), [&](const TileEdge& e) { return !e.stand_in && e.a == a && e.b == b; });
      EXPECT_TRUE(kept) << "trial " << trial << " edge " << i;
    }
    far += any_far;
    for (const TileEdge& e : edges) {
      if (!e.stand_in) continue;
      ++stood_in;
      EXPECT_FALSE(enters(e.a, e.b, tile)) << "trial " << trial << ": (" << e.a.x << ", " << e.a.y << ") -> (" << e.b.x << ", " << e.b.y << ")";
    }
    const auto whole = ring_edges(ring), near = tile_edges(edges);
    for (int q = 0; q < 40; ++q) {
      const Vec2 at{tile.min_x + inside(random) * tile.width() + 1e-7 * q, tile.min_y + inside(random) * tile.height() + 3e-8};
      ASSERT_EQ(winding(near, at), winding(whole, at)) << "trial " << trial << " at (" << at.x << ", " << at.y << ")";
    }
  }
  EXPECT_GT(stood_in, 10000);  // the cases the test is for were there
  EXPECT_GT(far, 100);
}

TEST(ValidateTiles, AFarRingBecomesTheTilesOutlineAsOftenAsItWindsAroundIt) {
  const Box tile{0, 0, 2, 1};
  auto count = [&](const geom::Ring& ring) {
    std::vector<TileEdge> edges;
    ring_near_tile(ring, tile, edges);
    for (const TileEdge& e : edges) EXPECT_TRUE(e.stand_in);
    return edges.size();
  };
  EXPECT_EQ(count({{-5, -5}, {5, -5}, {5, 5}, {-5, 5}}), 4u);
  EXPECT_EQ(count({{-5, -5}, {5, -5}, {5, 5}, {-5, 5}, {-4, -4}, {4, -4}, {4, 4}, {-4, 4}}), 8u);
  EXPECT_EQ(count({{3, -5}, {5, -5}, {5, 5}, {3, 5}}), 0u);  // beside it
  EXPECT_EQ(count({{-5, 5}, {5, 5}, {5, -5}, {-5, -5}}), 4u);  // clockwise: the outline clockwise
}

}  // namespace
}  // namespace exacity
