#include "generate/placement/grid_filling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>

#include "generate/placement/building_settings.h"
#include "generate/placement/model_placement.h"
#include "geom/measure.h"

namespace exacity {
namespace {

using geom::Vec2;

// Whether the segment pq enters the closed box [x0, x1] x [y0, y1] (Liang-Barsky).
bool segment_meets_box(Vec2 p, Vec2 q, double x0, double y0, double x1, double y1) {
  double lo = 0, hi = 1;
  const double d[2] = {q.x - p.x, q.y - p.y}, from[2] = {p.x, p.y}, min[2] = {x0, y0}, max[2] = {x1, y1};
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0) {
      if (from[a] < min[a] || from[a] > max[a]) return false;
      continue;
    }
    double t0 = (min[a] - from[a]) / d[a], t1 = (max[a] - from[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0), hi = std::min(hi, t1);
    if (lo > hi) return false;
  }
  return true;
}

// A quarter turn `r` times, counter-clockwise.
Vec2 turned(Vec2 v, int r) {
  for (int k = 0; k < r; ++k) v = {-v.y, v.x};
  return v;
}

// Calls mark(i) for each cell i of a row of `width` cells of side `cell`, the first from
// x0, whose centre lies inside the rings (even-odd) on the row's middle line y.
template <typename Mark>
void mark_inside(const std::vector<geom::Ring>& rings, double x0, double y, double cell, int width, Mark&& mark) {
  std::vector<double> crossings;
  for (const geom::Ring& r : rings)
    for (std::size_t e = 0; e < r.size(); ++e) {
      const Vec2 a = r[e], b = r[(e + 1) % r.size()];
      if ((a.y <= y) != (b.y <= y)) crossings.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
    }
  std::sort(crossings.begin(), crossings.end());
  for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
    for (int i = std::max(0, static_cast<int>(std::ceil((crossings[k] - x0) / cell - 0.5)));
         i < width && x0 + (i + 0.5) * cell < crossings[k + 1]; ++i)
      mark(i);
}

// The lot piece over a grid in its frontage's frame: cell (i, j) is the square from
// (t0 + i cell, j cell) in (along the street, back from it).
struct LotGrid {
  Frontage f;
  double cell = 1;
  int width = 0, height = 0;
  std::vector<char> blocked;
  std::vector<int> facing;      // per cell: the quarter turn that faces the nearest street
  std::vector<int> sums;        // blocked cells below and left of each cell corner ((width + 1) * (height + 1))
  // With nesting (the 3D occupancy grid): per cell, the levels taken (Levels); a
  // cell the lot blocks has them all. `blocked` then holds what stands on the ground.
  std::vector<std::uint64_t> levels;

  Vec2 world(double t, double d) const { return f.at(f.t0 + t, d); }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * width + i; }
  void count_blocked() {
    sums.assign(static_cast<std::size_t>(width + 1) * (height + 1), 0);
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i)
        sums[corner(i + 1, j + 1)] = blocked[index(i, j)] + sums[corner(i, j + 1)] + sums[corner(i + 1, j)] - sums[corner(i, j)];
  }
  // Whether the cells of r, moved by (i, j), all on the grid, are free.
  bool free(const FootprintGrid::Rect& r, int i, int j) const {
    return sums[corner(i + r.i1, j + r.j1)] - sums[corner(i + r.i0, j + r.j1)] - sums[corner(i + r.i1, j + r.j0)] +
               sums[corner(i + r.i0, j + r.j0)] ==
           0;
  }

 private:
  std::size_t corner(int i, int j) const { return static_cast<std::size_t>(j) * (width + 1) + i; }
};

// The largest a lot's grid may be (256 x 256 one-metre cells): a coarser cell for larger
// lots keeps the fill quick.
constexpr double kMaxCells = 1 << 16;

