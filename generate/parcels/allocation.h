// Lots measured from the street (docs/design.md, Lots), the "allocation" lot layout: its
// settings, and its lots before the map cuts them.
#pragma once

#include <vector>

#include "generate/parcels/lot_layout.h"

namespace exacity {

// Allocation's settings ("lots": "allocation"); the defaults are a residential zone's.
struct AllocationSettings {
  Range lot_width{14, 24};  // m: frontage of a lot, drawn per street side
  double lot_depth = 30;    // m: how far lots reach back from the street
  double min_lot_edge = 3;  // m: lots with a shorter edge are dropped
  // m: when given, frontages at equal steps of their distribution (a real place's, as
  // --like measures it): each lot's drawn from it in turn along the street, in place of
  // lot_width; the industrial zone's open yards are then the place's own, so no lot is left out.
  std::vector<double> lot_frontages;
  // The zone's lots fill their blocks to a real place's coverage of its land (the zone's
  // lot_coverage, which --like sets), whose open yards that coverage holds: no lot is left out.
  bool fills_blocks = false;
};

// Allocation as a zone chose it.
class AllocationChoice : public LotLayoutChoice {
 public:
  explicit AllocationChoice(const AllocationSettings& settings) : LotLayoutChoice("allocation"), settings_(settings) {}
  std::unique_ptr<LotLayout> make(ZoneType zone, const ModelLibrary* library, const Channels& channels) const override;
  const AllocationSettings& settings() const { return settings_; }

 private:
  AllocationSettings settings_;
};

// Lots measured from the street (docs/design.md, Lots): along every run of road edges of the block
// (BlockEdge::is_road), lots side by side, about `lot_width` wide (or each as wide as drawn
// from `lot_frontages`, all of a run's scaled alike so that they fill it) and `lot_depth` deep (at most
// half the way across the block), split at the run's corners along the corner's bisector;
// the block's middle is left open. Rings in doubles, not yet on the grid; each reaches a
// little past the block's edge, so the map cuts it back exactly there.
std::vector<geom::Ring> street_lots(const geom::Cell& block, const AllocationSettings& p, Random& rng);

}  // namespace exacity
