// Nesting's 3D occupancy grid, made exact (docs/design.md, Placement: nesting): a model as
// a few horizontal slabs, each the height range it spans and what of the model lies in that
// range seen from above. An arch is a slab of two pillars under a slab of its beam, so a
// smaller model may stand under the beam where the two models' slabs do not meet.
#pragma once

#include <vector>

#include "generate/placement/obj_file.h"
#include "geom/plain.h"

namespace exacity {

struct Slab {
  double bottom = 0, top = 0;       // m: in the model, from its base; placed, from its floor
  std::vector<geom::Ring> outline;  // seen from above: simple, counter-clockwise, on the grid
};

// At most this many slabs a model (so a few exact ring tests a pair of models).
inline constexpr int kMaxSlabs = 4;

// The mesh's slabs, bottom to top, covering [0, height] without gaps: cut at the heights of
// the mesh's undersides (downward-facing triangles above the ground), at most kMaxSlabs.
// A slab's outline covers every triangle's part within its range (its shadow, and its
// cross-section, so vertical walls count); where that cannot be made sure (an open mesh),
// the whole `outline` stands in. A model without undersides is one slab: `outline`.
std::vector<Slab> model_slabs(const TriangleMesh& mesh, const geom::Ring& outline, double height);

// Whether two placed models' slabs meet: some slab of each spans heights that meet (closed
// ranges, counted from each one's floor) and outlines that meet (touching counts), decided
// exactly on the doubles as written.
bool slabs_meet(const std::vector<Slab>& a, double floor_a, const std::vector<Slab>& b, double floor_b);

}  // namespace exacity
