// The recursive split (docs/design.md, Lots): a block halved again and again until its parts are small enough.
#include "generate/parcels/lot_layout.h"

#include <algorithm>
#include <cmath>

#include "geom/grid.h"

namespace exacity {
namespace {

using geom::Vec2;

using geom::lerp;

// Halve perpendicular to the longest edge near its middle until below lot_area;
// a split that would leave a part with no road edge (no frontage) is not made.
std::vector<geom::Cell> split_lots(const geom::Cell& block, double lot_area, Random& rng) {
  std::vector<geom::Cell> done, todo{block};
  while (!todo.empty()) {
    geom::Cell cell = std::move(todo.back());
    todo.pop_back();
    if (cell.area() <= lot_area) {
      done.push_back(std::move(cell));
      continue;
    }
    geom::Polygon shape = cell.to_plain();
    std::vector<std::pair<double, std::size_t>> edges;
    for (std::size_t i = 0; i < shape.outer.size(); ++i)
      edges.push_back({geom::distance(shape.outer[i], shape.outer[(i + 1) % shape.outer.size()]), i});
    std::sort(edges.rbegin(), edges.rend());
    const geom::Box b = cell.bounds();
    const double reach = 2 * std::hypot(b.width(), b.height()) + 1;
    bool split = false;
    for (std::size_t k = 0; k < std::min<std::size_t>(edges.size(), 2) && !split; ++k) {
      Vec2 a = shape.outer[edges[k].second], c = shape.outer[(edges[k].second + 1) % shape.outer.size()];
      Vec2 m = lerp(a, c, 0.5 + rng.uniform(-0.1, 0.1));
      Vec2 n = left_normal(a, c);
      auto cut = geom::Path::from({geom::snap({m.x - n.x * reach, m.y - n.y * reach}),
                                   geom::snap({m.x + n.x * reach, m.y + n.y * reach})});
      auto parts = geom::split_cell(cell, {cut}, BlockEdge::kLotCut);
      bool fronted = parts.size() >= 2;
      for (const geom::Cell& part : parts) {
        auto kinds = part.edge_kinds();
        fronted &= !kinds.empty() && BlockEdge::is_road(kinds.back());
      }
      if (!fronted) continue;
      for (auto& part : parts) todo.push_back(std::move(part));
      split = true;
    }
    if (!split) done.push_back(std::move(cell));
  }
  return done;
}

class Split : public LotLayout {
 public:
  explicit Split(double lot_area) : lot_area_(lot_area) {}
  std::vector<PlannedLot> plan(const Block& block, int index, Random& rng) const override {
    std::vector<PlannedLot> out;
    for (geom::Cell& c : split_lots(block.cell, lot_area_, rng)) out.push_back({index, block.zone, {}, std::move(c)});
    return out;
  }

 private:
  double lot_area_;
};

class SplitChoice : public LotLayoutChoice {
 public:
  explicit SplitChoice(double lot_area) : LotLayoutChoice("split"), lot_area_(lot_area) {}
  std::unique_ptr<LotLayout> make(ZoneType, const ModelLibrary*, const Channels&) const override {
    return std::make_unique<Split>(lot_area_);
  }

 private:
  double lot_area_;  // m²: a part is split no further below this
};

}  // namespace

std::shared_ptr<const LotLayoutChoice> read_split(const LotLayoutReading& reading) {
  double lot_area = reading.zone == ZoneType::Commercial ? 1500 : reading.zone == ZoneType::Industrial ? 3000 : 600;
  reading.settings.number("lot_area", lot_area, 10, 1e8);
  return std::make_shared<SplitChoice>(lot_area);
}

}  // namespace exacity
