// The grid build's kernel (EXACITY_FLOAT_KERNEL 5; geom/exact.h includes this header for it
// alone): the practitioner's float pipeline as the robustness issue describes it, the
// snapped build on plain doubles with a practitioner's grid. Constructed points (road ends,
// crossings, projections) are snapped to a decimal grid of 1e-6 m and tested again on it;
// equality of constructed points is tested on that grid; each batch is noded by one pass of
// snap rounding on it (geom/snap_noding.h, kSnapRounds), not iterated, with the sketch's own
// corners, the map's vertices and crossings on drawn edges written where they lie, not at
// their pixels' grid points (Placement); predicates round.
// A decimal grid's points are not exact doubles, so three points that the grid puts on one
// line are only nearly collinear in doubles: the orientation tests that iterated snap
// rounding on 2^-24 m keeps exact (docs/benchmarks.md) can come out wrong here.
#pragma once

#include <CGAL/Simple_cartesian.h>

#include "geom/snap_noding.h"

// 1e-6 m: the round figure a practitioner picks, below the validator's 1 µm so a snapped
// point (at most 0.71 µm off) stays within it of the edge it was computed on.
#define EXACITY_SNAP_STEP 1e-6

namespace geom::exact {

using Kernel = CGAL::Simple_cartesian<double>;
inline constexpr const char* kKernelName = "float grid (Simple_cartesian<double>, constructions on a 1e-6 m grid, noded in one pass)";

}  // namespace geom::exact
