#include "generate/city/water_outline.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

#include "geom/grid.h"

namespace exacity {

namespace {

// A block of pixels is at least this wide on the ground, so that the samples at the blocks'
// centres and at the bounds lie at least two grid steps apart once on the grid, and every
// crossing between two of them can sit on a grid point strictly between them.
constexpr double kMinBlock = 6 * geom::kGridStep;

// One axis of the lattice the contour is traced on, from the low bound up: the blocks of
// pixels along it (single pixels unless pixels are finer than kMinBlock) and the sample
// lines: an outside sample at the low bound, the low bound, each block's centre, the high
// bound and an outside sample at it. The outside samples are land and lie on the bounds,
// so the zero-length cells between them close the rings along the bounds.
struct Axis {
  std::vector<int> first_pixel;  // block b covers pixels [first_pixel[b], first_pixel[b + 1])
  std::vector<double> at;        // the sample lines, on the grid, not decreasing

  Axis(int pixels, double low, double high) {
    const double pixel = (high - low) / pixels;
    const int per_block = pixel >= kMinBlock ? 1 : static_cast<int>(std::ceil(kMinBlock / pixel));
    const int centred = pixels / per_block;  // 0 when even all pixels together are too narrow
    const int blocks = std::max(centred, 1);
    for (int b = 0; b <= blocks; ++b)
      first_pixel.push_back(static_cast<int>(static_cast<std::int64_t>(b) * pixels / blocks));
    at = {geom::snap(low), geom::snap(low)};
    for (int b = 0; b < centred; ++b)
      at.push_back(geom::snap(low + (high - low) * (first_pixel[b] + first_pixel[b + 1]) / (2.0 * pixels)));
    at.push_back(geom::snap(high));
    at.push_back(geom::snap(high));
  }
  int blocks() const { return static_cast<int>(first_pixel.size()) - 1; }
  int samples() const { return static_cast<int>(at.size()); }
  // The block a sample takes its value from (the bounds take the nearest block's), -1 outside.
  int block_of(int sample) const {
    if (sample == 0 || sample == samples() - 1) return -1;
    return std::clamp(sample - 2, 0, blocks() - 1);
  }
};

// The water mask in blocks (block (i, j), j counted from the south, is water where any of
// its pixels is), filtered where the contour needs it.
class BlockMask {
 public:
  BlockMask(const std::vector<char>& water, int width, int height, const Axis& x, const Axis& y)
      : columns_(x.blocks()), rows_(y.blocks()), water_(static_cast<std::size_t>(columns_) * rows_, 0) {
    for (int row = 0; row < height; ++row) {
      const int south = height - 1 - row;
      const auto above = std::upper_bound(y.first_pixel.begin(), y.first_pixel.end(), south);
      const int j = static_cast<int>(above - y.first_pixel.begin()) - 1;
      for (int i = 0, col = 0; col < width; ++col) {
        while (col >= x.first_pixel[i + 1]) ++i;
        if (water[static_cast<std::size_t>(row) * width + col]) water_[index(i, j)] = 1;
      }
    }
  }

  // Past the map's edge its edge blocks repeat.
  bool water(int i, int j) const { return water_[index(std::clamp(i, 0, columns_ - 1), std::clamp(j, 0, rows_ - 1))]; }

  struct Filtered {
    double value;
    // Water thinner than the filter (a lone pixel, a river a pixel wide) sinks to 1/2 or
    // below, and land that thin rises: such a block is lifted back to 3/4 (land lowered to
    // 1/4), as beside a straight edge, so that its side of 1/2 is its own and no water is
    // lost; the filter then says nothing about where its edges lie.
    bool lifted;
  };
  // The binomial filter (1 2 1)/4 across and along: a straight edge of water keeps its place
  // (3/4 beside 1/4) and a staircase of pixels becomes a slope. Its values are sixteenths,
  // exact.
  Filtered filtered(int i, int j) const {
    const double weight[3] = {0.25, 0.5, 0.25};
    double f = 0;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) f += weight[di + 1] * weight[dj + 1] * water(i + di, j + dj);
    if (water(i, j)) return f > 0.5 ? Filtered{f, false} : Filtered{0.75, true};
    return f < 0.5 ? Filtered{f, false} : Filtered{0.25, true};
  }

 private:
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * columns_ + i; }
  int columns_, rows_;
  std::vector<char> water_;
};

// Drops the middle of three corners on one vertical or horizontal line (runs along the
// bounds, or along a straight edge of pixels), across the seam too. The contour never turns
// back along such a line, so each run keeps its two ends.
geom::Ring merge_axis_runs(const geom::Ring& r) {
  geom::Ring out;
  const std::size_t n = r.size();
  for (std::size_t i = 0; i < n; ++i) {
    const geom::Vec2 a = r[(i + n - 1) % n], b = r[i], c = r[(i + 1) % n];
    if (!((a.x == b.x && b.x == c.x) || (a.y == b.y && b.y == c.y))) out.push_back(b);
  }
  return out;
}

}  // namespace

