// What a part of a mesh covers seen from above, holes filled: a model's outline within one
// horizontal slab (nesting's 3D occupancy grid; docs/design.md, Placement: nesting).
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "geom/plain.h"

namespace geom {

// The union of the `shadows` (triangles seen from above) and of the region the `section`
// winds around (directed edges with the inside on their left: a closed mesh's
// cross-section, which its vertical walls alone do not cover), corners rounded to the grid
// first: each piece's outer ring, exact, simple, counter-clockwise. Holes are filled, so the
// result covers at least what the slab holds. Nothing (nullopt) when the rounded section's
// edges do not close into loops (an open or inconsistently wound mesh), or a point of
// `must_cover` (rounded) lies outside the result: the caller then falls back to a coarser
// outline that surely covers the part.
std::optional<std::vector<Ring>> filled_outline(const std::vector<std::array<Vec2, 3>>& shadows,
                                                const std::vector<std::pair<Vec2, Vec2>>& section,
                                                const std::vector<Vec2>& must_cover);

}  // namespace geom
