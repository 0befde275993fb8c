// How often a drawing's strokes meet: a bound on the work of the exact map before it is built.
// Doubles only, to count (docs/design.md, Exactness rule 6: never for topology).
#pragma once

#include <cstddef>
#include <vector>

#include "geom/plain.h"

namespace geom {

// A segment drawn `radius` wide on each side (0: a line): a road's piece with its
// sidewalks, or a zone's edge. `chain` names the line or ring it is a piece of, `index` its
// place there, so the pieces that follow each other in one chain (meeting at their shared
// end) are not counted; `ring` chains also wrap from their last piece to their first.
struct FatSegment {
  Vec2 a, b;
  double radius = 0;
  int chain = 0, index = 0;
  int last_index = 0;  // the chain's last piece
  bool ring = false;
};

// The pairs of segments that come within their radii of each other (their strokes overlap
// or their lines cross), counted up to `limit` (the count then stops at the limit).
// `per_chain` gets each chain's share of the pairs counted.
std::size_t count_meetings(const std::vector<FatSegment>& segments, std::size_t limit, std::vector<std::size_t>& per_chain);

}  // namespace geom
