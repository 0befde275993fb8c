// Lot layouts (docs/design.md, Lots): how a block is cut into lots, one layout per zone
// type from its "lots" setting (the table of lot layouts, parcel_settings.h): allocation
// measured from the street (generate/parcels/allocation.cpp), the recursive split
// (generate/parcels/split.cpp) or the lot library (generate/parcels/library_lots.cpp). A
// layout plans from the block alone; the lots stage puts every plan into the map at once.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "generate/city/random.h"
#include "generate/city/zone_settings.h"
#include "generate/parcels/blocks.h"
#include "generate/parcels/parcel_settings.h"
#include "generate/placement/model_library.h"

namespace exacity {

// A planned lot: a ring of grid points, counter-clockwise (allocated lots), or an exact part
// of the block (split lots).
struct PlannedLot {
  int block = -1;
  ZoneType zone = ZoneType::Residential;
  geom::Ring ring;
  geom::Cell cell;
  std::optional<int> model = std::nullopt;  // a library lot's model
};

class LotLayout {
 public:
  virtual ~LotLayout() = default;
  // The lots of `block` (its index in the city's blocks: `index`).
  virtual std::vector<PlannedLot> plan(const Block& block, int index, Random& rng) const = 0;
};

// The library's lots for the zone's building entries that carry one; none when it has none.
std::unique_ptr<LotLayout> make_library_lots(const ModelLibrary& library, ZoneType zone, const Channels& channels);

}  // namespace exacity
