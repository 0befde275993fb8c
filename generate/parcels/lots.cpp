#include "generate/parcels/lots.h"

#include <map>
#include <optional>

#include <tbb/parallel_for.h>

#include "generate/city/random.h"
#include "generate/parcels/lot_layout.h"
#include "geom/measure.h"

namespace exacity {

std::vector<PlannedLot> plan_lots(const std::vector<Block>& blocks, const Sketch& sketch) {
  std::map<ZoneType, std::unique_ptr<LotLayout>> layouts;
  for (const auto& [zone, settings] : sketch.zone_settings) layouts[zone] = make_lot_layout(settings.lots);
  std::vector<std::vector<PlannedLot>> per_block(blocks.size());
  const std::uint64_t stage = mix(sketch.seed, static_cast<std::uint64_t>(Stage::Lots));
  tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t bi) {
    const Block& block = blocks[bi];
    if (block.green) return;
    Random rng(mix(stage, bi));
    per_block[bi] = layouts.at(block.zone)->plan(block, static_cast<int>(bi), rng);
  });
  std::vector<PlannedLot> lots;
  for (auto& list : per_block)
    for (auto& lot : list) lots.push_back(std::move(lot));
  return lots;
}

std::unique_ptr<LotLayout> make_lot_layout(const LotSettings& settings) {
  return settings.layout == "split" ? make_split(settings) : make_allocation(settings);
}

std::vector<Lot> insert_lots(CityMap& city_map, const std::vector<PlannedLot>& planned,
                             const Sketch& sketch) {
  city_map.lots = {city_map.generated_roads.end(), static_cast<int>(planned.size())};
  for (std::size_t l = 0; l < planned.size(); ++l) {
    const int counter = city_map.lots.at(static_cast<int>(l));
    if (planned[l].ring.empty()) city_map.map.add_cell_within(planned[l].block, planned[l].cell, counter);
    else city_map.map.add_ring_within(planned[l].block, planned[l].ring, counter);
  }
  city_map.insert_lots();
  // The last batch: the map is snap-rounded now, so every layer written from it, lots
  // included, rounds without edges crossing.
  city_map.map.snap_round();

  // Each planned lot's pieces, those that make sensible lots.
  const std::vector<int> group = city_map.per_label([](const FaceLabel& f) { return f.lot; });
  const std::vector<int> kind =
      city_map.per_label([](const FaceLabel& f) { return f.road_surface() ? LotEdge::kStreet : LotEdge::kInner; });
  std::vector<int> planned_of;
  std::vector<geom::Cell> pieces = city_map.map.cells(group, kind, &planned_of);
  std::vector<std::optional<Lot>> kept(pieces.size());
  tbb::parallel_for(std::size_t(0), pieces.size(), [&](std::size_t i) {
    const PlannedLot& plan = planned[planned_of[i]];
    // Collapsed by rounding, off the street, too small, or too narrow or shallow for its
    // frontage: left open. A lot is its rounded cell, so the buildings placed in it lie
    // inside the lot as written.
    std::optional<geom::Cell> cell = pieces[i].as_written();
    if (!cell) return;
    geom::Polygon shape = cell->to_plain();
    if (geom::area(shape) < sketch.zone_settings.at(plan.zone).lots.min_lot_area) return;
    double longest = 0, ratio = 0;
    for (auto [a, b] : cell->edges_of_kind(LotEdge::kStreet)) {
      double len = std::hypot(b.x - a.x, b.y - a.y);
      if (len > longest) longest = len, ratio = geom::depth_over_width(shape.outer, a, b);
    }
    if (ratio < kLotShape.min || ratio > kLotShape.max) return;
    kept[i] = Lot{plan.block, plan.zone, {}, std::move(*cell), std::move(shape)};
  });
  std::vector<Lot> lots;
  for (auto& lot : kept)
    if (lot) lots.push_back(std::move(*lot));
  return lots;
}

}  // namespace exacity
