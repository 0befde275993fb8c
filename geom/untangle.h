// Rounding a snap-rounded polygon to doubles moves no edge across another (PlanarMap::
// snap_round), but it can collapse parts of it: a neck narrower than a double's step
// becomes one vertex or one edge run both ways, a hole can come to touch its outer ring.
// The rings are then no longer simple; these are the simple polygons they bound.
#pragma once

#include <vector>

#include "geom/plain.h"

namespace geom {

// `rings` are the rounded rings of one polygon, the interior on the left of every edge
// (outer counter-clockwise, holes clockwise), free of crossings. Returns simple polygons
// covering what they enclose: edges run both ways cancel, each boundary is walked turning
// as tightly as possible and cut where it touches itself; counter-clockwise loops are outer
// rings, clockwise ones holes of the smallest outer ring around them (a hole may touch it
// at a vertex). When no rounded vertex repeats, the rings come back as one polygon,
// unchanged. Decided exactly on the doubles.
std::vector<Polygon> untangle(const std::vector<Ring>& rings);

// Some vertex occurs twice across the rings (rounding landed two on one double pair, or
// the exact rings already touched there).
bool vertex_repeats(const std::vector<Ring>& rings);

}  // namespace geom