LotGrid lay_grid(const Occupancy& occupancy, const BuildingSettings& params, double cell, bool nesting) {
  LotGrid g;
  g.f = occupancy.frontage();
  const double length = g.f.t1 - g.f.t0, depth = g.f.depth;
  cell = std::max(cell, std::sqrt(length * depth / kMaxCells));
  g.cell = cell;
  g.width = static_cast<int>(std::ceil(length / cell)), g.height = static_cast<int>(std::ceil(depth / cell));
  g.blocked.assign(static_cast<std::size_t>(g.width) * g.height, 0);
  g.facing.assign(g.blocked.size(), 0);
  // A cell is free when its square lies inside the piece, `setback` from the street and
  // half the building gap from the piece's other edges: inside by the crossings of its
  // row's middle line, then each edge blocks the cells near it.
  const std::vector<geom::KindedRing> rings = occupancy.piece().kinded_rings();
  auto frame = [&](Vec2 p) {
    const Vec2 d = p - g.f.a;
    return Vec2{d.x * g.f.u.x + d.y * g.f.u.y - g.f.t0, d.x * g.f.n.x + d.y * g.f.n.y};
  };
  std::vector<geom::Ring> in_frame;
  for (const geom::KindedRing& r : rings) {
    in_frame.emplace_back();
    for (Vec2 p : r.points) in_frame.back().push_back(frame(p));
  }
  std::fill(g.blocked.begin(), g.blocked.end(), 1);
  for (int j = 0; j < g.height; ++j)
    mark_inside(in_frame, 0, (j + 0.5) * cell, cell, g.width, [&](int i) { g.blocked[g.index(i, j)] = 0; });
  const double half_diagonal = cell * M_SQRT1_2;
  std::vector<std::pair<Vec2, Vec2>> streets;
  for (const geom::KindedRing& r : rings)
    for (std::size_t e = 0; e < r.points.size(); ++e) {
      const Vec2 a = r.points[e], b = r.points[(e + 1) % r.points.size()];
      const bool street = r.kinds[e] == LotEdge::kStreet;
      if (street) streets.push_back({a, b});
      const double reach = (street ? params.setback : params.building_gap / 2) + half_diagonal;
      const Vec2 fa = frame(a), fb = frame(b);
      const int i0 = std::max(0, static_cast<int>(std::floor((std::min(fa.x, fb.x) - reach) / cell)));
      const int i1 = std::min(g.width - 1, static_cast<int>(std::floor((std::max(fa.x, fb.x) + reach) / cell)));
      const int j0 = std::max(0, static_cast<int>(std::floor((std::min(fa.y, fb.y) - reach) / cell)));
      const int j1 = std::min(g.height - 1, static_cast<int>(std::floor((std::max(fa.y, fb.y) + reach) / cell)));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          if (geom::distance_to_segment({(i + 0.5) * cell, (j + 0.5) * cell}, fa, fb) < reach) g.blocked[g.index(i, j)] = 1;
    }
  // Each free cell faces the street nearest it: the quarter turn whose front (the model's
  // -y) points most nearly that way. The piece lies left of its edges, the street right.
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      if (g.blocked[g.index(i, j)] || streets.empty()) continue;
      const Vec2 c = g.world((i + 0.5) * cell, (j + 0.5) * cell);
      double nearest = INFINITY;
      Vec2 towards{0, -1};
      for (auto [a, b] : streets)
        if (const double d = geom::distance_to_segment(c, a, b); d < nearest) {
          nearest = d;
          const Vec2 n = geom::left_normal(a, b);
          towards = {-(n.x * g.f.u.x + n.y * g.f.u.y), -(n.x * g.f.n.x + n.y * g.f.n.y)};
        }
      int best = 0;
      double best_dot = -INFINITY;
      for (int r = 0; r < 4; ++r) {
        const Vec2 front = turned({0, -1}, r);
        if (const double dot = front.x * towards.x + front.y * towards.y; dot > best_dot + 1e-9) best_dot = dot, best = r;
      }
      g.facing[g.index(i, j)] = best;
    }
  if (nesting)
    for (char b : g.blocked) g.levels.push_back(b ? ~std::uint64_t{0} : 0);
  g.count_blocked();
  return g;
}

// The 3D occupancy grid stacks footprint grids, one per unit of height (a cell's
// side): a bit per level from the floor up, the last standing for every level above it.
using Levels = std::uint64_t;
constexpr int kLevels = 64;
Levels levels_between(double bottom, double top, double cell) {
  const int lo = std::clamp(static_cast<int>(std::floor(bottom / cell)), 0, kLevels - 1);
  const int hi = std::clamp(static_cast<int>(std::ceil(top / cell)) - 1, lo, kLevels - 1);
  return (hi == kLevels - 1 ? ~Levels{0} : (Levels{1} << (hi + 1)) - 1) & ~((Levels{1} << lo) - 1);
}

