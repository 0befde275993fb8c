// Models on one lot piece (docs/design.md, Placement): buildings in rows parallel to the lot's
// principal road frontage, their fronts to the road, spaced by the zone's density and
// placed largest first; street furniture along the frontage inside the setback; trees
// where room is left. Every footprint is checked exactly: strictly inside the lot piece
// (so off roads, water and parks) and apart from every footprint already there.
#pragma once

#include <vector>

#include "geom/cell.h"
#include "generate/city/random.h"
#include "generate/placement/buildings.h"
#include "generate/placement/model_library.h"
#include "generate/placement/occupancy.h"

namespace exacity {

// The same as choices_at(models, library, channels, point) where a lot piece stands: at its
// centroid.
Choices choices_at(const std::vector<int>& models, const ModelLibrary& library, const Channels* channels,
                   const geom::Cell& piece);

// Models of `kind` drawn from `choices` on the occupancy's piece.
std::vector<ModelInstance> place_models(Occupancy& occupancy, const Choices& choices, ModelKind kind,
                                        const ModelLibrary& library, const BuildingSettings& params, Random& rng);

// The model's outline turned by `angle`, scaled and moved to `position`, on the grid.
geom::Ring placed_outline(const Model& model, const Placement& p);

// The model's slabs (slabs_of) in place: outlines turned, scaled, moved and rounded as
// placed_outline's (a ring that rounds to no simple counter-clockwise one gives way to the
// whole `footprint`), heights scaled; the lowest from 0.
std::vector<Slab> placed_slabs(const Model& model, const Placement& p, const geom::Ring& footprint);

// The model standing there, its footprint `ring` (placed_outline's).
ModelInstance made(const Model& model, const Placement& p, geom::Ring ring);

}  // namespace exacity
