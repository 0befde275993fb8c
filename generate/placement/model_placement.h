// Models on one lot piece (seeds 001 and 002): buildings in rows parallel to the lot's
// principal road frontage, their fronts to the road, spaced by the zone's density and
// placed largest first; street furniture along the frontage inside the setback; trees
// where room is left. Every footprint is checked exactly: strictly inside the lot piece
// (so off roads, water and parks) and apart from every footprint already there.
#pragma once

#include <vector>

#include "generate/city/channels.h"
#include "generate/city/random.h"
#include "generate/placement/buildings.h"
#include "generate/placement/model_library.h"
#include "generate/placement/occupancy.h"

namespace exacity {

// The models a placer draws from, each with its weight where it draws: the library's weight
// times its channel affinity there (seed 004).
struct Choices {
  std::vector<int> models;
  std::vector<double> weights;
  bool empty() const { return models.empty(); }
};
// `channels` may be null (no channels: the library's weights).
Choices choices_at(const std::vector<int>& models, const ModelLibrary& library, const Channels* channels, geom::Vec2 p);
// The same where a lot piece stands: at its centroid.
Choices choices_at(const std::vector<int>& models, const ModelLibrary& library, const Channels* channels,
                   const geom::Cell& piece);

// One of the choices, drawn by weight; -1 when every weight is 0.
int pick(const Choices& choices, Random& rng);

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