// The covered cells as rectangles: each row's runs, a run carried up while the rows above
// have the same one.
std::vector<FootprintGrid::Rect> rectangles(const FootprintGrid& f) {
  std::vector<FootprintGrid::Rect> done, open;
  for (int j = 0; j <= f.height; ++j) {
    std::vector<FootprintGrid::Rect> runs;
    for (int i = 0; j < f.height && i < f.width;) {
      if (!f.at(i, j)) {
        ++i;
        continue;
      }
      int end = i;
      while (end < f.width && f.at(end, j)) ++end;
      runs.push_back({i, j, end, j + 1});
      i = end;
    }
    std::vector<FootprintGrid::Rect> next;
    for (FootprintGrid::Rect run : runs) {
      auto same = std::find_if(open.begin(), open.end(), [&](const auto& o) { return o.i0 == run.i0 && o.i1 == run.i1; });
      if (same != open.end()) run.j0 = same->j0, open.erase(same);
      next.push_back(run);
    }
    done.insert(done.end(), open.begin(), open.end());
    open = std::move(next);
  }
  return done;
}

// The footprint grown by k cells each way (a square's reach): along rows, then columns.
FootprintGrid grown(const FootprintGrid& f, int k) {
  FootprintGrid g;
  g.width = f.width + 2 * k, g.height = f.height + 2 * k;
  std::vector<char> rows(static_cast<std::size_t>(g.width) * f.height, 0);
  for (int j = 0; j < f.height; ++j)
    for (int i = 0, last = -1; i < g.width; ++i) {
      // The nearest covered cell at or before column i + k of f's row j, within 2k.
      const int src = i;  // g's column i spans f's columns [i - 2k, i]
      if (src < f.width && f.at(src, j)) last = src;
      rows[static_cast<std::size_t>(j) * g.width + i] = last >= 0 && src - last <= 2 * k;
    }
  g.covered.assign(static_cast<std::size_t>(g.width) * g.height, 0);
  for (int i = 0; i < g.width; ++i)
    for (int j = 0, last = -1; j < g.height; ++j) {
      if (j < f.height && rows[static_cast<std::size_t>(j) * g.width + i]) last = j;
      g.covered[static_cast<std::size_t>(j) * g.width + i] = last >= 0 && j - last <= 2 * k;
    }
  for (char c : g.covered) g.cells += c;
  g.rects = rectangles(g);
  return g;
}

// One slab of a candidate on the grid: the levels it spans, the cells it covers in its
// footprint grid's frame, and the same grown by the building gap.
struct SlabGrid {
  Levels levels = 0;
  FootprintGrid own, taken;
};

// A model drawn for the lot, before it has a place: its footprint grid for each quarter
// turn, and the same grown by the building gap (the cells it takes from later models),
// each made when first asked for; with nesting, its slabs' grids as well.
class Candidate {
 public:
  Candidate(const Model& model, int index, double scale, int tint, double cell, int gap_cells, bool nesting)
      : model_(&model), index_(index), scale_(scale), tint_(tint), cell_(cell), gap_cells_(gap_cells),
        nesting_(nesting) {}

  int index() const { return index_; }
  double scale() const { return scale_; }
  int tint() const { return tint_; }
  int gap_cells() const { return gap_cells_; }
  const FootprintGrid& footprint(int r) const {
    if (!turns_[r]) {
      geom::Ring outline;
      for (Vec2 v : model_->outline) outline.push_back(turned({v.x * scale_, v.y * scale_}, r));
      turns_[r] = footprint_grid(outline, cell_);
    }
    return *turns_[r];
  }
  const FootprintGrid& taken(int r) const {
    if (!taken_[r]) taken_[r] = grown(footprint(r), gap_cells_);
    return *taken_[r];
  }
  bool nesting() const { return nesting_; }
  // The 3D occupancy grid: each slab's cells in the footprint grid's frame, bottom to top.
  const std::vector<SlabGrid>& slabs(int r) const {
    if (!slabs_[r]) {
      slabs_[r].emplace();
      for (const Slab& s : slabs_of(*model_)) {
        std::vector<geom::Ring> rings;
        for (const geom::Ring& ring : s.outline) {
          rings.emplace_back();
          for (Vec2 v : ring) rings.back().push_back(turned({v.x * scale_, v.y * scale_}, r));
        }
        SlabGrid g{levels_between(s.bottom * scale_, s.top * scale_, cell_), footprint_grid_within(rings, footprint(r), cell_), {}};
        g.taken = grown(g.own, gap_cells_);
        slabs_[r]->push_back(std::move(g));
      }
    }
    return *slabs_[r];
  }
  // A model's size: the cells of its bounding grid, counted per level with nesting.
  int size() const {
    if (!nesting_) return footprint(0).cells;
    int cells = 0;
    for (const SlabGrid& s : slabs(0)) cells += s.own.cells * std::popcount(s.levels);
    return cells;
  }

