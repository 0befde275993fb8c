#include "generate/blocks.h"

#include <cmath>

#include "generate/road_network.h"

namespace exacity {
namespace {

double perimeter(const geom::Polygon& p) {
  double sum = 0;
  auto ring = [&](const geom::Ring& r) {
    for (std::size_t i = 0; i < r.size(); ++i)
      sum += std::hypot(r[(i + 1) % r.size()].x - r[i].x, r[(i + 1) % r.size()].y - r[i].y);
  };
  ring(p.outer);
  for (const auto& h : p.holes) ring(h);
  return sum;
}

double area(const geom::Polygon& p) {
  auto ring = [](const geom::Ring& r) {
    double a = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      // Relative to the first vertex, so large coordinates do not swamp small areas.
      const geom::Vec2 &o = r[0], &u = r[i], &v = r[(i + 1) % r.size()];
      a += (u.x - o.x) * (v.y - o.y) - (v.x - o.x) * (u.y - o.y);
    }
    return a / 2;
  };
  double a = ring(p.outer);
  for (const auto& h : p.holes) a += ring(h);
  return a;
}

}  // namespace

std::vector<Block> cut_blocks(const ZoneMap& zm, const Sketch& sketch) {
  const int types = static_cast<int>(ZoneType::Water);
  std::vector<int> group(zm.labels.size(), -1);
  for (std::size_t l = 0; l < zm.labels.size(); ++l) {
    const FaceLabel& f = zm.labels[l];
    if (f.cover == Cover::Zone && grows_roads(sketch.zones[f.zone].type))
      group[l] = static_cast<int>(sketch.zones[f.zone].type);
  }
  std::vector<Block> blocks;
  auto parts = zm.map.dissolve(group, types);
  for (int t = 0; t < types; ++t) {
    const ZoneParams& p = sketch.zone_params.at(static_cast<ZoneType>(t));
    for (geom::Dissolved& d : parts[t]) {
      Block b;
      b.zone = static_cast<ZoneType>(t);
      double a = area(d.polygon);
      if (a < p.min_block_area || 2 * a / perimeter(d.polygon) < p.min_block_width) {
        b.green = true;
        b.zone = ZoneType::Park;
      }
      for (int l : d.neighbour_labels)
        if (l >= 0 && zm.labels[l].road >= 0 && (zm.labels[l].cover == Cover::Road || zm.labels[l].bridge))
          b.roads.push_back(zm.labels[l].road);
      std::sort(b.roads.begin(), b.roads.end());
      b.roads.erase(std::unique(b.roads.begin(), b.roads.end()), b.roads.end());
      b.polygon = std::move(d.polygon);
      blocks.push_back(std::move(b));
    }
  }
  return blocks;
}

}  // namespace exacity
