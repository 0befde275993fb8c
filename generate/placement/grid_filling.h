// Grid filling (docs/design.md, Placement): a lot piece laid over a grid of
// square cells in its frontage's frame, free or blocked; each model's footprint grid (the
// cells its real outline covers, so an L leaves its notch free); models placed largest
// first, each at the first free place along a serpentine curve (one row along the street,
// the next back), facing the road edge nearest that place. With nesting, a 3D occupancy
// grid: a stack of footprint grids, one per slab (slabs.h) over its units of
// height, so a smaller model may stand under another's overhang. The grid only proposes:
// the lot's Occupancy, exact, has the last word.
#pragma once

#include <memory>
#include <vector>

#include "generate/placement/placer.h"

namespace exacity {

// The cells a footprint covers, row by row from its lower-left cell.
struct FootprintGrid {
  struct Rect {
    int i0, j0, i1, j1;  // cells [i0, i1) x [j0, j1)
  };
  int width = 0, height = 0;  // cells
  std::vector<char> covered;  // width * height
  geom::Vec2 corner;          // the outline's lower-left bounding corner, in its own frame
  int cells = 0;              // covered cells
  std::vector<Rect> rects;    // the covered cells as rectangles: runs of rows alike
  bool at(int i, int j) const { return covered[static_cast<std::size_t>(j) * width + i] != 0; }
};

// The cells of side `cell` that the ring (in its own frame) overlaps, its bounding box's
// lower-left at a cell corner: a cell counts when the ring enters its square at all, so a
// footprint standing on free cells stands on free ground.
FootprintGrid footprint_grid(const geom::Ring& outline, double cell);

// The same test for several rings (a slab's pieces, the 3D occupancy grid) on the
// cells of another footprint grid: its corner and size.
FootprintGrid footprint_grid_within(const std::vector<geom::Ring>& rings, const FootprintGrid& frame, double cell);

// The serpentine order of a grid's cells: row 0 left to right, row 1 right to left, ...
std::vector<std::pair<int, int>> serpentine(int width, int height);

// Grid filling's settings ("placement": "grid").
struct GridFillingSettings {
  double cell = 1;    // m: the grid's cell ("grid_cell")
  int passes = 1;     // how many times a lot is filled ("grid_passes")
  // Nesting, a 3D occupancy grid: a model may stand under another's overhang.
  bool nesting = false;
};

// Grid filling as a zone chose it.
class GridFillingChoice : public PlacerChoice {
 public:
  explicit GridFillingChoice(const GridFillingSettings& settings) : PlacerChoice("grid"), settings_(settings) {}
  std::unique_ptr<Placer> make(const ModelLibrary& library, ZoneType zone, const Channels& channels) const override;
  bool nests() const override { return settings_.nesting; }
  const GridFillingSettings& settings() const { return settings_; }

 private:
  GridFillingSettings settings_;
};

// Grid filling with the library's building models for the zone (none when it has none),
// drawn by their weights and channels where the lot stands.
std::unique_ptr<Placer> make_grid_filler(const ModelLibrary& library, ZoneType zone, const Channels& channels,
                                         const GridFillingSettings& settings);

}  // namespace exacity
