// Noding in doubles by snap rounding to a fixed grid, as careful floating-point geometry
// code does it (Hobby, "Practical segment intersection with finite precision output",
// 1999): only the robustness benchmark's practitioner build (geom/exact.h, the snapped
// kernel) uses it, in place of the exact sweep's constructed intersections.
#pragma once

#include <utility>
#include <vector>

#include "geom/plain.h"

namespace geom {

// The snap tolerance, in grid steps (measured in x and y apart): an end this near a vertex
// of the arrangement moves onto it, and a segment passing this near an end (but not this
// near its own ends) is routed through that end.
inline constexpr double kEndReach = 2.5;

// The nearest point of the grid of `step`.
Vec2 snap_to(Vec2 p, double step);

// Each segment's ends snapped to the grid of `step` but a `monotone` segment's (vertices the
// arrangement has, kept where they are), an end within kEndReach of an end of a `monotone`
// segment moved onto it; the pixels (squares of
// side `step` around grid points) holding an end or a crossing of two segments are hot, but
// for a crossing within a pixel of an end of either segment where the other is routed
// through that end; each segment becomes the polyline from its snapped start through the
// centre of every hot pixel it passes through (and of every end it passes within kEndReach
// of), in order, to its snapped end. Rounded so, segments meet only at shared vertices
// (they may overlap: equal pieces). A segment that snaps to one point gives an empty
// polyline. Pixels are tested in doubles, a hair wider than half a step; then each piece
// again until none meets a hot pixel not its own (iterated snap rounding). The first
// `monotone` segments (or those it marks) run one way in (x, y) order, as the pieces of a
// split arrangement edge must: a hot pixel that would turn one back is passed by (a
// crossing left unnoded, the rare price).
// In the grid build (geom/grid_kernel.h) every end, the `monotone` segments' too, is snapped
// for the rounding, and each hot pixel is then written at one point inside it: an end of a
// `monotone` segment or of one `given` marks (edges given as doubles: the sketch's rings)
// where it was; a crossing on a `given` segment as computed on its ends; a pixel a
// `monotone` or `given` segment is routed through, on that segment; any other at its grid
// point. Pieces of a `monotone` segment run one way as written. So the sketch's corners
// stay as drawn and only constructed points land on the grid.
std::vector<Polyline> snap_round_segments(const std::vector<std::pair<Vec2, Vec2>>& segments, double step,
                                          const std::vector<bool>& monotone = {}, const std::vector<bool>& given = {});

}  // namespace geom
