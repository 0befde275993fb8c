// The zones as drawn, inside a planar map: every ring winds around its own counter, and
// a face lies in a drawn polygon when the outer ring winds around it (nonzero) and no
// hole does. Where zones overlap, the later feature wins.
#pragma once

#include <vector>

#include "generate/city/features.h"
#include "geom/planar_map.h"

namespace exacity {

class DrawnZones {
 public:
  // Queues every ring of `zones` in `map`, with counters from first_counter on.
  DrawnZones(const std::vector<ZoneFeature>& zones, geom::PlanarMap& map, int first_counter);

  int end_counter() const { return first_ + static_cast<int>(rings_.size()); }

  // Index into `zones` of the last zone containing a face with these windings, or -1.
  int top_zone(const geom::Windings& w) const;

 private:
  struct RingRef {
    int zone, polygon, ring;  // ring 0 is the outer ring
  };
  std::vector<RingRef> rings_;
  int first_;
};

}  // namespace exacity
