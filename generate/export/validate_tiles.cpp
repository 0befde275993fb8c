#include "generate/export/validate_tiles.h"

#include <optional>

#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::Box;
using geom::Vec2;

// Where a point outside the tile lies around it, as a position on its outline counted
// counter-clockwise: the corners even (0 lower left, 2 lower right, 4 upper right, 6 upper
// left), the open sides odd (1 below, 3 right, 5 above, 7 left). It is where the tile's
// nearest point to it lies: a corner for a point in a corner's quadrant or on its edges.
int position(Vec2 p, const Box& tile) {
  const int column = p.x <= tile.min_x ? 0 : p.x >= tile.max_x ? 2 : 1;
  const int row = p.y <= tile.min_y ? 0 : p.y >= tile.max_y ? 2 : 1;
  static constexpr int kAt[3][3] = {{0, 7, 6}, {1, -1, 5}, {2, 3, 4}};  // [column][row]
  return kAt[column][row];
}

Vec2 corner(int position, const Box& tile) {
  switch (((position % 8) + 8) % 8) {
    case 0: return {tile.min_x, tile.min_y};
    case 2: return {tile.max_x, tile.min_y};
    case 4: return {tile.max_x, tile.max_y};
    default: return {tile.min_x, tile.max_y};
  }
}

// How far the nearest point of the tile moves along its outline (in the positions above)
// as a point runs along the segment a -> b, which does not meet the tile. A segment lies in
// a half-plane the tile does not meet, so it moves at most half way round (4): less, and the
// positions' difference modulo 8 says how far; exactly, between opposite corners' quadrants,
// and it went the way the segment passes the tile's centre (exact orientation). None where
// that orientation cannot be told, which a segment apart from the tile never gives.
std::optional<int> step(Vec2 a, Vec2 b, const Box& tile) {
  int d = ((position(b, tile) - position(a, tile)) % 8 + 8) % 8;
  if (d < 4) return d;
  if (d > 4) return d - 8;
  const Vec2 centre{tile.min_x + (tile.max_x - tile.min_x) / 2, tile.min_y + (tile.max_y - tile.min_y) / 2};
  const int side = geom::ring_orientation({a, b, centre});  // +1: the centre on the left, passed counter-clockwise
  if (side == 0) return std::nullopt;
  return 4 * side;
}

bool meets(Vec2 a, Vec2 b, const Box& tile) {
  Box box = Box::none();
  box.add(a), box.add(b);
  return box.meets(tile);
}

// The path standing in for a run from u to v that moved `turn` positions around the tile:
// u, the corners passed, v. A segment from a point to a corner of its own quadrant or side,
// or between two points of one, stays in it; the corners' sides are the tile's outline.
void stand_in(Vec2 u, Vec2 v, int turn, const Box& tile, std::vector<TileEdge>& out) {
  const int from = position(u, tile), to = from + turn, dir = turn > 0 ? 1 : -1;
  Vec2 at = u;
  if (turn != 0)
    for (int p = from; p != to + dir; p += dir)
      if (((p % 2) + 2) % 2 == 0) {
        const Vec2 c = corner(p, tile);
        out.push_back({at, c, true});
        at = c;
      }
  out.push_back({at, v, true});
}

}  // namespace

void ring_near_tile(const geom::Ring& ring, const Box& tile, std::vector<TileEdge>& out) {
  const std::size_t n = ring.size();
  if (n < 2) return;
  // Each edge: kept as it is (near), or how far it turns around the tile.
  std::vector<int> turns(n, 0);
  std::vector<char> near(n, 0);
  std::size_t first_near = n;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = ring[i], b = ring[(i + 1) % n];
    std::optional<int> t;
    if (!meets(a, b, tile)) t = step(a, b, tile);
    if (t) turns[i] = *t;
    else near[i] = 1, first_near = std::min(first_near, i);
  }
  if (first_near == n) {  // far from the tile: it winds around all of it, or none
    int turn = 0;
    for (int t : turns) turn += t;
    const int windings = turn / 8;
    for (int w = 0; w < std::abs(windings); ++w)
      for (int k = 0; k < 4; ++k) {
        const int p = windings > 0 ? 2 * k : -2 * k;
        out.push_back({corner(p, tile), corner(p + (windings > 0 ? 2 : -2), tile), true});
      }
    return;
  }
  // From the first near edge round: near edges as they are, each run of far ones stood in for.
  for (std::size_t k = 0; k < n;) {
    const std::size_t i = (first_near + k) % n;
    if (near[i]) {
      out.push_back({ring[i], ring[(i + 1) % n], false});
      ++k;
      continue;
    }
    int turn = 0;
    std::size_t j = i;
    for (; k < n && !near[(first_near + k) % n]; ++k) j = (first_near + k) % n, turn += turns[j];
    stand_in(ring[i], ring[(j + 1) % n], turn, tile, out);
  }
}

}  // namespace exacity
