#include "generate/zone_map.h"

#include <map>

#include "generate/drawn_zones.h"

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

ZoneMap build_zone_map(const Sketch& sketch, const Terrain* terrain) {
  ZoneMap zm;
  constexpr int kWater = 0;
  const int road_base = 1;
  const int roads = static_cast<int>(sketch.roads.size());

  if (terrain) {
    for (auto [a, b] : terrain->water_boundary()) zm.map.add_edge(a, b, kWater);
  }
  int tag = 0;
  for (int r = 0; r < roads; ++r) {
    zm.first_line_tag.push_back(tag);
    for (const geom::Polyline& line : sketch.roads[r].lines) {
      zm.map.add_stroke(line, sketch.roads[r].width / 2, road_base + r);
      zm.map.add_polyline(line, tag++);
    }
  }
  DrawnZones drawn(sketch.zones, zm.map, road_base + roads);
  zm.map.insert_batch();

  std::map<FaceLabel, int> index;
  zm.map.label_faces([&](const geom::Windings& w) {
    FaceLabel l;
    l.zone = drawn.top_zone(w);
    for (auto [counter, winding] : w) {
      if (counter >= road_base && counter < road_base + roads) {
        l.road = counter - road_base;  // the first road listed owns a crossing
        break;
      }
    }
    bool water = geom::winding_of(w, kWater) != 0 ||
                 (l.zone >= 0 && sketch.zones[l.zone].type == ZoneType::Water);
    if (water) {
      l.cover = Cover::Water;
      l.bridge = l.road >= 0;
    } else if (l.road >= 0) {
      l.cover = Cover::Road;
    } else if (l.zone >= 0) {
      l.cover = Cover::Zone;
    }
    auto [it, added] = index.emplace(l, static_cast<int>(zm.labels.size()));
    if (added) zm.labels.push_back(l);
    return it->second;
  });
  return zm;
}

}  // namespace exacity