 private:
  const Model* model_;
  int index_;
  double scale_;
  int tint_;
  double cell_;
  int gap_cells_;  // how far `taken` reaches past the footprint, in cells each way
  bool nesting_;
  mutable std::optional<FootprintGrid> turns_[4], taken_[4];
  mutable std::optional<std::vector<SlabGrid>> slabs_[4];
};

// A random model of the choices, of a random size and colour (the library's size and colour variation); none
// when no choice has weight here.
std::optional<Candidate> draw(const Choices& choices, const ModelLibrary& lib, const BuildingSettings& params,
                              double cell, bool nesting, Random& rng) {
  const std::optional<int> model = pick(choices, rng);
  if (!model) return std::nullopt;
  const Model& m = lib.models[*model];
  const double scale = rng.uniform(m.min_scale, m.max_scale);
  const int tint = static_cast<int>(rng.next() % kTints);
  // The lot's edges keep half the gap already (lay_grid); between models, the whole gap,
  // and a cell at least: footprints that touch are not apart (Occupancy).
  return Candidate{m, *model, scale, tint, cell, std::max(1, static_cast<int>(std::ceil(params.building_gap / cell - 1e-9))),
                   nesting};
}

// Whether the candidate, turned r times, fits with its footprint's lower-left cell at (i, j):
// its footprint on free cells, or with nesting, its lowest slab on free ground and each
// slab's cells free at its levels.
bool fits(const LotGrid& g, const Candidate& c, int r, int i, int j) {
  const FootprintGrid& own = c.footprint(r);
  if (i + own.width > g.width || j + own.height > g.height) return false;
  const FootprintGrid& ground = c.nesting() ? c.slabs(r).front().own : own;
  if (!std::all_of(ground.rects.begin(), ground.rects.end(), [&](const FootprintGrid::Rect& rect) { return g.free(rect, i, j); }))
    return false;
  if (!c.nesting()) return true;
  for (const SlabGrid& s : c.slabs(r))
    for (const FootprintGrid::Rect& rect : s.own.rects)
      for (int b = rect.j0; b < rect.j1; ++b)
        for (int a = rect.i0; a < rect.i1; ++a)
          if (g.levels[g.index(i + a, j + b)] & s.levels) return false;
  return true;
}

// Blocks the cells the footprint's lower-left cell at (i, j) takes (off the grid: nothing).
void mark(LotGrid& g, const FootprintGrid& f, int i, int j) {
  for (int b = 0; b < f.height; ++b)
    for (int a = 0; a < f.width; ++a)
      if (f.at(a, b) && i + a >= 0 && i + a < g.width && j + b >= 0 && j + b < g.height) g.blocked[g.index(i + a, j + b)] = 1;
  g.count_blocked();
}

// With nesting: each slab takes its levels over its cells grown by the gap, and the lowest
// slab's cells the ground (off the grid: nothing).
void mark_slabs(LotGrid& g, const Candidate& c, int r, int i, int j) {
  for (const SlabGrid& s : c.slabs(r))
    for (int b = 0; b < s.taken.height; ++b)
      for (int a = 0; a < s.taken.width; ++a)
        if (s.taken.at(a, b) && i + a >= 0 && i + a < g.width && j + b >= 0 && j + b < g.height)
          g.levels[g.index(i + a, j + b)] |= s.levels;
  mark(g, c.slabs(r).front().taken, i, j);
}

