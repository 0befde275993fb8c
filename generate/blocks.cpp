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
  std::vector<int> group(zm.labels.size(), -1), road_across(zm.labels.size(), -1);
  for (std::size_t l = 0; l < zm.labels.size(); ++l) {
    const FaceLabel& f = zm.labels[l];
    if (f.cover == Cover::Zone && grows_roads(sketch.zones[f.zone].type))
      group[l] = static_cast<int>(sketch.zones[f.zone].type);
    if (f.road >= 0 && (f.cover == Cover::Road || f.bridge)) road_across[l] = f.road;
  }
  std::vector<Block> blocks;
  std::vector<int> types;
  std::vector<geom::Cell> cells = zm.map.cells(group, road_across, &types);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    geom::Cell& cell = cells[i];
    Block b;
    b.polygon = cell.to_plain();
    if (b.polygon.outer.empty()) continue;
    b.zone = static_cast<ZoneType>(types[i]);
    const ZoneParams& p = sketch.zone_params.at(b.zone);
    double a = area(b.polygon);
    if (a < p.min_block_area || 2 * a / perimeter(b.polygon) < p.min_block_width) {
      b.green = true;
      b.zone = ZoneType::Park;
    }
    for (int k : cell.edge_kinds())
      if (k >= 0) b.roads.push_back(k);
    b.cell = std::move(cell);
    blocks.push_back(std::move(b));
  }
  return blocks;
}

}  // namespace exacity
