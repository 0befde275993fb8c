// Exacity's own trees and lamps (docs/design.md, Placement: built-in models): small meshes
// made in code, so a city whose sketch names no model library, or one without trees or
// lamps, still has trees in its gardens, parks and residential streets and lamps along its
// streets. They join the library as entries like any other (kind, zones, spacing, offset),
// so they go through the same placement, checks and outputs as the library's own.
#pragma once

#include <optional>

#include "generate/city/features.h"
#include "generate/placement/model_library.h"

namespace exacity {

// The meshes, in metres, z up, standing on z = 0 around the origin; a lamp's arm reaches
// towards -y, its front (where the road is once placed).
TriangleMesh broadleaf_mesh();  // a round crown on a trunk, about 6.5 m tall
TriangleMesh conifer_mesh();    // three stacked cones on a short trunk, about 9 m tall
TriangleMesh lamp_mesh();       // a pole with an arm and a head, about 6 m tall

// Adds the built-in models of each kind the sketch asks for ("builtin_models", both by
// default) that the library has no entry of: trees (a broadleaf and a conifer) in
// residential and park zones, lamps in every zone. A library is made when there is none
// and something is added; its `file` stays empty.
void add_builtin_models(std::optional<ModelLibrary>& library, bool trees, bool lamps);

}  // namespace exacity