// Places one candidate at the first place along the serpentine where its footprint grid
// is free and the exact check agrees; whether it found one.
bool place_first_free(LotGrid& g, const std::vector<std::pair<int, int>>& order, const Candidate& c,
                      const ModelLibrary& lib, Occupancy& occupancy, std::vector<ModelInstance>& out) {
  constexpr int kRefusals = 16;  // exact refusals (rounding at an edge) before giving up
  int refused = 0;
  for (auto [i, j] : order) {
    const int r = g.facing[g.index(i, j)];
    if (!fits(g, c, r, i, j)) continue;
    const FootprintGrid& own = c.footprint(r);
    // The model's origin, in the frame: the footprint's lower-left cell corner less the
    // outline's lower-left bounding corner.
    const Vec2 origin = g.world(i * g.cell - own.corner.x, j * g.cell - own.corner.y);
    const Placement p{c.index(), origin, std::atan2(g.f.u.y, g.f.u.x) + r * M_PI / 2, c.scale(), c.tint()};
    geom::Ring ring = placed_outline(lib.models[c.index()], p);
    std::vector<Slab> slabs;
    if (c.nesting()) {
      slabs = placed_slabs(lib.models[c.index()], p, ring);
      const auto [base, floor] = occupancy.ground_under(ring);
      slabs.front().bottom = base - floor;  // its foundation reaches down to the lowest ground
    }
    if (!occupancy.take(ring, c.nesting() ? &slabs : nullptr)) {
      if (++refused == kRefusals) return false;
      continue;
    }
    if (c.nesting()) mark_slabs(g, c, r, i - c.gap_cells(), j - c.gap_cells());
    else mark(g, c.taken(r), i - c.gap_cells(), j - c.gap_cells());
    out.push_back(made(lib.models[c.index()], p, std::move(ring)));
    out.back().slabs = std::move(slabs);
    return true;
  }
  return false;
}

class GridFiller : public Placer {
 public:
  GridFiller(const ModelLibrary& library, std::vector<int> models, const Channels& channels,
             const GridFillingSettings& settings)
      : library_(library), models_(std::move(models)), channels_(channels), settings_(settings) {}

  void place(const Lot&, const BuildingSettings& params, Occupancy& occupancy, Random& rng,
             Structures& out) const override {
    const Frontage& f = occupancy.frontage();
    if (!(f.t1 > f.t0) || !(f.depth > 0)) return;
    LotGrid g = lay_grid(occupancy, params, settings_.cell, settings_.nesting);
    const std::vector<std::pair<int, int>> order = serpentine(g.width, g.height);
    double mean_cells = 0;
    for (int c : models_) mean_cells += library_.models[c].width * library_.models[c].depth;
    mean_cells = std::max(mean_cells / static_cast<double>(models_.size()) / (g.cell * g.cell), 1.0);
    const Choices choices = choices_at(models_, library_, &channels_, occupancy.piece());
    for (int pass = 0; pass < settings_.passes; ++pass) {
      const int free = static_cast<int>(std::count(g.blocked.begin(), g.blocked.end(), 0));
      if (free == 0) return;
      // Enough for the free cells to fill, largest first (first-fit decreasing), each a random size and colour.
      const int count = static_cast<int>(std::clamp(std::ceil(1.5 * free / mean_cells), 1.0, 256.0));
      std::vector<Candidate> candidates;
      for (int n = 0; n < count; ++n)
        if (std::optional<Candidate> c = draw(choices, library_, params, g.cell, settings_.nesting, rng)) candidates.push_back(std::move(*c));
      std::stable_sort(candidates.begin(), candidates.end(),
                       [](const Candidate& a, const Candidate& b) { return a.size() > b.size(); });
      // A model that found no place three times in a pass (at sizes no larger each time)
      // is not tried again in it; a pass that places nothing ends the filling.
      constexpr int kMisses = 3;
      std::map<int, int> misses;
      int placed = 0;
      for (const Candidate& c : candidates) {
        if (misses[c.index()] == kMisses) continue;
        if (place_first_free(g, order, c, library_, occupancy, out.models)) ++placed;
        else ++misses[c.index()];
      }
      if (placed == 0) return;
    }
  }

 private:
  const ModelLibrary& library_;
  std::vector<int> models_;
  const Channels& channels_;
  GridFillingSettings settings_;
};

}  // namespace

std::unique_ptr<Placer> GridFillingChoice::make(const ModelLibrary& library, ZoneType zone, const Channels& channels) const {
  return make_grid_filler(library, zone, channels, settings_);
}

