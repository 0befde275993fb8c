#include "generate/city/drawn_zones.h"

#include <algorithm>

namespace exacity {

DrawnZones::DrawnZones(const std::vector<ZoneFeature>& zones, geom::PlanarMap& map, int first_counter)
    : first_(first_counter) {
  for (int z = 0; z < static_cast<int>(zones.size()); ++z) {
    for (int p = 0; p < static_cast<int>(zones[z].polygons.size()); ++p) {
      const geom::Polygon& poly = zones[z].polygons[p];
      map.add_ring(poly.outer, end_counter());
      rings_.push_back({z, p, 0});
      for (int h = 0; h < static_cast<int>(poly.holes.size()); ++h) {
        map.add_ring(poly.holes[h], end_counter());
        rings_.push_back({z, p, h + 1});
      }
    }
  }
}

int DrawnZones::top_zone(const geom::Windings& w) const {
  int top = -1;
  // Counters run zone by zone, polygon by polygon, so one polygon's rings are adjacent;
  // windings list only non-zero entries.
  for (std::size_t i = 0; i < w.size();) {
    int c = w[i].first;
    if (c < first_ || c >= end_counter()) { ++i; continue; }
    const RingRef& first = rings_[c - first_];
    bool outer = false, hole = false;
    for (; i < w.size() && w[i].first >= first_ && w[i].first < end_counter(); ++i) {
      const RingRef& r = rings_[w[i].first - first_];
      if (r.zone != first.zone || r.polygon != first.polygon) break;
      (r.ring == 0 ? outer : hole) = true;
    }
    if (outer && !hole) top = std::max(top, first.zone);
  }
  return top;
}

}  // namespace exacity