// Marching squares through the blocks' centres (docs/design.md, Terrain): the contour at
// 1/2 of the filtered mask, each crossing placed along its cell edge by linear
// interpolation and then put on the grid, strictly between the edge's ends. A cell's pieces join crossings on
// different edges and never cross, so the rings stay simple and apart on the grid.
std::vector<geom::Ring> water_outline(const std::vector<char>& water, int width, int height, const geom::Box& bounds) {
  const Axis x(width, bounds.min_x, bounds.max_x), y(height, bounds.min_y, bounds.max_y);
  const BlockMask mask(water, width, height, x, y);
  const int nx = x.samples(), ny = y.samples();
  // Samples outside are land, 0; the filtered value is above 1/2 exactly at water.
  auto wet = [&](int i, int k) {
    return x.block_of(i) >= 0 && y.block_of(k) >= 0 && mask.water(x.block_of(i), y.block_of(k));
  };
  auto filtered = [&](int i, int k) {
    return x.block_of(i) < 0 || y.block_of(k) < 0 ? BlockMask::Filtered{0, false}
                                                  : mask.filtered(x.block_of(i), y.block_of(k));
  };
  // Lattice edges: (i, k) -> (i + 1, k) and then (i, k) -> (i, k + 1), numbered.
  const std::int64_t horizontal = static_cast<std::int64_t>(ny) * (nx - 1);
  auto east = [&](int i, int k) { return static_cast<std::int64_t>(k) * (nx - 1) + i; };
  auto north = [&](int i, int k) { return horizontal + static_cast<std::int64_t>(k) * nx + i; };
  auto crossing = [&](std::int64_t edge) {
    const bool along_x = edge < horizontal;
    const std::int64_t e = along_x ? edge : edge - horizontal;
    const int stride = along_x ? nx - 1 : nx;
    const int i = static_cast<int>(e % stride), k = static_cast<int>(e / stride);
    const int ib = along_x ? i + 1 : i, kb = along_x ? k : k + 1;
    const BlockMask::Filtered a = filtered(i, k), b = filtered(ib, kb);
    // Beside a lifted block the filter says nothing: the crossing stays on the pixel edge.
    const double t = a.lifted || b.lifted ? 0.5 : (a.value - 0.5) / (a.value - b.value);
    const double lo = along_x ? x.at[i] : y.at[k], hi = along_x ? x.at[i + 1] : y.at[k + 1];
    const double v =
        lo == hi ? lo : std::clamp(geom::snap(lo + (hi - lo) * t), lo + geom::kGridStep, hi - geom::kGridStep);
    return along_x ? geom::Vec2{v, y.at[k]} : geom::Vec2{x.at[i], v};
  };

  // Each piece runs from the crossing where the cell's corners, taken counter-clockwise, go
  // from water to land to one where they go from land to water: water on its left.
  std::vector<std::int64_t> starts;  // in lattice order, so the rings come out in it
  std::unordered_map<std::int64_t, std::int64_t> next;
  for (int k = 0; k + 1 < ny; ++k)
    for (int i = 0; i + 1 < nx; ++i) {
      const bool w[4] = {wet(i, k), wet(i + 1, k), wet(i + 1, k + 1), wet(i, k + 1)};
      if (w[0] == w[1] && w[1] == w[2] && w[2] == w[3]) continue;
      const std::int64_t edge[4] = {east(i, k), north(i + 1, k), east(i, k + 1), north(i, k)};
      // A saddle (water at opposite corners) joins the water across the cell where the
      // cell's centre, the mean of its corners, is water (ties too: a river a pixel wide
      // running diagonally stays one river), else it cuts the two water corners off.
      const bool saddle = w[0] == w[2] && w[1] == w[3];
      const bool joined = saddle && filtered(i, k).value + filtered(i + 1, k).value + filtered(i + 1, k + 1).value +
                                            filtered(i, k + 1).value >=
                                        2;
      for (int m = 0; m < 4; ++m) {
        if (!w[m] || w[(m + 1) % 4]) continue;  // not a crossing from water to land
        int to = (m + 3) % 4;                   // the entry before it
        if (!saddle) {
          while (w[to] || !w[(to + 1) % 4]) to = (to + 3) % 4;
        } else if (joined) {
          to = (m + 1) % 4;
        }
        starts.push_back(edge[m]);
        next[edge[m]] = edge[to];
      }
    }

  std::vector<geom::Ring> rings;
  std::unordered_set<std::int64_t> done;
  for (std::int64_t start : starts) {
    if (done.count(start)) continue;
    geom::Ring ring;
    for (std::int64_t e = start; done.insert(e).second; e = next.at(e)) {
      const geom::Vec2 p = crossing(e);
      if (ring.empty() || !(ring.back() == p)) ring.push_back(p);  // the bounds' corners repeat
    }
    if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    ring = merge_axis_runs(ring);
    if (ring.size() >= 3) rings.push_back(std::move(ring));
  }
  return rings;
}

}  // namespace exacity