namespace {

// Marks the cells of `f` (its corner and size set) that the rings overlap: a cell counts
// when a ring enters its square at all.
void cover(FootprintGrid& f, const std::vector<geom::Ring>& rings, double cell) {
  const double x0 = f.corner.x, y0 = f.corner.y;
  f.covered.assign(static_cast<std::size_t>(f.width) * f.height, 0);
  // Cells whose centre is inside a ring (each on its own: a slab's pieces may lie one in
  // another), by the crossings of each row's middle line...
  for (const geom::Ring& ring : rings)
    for (int j = 0; j < f.height; ++j)
      mark_inside({ring}, x0, y0 + (j + 0.5) * cell, cell, f.width,
                  [&](int i) { f.covered[static_cast<std::size_t>(j) * f.width + i] = 1; });
  // ... and those an edge enters: the open square, so an edge along a side of the square
  // only touches it and the cell beyond stays free.
  const double in = 1e-9 * cell;
  for (const geom::Ring& outline : rings)
    for (std::size_t e = 0; e < outline.size(); ++e) {
      const Vec2 a = outline[e], b = outline[(e + 1) % outline.size()];
      const int i0 = std::max(0, static_cast<int>(std::floor((std::min(a.x, b.x) - x0) / cell)) - 1);
      const int i1 = std::min(f.width - 1, static_cast<int>(std::floor((std::max(a.x, b.x) - x0) / cell)) + 1);
      const int j0 = std::max(0, static_cast<int>(std::floor((std::min(a.y, b.y) - y0) / cell)) - 1);
      const int j1 = std::min(f.height - 1, static_cast<int>(std::floor((std::max(a.y, b.y) - y0) / cell)) + 1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          char& c = f.covered[static_cast<std::size_t>(j) * f.width + i];
          const double x = x0 + i * cell, y = y0 + j * cell;
          if (!c && segment_meets_box(a, b, x + in, y + in, x + cell - in, y + cell - in)) c = 1;
        }
    }
  for (char c : f.covered) f.cells += c;
  f.rects = rectangles(f);
}

}  // namespace

FootprintGrid footprint_grid(const geom::Ring& outline, double cell) {
  FootprintGrid f;
  if (outline.size() < 3) return f;
  geom::Box box = geom::Box::none();
  for (Vec2 v : outline) box.add(v);
  f.corner = {box.min_x, box.min_y};
  // A hair under a whole cell stays one cell: outlines on the grid would otherwise spill.
  f.width = std::max(1, static_cast<int>(std::ceil(box.width() / cell - 1e-9)));
  f.height = std::max(1, static_cast<int>(std::ceil(box.height() / cell - 1e-9)));
  cover(f, {outline}, cell);
  return f;
}

FootprintGrid footprint_grid_within(const std::vector<geom::Ring>& rings, const FootprintGrid& frame, double cell) {
  FootprintGrid f;
  f.corner = frame.corner, f.width = frame.width, f.height = frame.height;
  cover(f, rings, cell);
  return f;
}

std::vector<std::pair<int, int>> serpentine(int width, int height) {
  std::vector<std::pair<int, int>> order;
  order.reserve(static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0));
  for (int j = 0; j < height; ++j)
    for (int k = 0; k < width; ++k) order.push_back({j % 2 == 0 ? k : width - 1 - k, j});
  return order;
}

std::unique_ptr<Placer> make_grid_filler(const ModelLibrary& library, ZoneType zone, const Channels& channels,
                                         const GridFillingSettings& settings) {
  std::vector<int> models = library.choices(zone, ModelKind::Building);
  if (models.empty()) return nullptr;
  return std::make_unique<GridFiller>(library, std::move(models), channels, settings);
}

std::shared_ptr<const PlacerChoice> read_grid_filler(const PlacerReading& reading) {
  const SettingsReader& s = reading.settings;
  GridFillingSettings g;
  s.number("grid_cell", g.cell, 0.1, 10);
  s.whole_number("grid_passes", g.passes, 1, 16, "passes");
  s.boolean("nesting", g.nesting);
  if (g.nesting && !reading.chosen)
    s.fail("nesting", "nesting stands models under others' overhangs in grid filling; set \"placement\": \"grid\" too, or remove it");
  return std::make_shared<GridFillingChoice>(g);
}

}  // namespace exacity
