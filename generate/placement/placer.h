// Placers (docs/design.md, Placement): the ways a lot is filled. Extruded footprints in a
// row along the street (generate/placement/buildings.cpp), rows of library buildings
// facing the road, street furniture and trees (generate/placement/
// model_placement.cpp). Each zone type has its placers, run on every lot in order; each
// proposes places in doubles and keeps those its lot's Occupancy lets it take.
#pragma once

#include <memory>
#include <vector>

#include "generate/city/channels.h"
#include "generate/city/random.h"
#include "generate/city/features.h"
#include "generate/parcels/lots.h"
#include "generate/placement/buildings.h"
#include "generate/placement/model_library.h"
#include "generate/placement/occupancy.h"

namespace exacity {

class Placer {
 public:
  virtual ~Placer() = default;
  // Adds what it places on the lot to `out`.
  virtual void place(const Lot& lot, const BuildingSettings& params, Occupancy& occupancy, Random& rng,
                     Structures& out) const = 0;
};

// Rows of the library's models of `kind` for the zone (none when it has none), drawn by
// their weights and channels where the lot stands.
std::unique_ptr<Placer> make_model_placer(const ModelLibrary& library, ZoneType zone, ModelKind kind,
                                          const Channels& channels);

// The lot library: each lot's own model (Lot::model) in the middle of it, facing the
// street.
std::unique_ptr<Placer> make_own_lot_placer(const ModelLibrary& library);

}  // namespace exacity
