#include "generate/blocks.h"

#include "geom/measure.h"

namespace exacity {

std::vector<Block> cut_blocks(const ZoneMap& zm, const Sketch& sketch) {
  std::vector<int> group(zm.labels.size(), -1), road_across(zm.labels.size(), -1);
  for (std::size_t l = 0; l < zm.labels.size(); ++l) {
    const FaceLabel& f = zm.labels[l];
    if (f.cover == Cover::Zone && grows_roads(sketch.zones[f.zone].type))
      group[l] = static_cast<int>(sketch.zones[f.zone].type);
    if (f.road_surface()) road_across[l] = f.road;
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
    double a = geom::area(b.polygon);
    if (a < p.min_block_area || 2 * a / geom::perimeter(b.polygon) < p.min_block_width) {
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
