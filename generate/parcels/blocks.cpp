#include "generate/parcels/blocks.h"

#include <optional>

#include "geom/measure.h"

namespace exacity {

namespace {

// The use of the planned land holding a point inside the block, if any.
const Terminal* use_of(const geom::Cell& cell, const std::vector<PlannedUse>& uses) {
  if (uses.empty()) return nullptr;
  const std::optional<geom::Vec2> inside = cell.point_inside_near(cell.centroid());
  if (!inside) return nullptr;
  for (const PlannedUse& u : uses)
    if (geom::odd_crossings(u.ring, *inside)) return &u.use;
  return nullptr;
}

}  // namespace

std::vector<Block> cut_blocks(CityMap& city_map, const CitySettings& city, const std::vector<ZoneFeature>& zones,
                              const std::vector<PlannedUse>& uses) {
  // The roads are the map's last batch before the lots; each block's lots are made in a map
  // of its cell alone (CityLots), which must be its edges as the city's map keeps them.
  city_map.map.snap_round();
  const std::vector<int> group = city_map.per_label([&](const FaceLabel& f) {
    return f.cover == Cover::Zone && grows_roads(zones[f.zone].type) ? static_cast<int>(zones[f.zone].type)
                                                                             : -1;
  });
  const std::vector<int> road_across =
      city_map.per_label([](const FaceLabel& f) { return f.road_surface() ? f.road : BlockEdge::kNoRoad; });
  std::vector<Block> blocks;
  std::vector<int> types, components;
  std::vector<geom::Cell> cells = city_map.map.cells(group, road_across, &types, &components);
  std::vector<int> block_of_component(components.empty() ? 0 : components.back() + 1, -1);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    geom::Cell& cell = cells[i];
    Block b;
    b.polygon = cell.to_plain();
    block_of_component[components[i]] = static_cast<int>(blocks.size());
    b.zone = static_cast<ZoneType>(types[i]);
    const BlockSettings& p = city.zone_settings.at(b.zone).blocks;
    double a = geom::area(b.polygon);
    const Terminal* use = use_of(cell, uses);
    // A block whose outline rounds to nothing (a sliver narrower than a double's step, left
    // where two zones' edges nearly meet) is green space, not dropped: its faces keep a
    // block, so the written blocks cover every written zone, whose rounding as one map may
    // keep the sliver.
    if (b.polygon.outer.empty() || a < p.min_block_area || 2 * a / geom::perimeter(b.polygon) < p.min_block_width ||
        (use && use->kind == Terminal::Park)) {
      b.green = true;
      b.zone = ZoneType::Park;
    } else if (use && use->kind == Terminal::Land) {
      b.density = use->density;
    }
    for (int k : cell.edge_kinds())
      if (BlockEdge::is_road(k)) b.roads.push_back(k);
    b.cell = std::move(cell);
    blocks.push_back(std::move(b));
  }
  // Each face learns its block (an edge-connected component of faces bounds one cell).
  std::pair<int, int> last{-1, -1};  // a component's faces mostly share one label
  int last_component = -1;
  city_map.map.relabel_components(group, [&](int c, int label) {
    if (c != last_component || label != last.first) {
      FaceLabel l = city_map.labels[label];
      l.block = block_of_component[c];
      last = {label, city_map.label_index(l)}, last_component = c;
    }
    return last.second;
  });
  return blocks;
}

}  // namespace exacity
