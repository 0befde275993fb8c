#include "generate/parcels/lots.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <limits>
#include <set>
#include <unordered_map>

#include <tbb/parallel_for.h>

#include "generate/cancel.h"
#include "generate/city/random.h"
#include "generate/errors.h"
#include "generate/city/format_number.h"
#include "generate/parcels/lot_layout.h"
#include "geom/measure.h"

namespace exacity {

std::vector<PlannedLot> plan_lots(const std::vector<Block>& blocks, const CitySettings& city, const ModelLibrary* library,
                                  const Channels& channels, Memo<std::vector<PlannedLot>>* memo) {
  std::map<ZoneType, std::unique_ptr<LotLayout>> layouts;
  for (const auto& [zone, settings] : city.zone_settings)
    layouts[zone] = settings.lots.layout->make(zone, library, channels);
  std::vector<std::vector<PlannedLot>> per_block(blocks.size());
  const std::uint64_t stage = mix(city.seed, static_cast<std::uint64_t>(Stage::Lots));
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t bi) {
    cancel.check();
    const Block& block = blocks[bi];
    if (block.green) return;
    // A block's stream is its shape's, so a block an edit left as it was is planned as before.
    const std::string cell_text = geom::exact_text(block.cell);
    auto plan = [&] {
      Random rng(mix(stage, content_id(cell_text)));
      std::vector<PlannedLot> lots = layouts.at(block.zone)->plan(block, static_cast<int>(bi), rng);
      // A block too small for the layout to cut is one lot, if it makes one (kept_lots); not
      // for the lot library, whose lots are the models' own.
      if (lots.empty() && !city.zone_settings.at(block.zone).lots.layout->models_own_lots())
        lots.push_back({static_cast<int>(bi), block.zone, {}, block.cell});
      return lots;
    };
    if (!memo) {
      per_block[bi] = plan();
      return;
    }
    // Everything the plan reads of the block; the rest (settings, library, channels) is the memo's context.
    std::string key = "block zone " + std::to_string(static_cast<int>(block.zone)) +
                      " density " + block.density + " roads";
    for (int r : block.roads) key += ' ', key += std::to_string(r);
    key += " " + cell_text;
    per_block[bi] = memo->get(key, plan);
    for (PlannedLot& lot : per_block[bi]) lot.block = static_cast<int>(bi);  // its index in this build
  });
  std::vector<PlannedLot> lots;
  for (auto& list : per_block)
    for (auto& lot : list) lots.push_back(std::move(lot));
  return lots;
}

void check_lot_library(const CitySettings& city, const ModelLibrary* library) {
  for (const auto& [zone, settings] : city.zone_settings) {
    if (!settings.lots.layout->models_own_lots()) continue;
    const std::string setting = city.path.string() + ": \"exacity\".zones." + std::string(name(zone)) + ".lots is \"" + settings.lots.layout->name() + "\"";
    if (!library)
      throw UserError(setting + ", but the sketch names no model library; name one in \"exacity\".models or with --models");
    const std::vector<int> models = library->lot_choices(zone);
    if (models.empty())
      throw UserError(setting + ", but " + library->file.string() + " has no building entry with a \"lot\" for " +
                      std::string(name(zone)) + " zones; add \"lot\": [width, depth] to one, or use \"allocation\"");
    for (int m : models) {
      const Model& model = library->models[m];
      const double shape = model.lot_depth / model.lot_width;
      const double smallest = settings.lots.min_lot_area;
      if (model.lot_width * model.lot_depth < smallest)
        throw UserError(library->file.string() + " models[" + std::to_string(m) + "]: \"lot\" [" +
                        format_number(model.lot_width) + ", " + format_number(model.lot_depth) + "] is under " +
                        std::string(name(zone)) + " zones' min_lot_area (" + format_number(smallest) +
                        " m²); give a larger lot, or lower \"exacity\".zones." + std::string(name(zone)) + ".min_lot_area");
      if (shape < kLotShape.min || shape > kLotShape.max)
        throw UserError(library->file.string() + " models[" + std::to_string(m) + "]: \"lot\" [" +
                        format_number(model.lot_width) + ", " + format_number(model.lot_depth) +
                        "] is " + format_number(std::round(shape * 100) / 100) +
                        " times as deep as wide; a lot keeps its depth within 0.5 to 5 times its width");
    }
  }
}

namespace {

// A lot's depth over its width (geom::depth_over_width) across and along its longest
// street edge, over the corners of `rings` (one lot, or two about to be one: the extents
// of a union are those of its parts); 0 without a street edge.
double lot_shape(const std::vector<const geom::Cell*>& cells, const std::vector<const geom::Ring*>& rings) {
  double longest = 0;
  std::pair<geom::Vec2, geom::Vec2> front;
  for (const geom::Cell* cell : cells)
    for (auto [a, b] : cell->edges_of_kind(LotEdge::kStreet))
      if (const double len = geom::distance(a, b); len > longest) longest = len, front = {a, b};
  if (longest == 0) return 0;
  geom::Ring corners;
  for (const geom::Ring* r : rings) corners.insert(corners.end(), r->begin(), r->end());
  return geom::depth_over_width(corners, front.first, front.second);
}

bool good_shape(double ratio) { return ratio >= kLotShape.min && ratio <= kLotShape.max; }

// Whether the zone type's lots fill their blocks: with `lot_coverage` (a real place's
// coverage of its land use, which --like sets), every piece of a block on a street is a
// lot whatever its shape, and the land no lot holds joins one (with_open_land_joined),
// since the place's coverage is of all its land and land outside lots is never built.
bool fills_blocks(const CitySettings& city, ZoneType zone) { return city.zone_settings.at(zone).buildings.lot_coverage > 0; }

// Why a piece of a planned lot, as written (rounded), makes no lot: off the street, too
// small, or too narrow or shallow for its frontage (unless its zone fills its blocks);
// null when it makes one. A lot is its rounded cell, so the buildings placed in it lie
// inside the lot as written.
const char* refusal(const geom::Cell& cell, const PlannedLot& plan, const CitySettings& city) {
  const geom::Polygon shape = cell.to_plain();
  if (geom::area(shape) < city.zone_settings.at(plan.zone).lots.min_lot_area) return "under min_lot_area";
  const double ratio = lot_shape({&cell}, {&shape.outer});
  if (ratio == 0) return "no street edge";
  if (fills_blocks(city, plan.zone)) return nullptr;
  if (ratio < kLotShape.min) return "shallower than half its width";
  if (ratio > kLotShape.max) return "deeper than five times its width";
  return nullptr;
}

// Each face's side of a lot edge: a street where it is road surface, else inner land.
std::vector<int> edge_kinds(const CityMap& city_map) {
  return city_map.per_label([](const FaceLabel& f) { return f.road_surface() ? LotEdge::kStreet : LotEdge::kInner; });
}

// What the last tracing of a block's map into lots found: its pieces' land (lot_land reports it).
struct Traced {
  PiecesLand land;
};

// Each planned lot's pieces in the map, those that make sensible lots: on the street, at
// least min_lot_area, and within kLotShape. A lot's rank orders the kept pieces of its
// planned lot. The pieces refused once rounded, when `refused` is given, go there. When
// `traced` is given it is made the pieces' land (LotLand's lots and refused, per zone type,
// in the pieces' order).
std::vector<Lot> kept_lots(const CityMap& city_map, const std::vector<PlannedLot>& planned, const CitySettings& city,
                           std::vector<Lot>* refused = nullptr, Traced* traced = nullptr) {
  const std::vector<int> group = city_map.per_label([](const FaceLabel& f) { return f.lot; });
  std::vector<int> planned_of, component;
  std::vector<geom::Cell> pieces = city_map.map.cells(group, edge_kinds(city_map), &planned_of, &component);
  std::vector<std::optional<Lot>> kept(pieces.size());
  std::vector<const char*> why(pieces.size(), "collapsed by rounding");  // null: a lot
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), pieces.size(), [&](std::size_t i) {
    cancel.check();
    const PlannedLot& plan = planned[planned_of[i]];
    std::optional<geom::Cell> cell = pieces[i].as_written();
    if (!cell) return;
    why[i] = refusal(*cell, plan, city);
    if (why[i] && !refused) return;
    geom::Polygon shape = cell->to_plain();
    kept[i] = Lot{plan.block, plan.zone, {}, std::move(*cell), std::move(shape), planned_of[i], 0, component[i], plan.model};
  });
  if (traced) {
    traced->land.clear();
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      LotLand& l = traced->land[planned[planned_of[i]].zone];
      LandShare& share = why[i] ? l.refused[why[i]] : l.lots;
      ++share.count, share.area_m2 += pieces[i].area();
    }
  }
  std::vector<Lot> lots;
  std::map<int, int> pieces_of_planned;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (!kept[i]) continue;
    if (why[i]) refused->push_back(std::move(*kept[i]));
    else kept[i]->rank = pieces_of_planned[kept[i]->planned]++, lots.push_back(std::move(*kept[i]));
  }
  return lots;
}

// How long two rings run side by side: the overlap of their collinear edges (both come
// from one map, so a shared edge is the same grid segment in each, or split by a vertex
// of a third lot; within a micrometre).
double shared_length(const geom::Ring& a, const geom::Ring& b) {
  double shared = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const geom::Vec2 p = a[i], q = a[(i + 1) % a.size()];
    const double len = geom::distance(p, q);
    if (len == 0) continue;
    const geom::Vec2 u = geom::unit_along(p, q);
    for (std::size_t k = 0; k < b.size(); ++k) {
      const geom::Vec2 r = b[k], s = b[(k + 1) % b.size()];
      if (std::abs(geom::cross(u, r - p)) > 1e-6 || std::abs(geom::cross(u, s - p)) > 1e-6) continue;
      const double t0 = geom::dot(u, r - p), t1 = geom::dot(u, s - p);
      shared += std::max(0.0, std::min(len, std::max(t0, t1)) - std::max(0.0, std::min(t0, t1)));
    }
  }
  return shared;
}

// Each block's lots, by index in ascending order.
std::map<int, std::vector<int>> lots_by_block(const std::vector<Lot>& lots) {
  std::map<int, std::vector<int>> of_block;
  for (std::size_t i = 0; i < lots.size(); ++i) of_block[lots[i].block].push_back(static_cast<int>(i));
  return of_block;
}

// Of the lots `candidates` (in their order; the first wins a tie) whose bounds meet `box`,
// the one sharing the longest edge with `ring` that `accept` allows; or -1. `accept` is
// asked only of a lot that would be the longest so far.
template <typename Accept>
int longest_shared(const std::vector<Lot>& lots, const std::vector<int>& candidates, const geom::Box& box,
                   const geom::Ring& ring, Accept&& accept) {
  int best = -1;
  double longest = 0;
  for (const int k : candidates) {
    if (!box.meets(lots[k].cell.bounds())) continue;
    if (const double d = shared_length(ring, lots[k].polygon.outer); d > longest && accept(k)) longest = d, best = k;
  }
  return best;
}

// The lot of lots[i]'s block that `may_join` allows and that shares the longest edge with
// it, of those it would make a lot of good shape with; or -1. `of_block` lists each block's
// lots in ascending order: a block's lots are all it scans, in the order of the lots.
template <typename MayJoin>
int neighbour(const std::vector<Lot>& lots, const std::map<int, std::vector<int>>& of_block, std::size_t i,
              MayJoin&& may_join) {
  return longest_shared(lots, of_block.at(lots[i].block), lots[i].cell.bounds(), lots[i].polygon.outer, [&](int k) {
    return k != static_cast<int>(i) && may_join(k) &&
           good_shape(lot_shape({&lots[i].cell, &lots[k].cell}, {&lots[i].polygon.outer, &lots[k].polygon.outer}));
  });
}

// Makes each block of `lot_of_block` one lot, the planned lot it maps to: every face of
// land in it, the gardens between its lots included.
void make_blocks_whole(CityMap& city_map, const std::map<int, int>& lot_of_block) {
  if (lot_of_block.empty()) return;
  const std::vector<int> group =
      city_map.per_label([&](const FaceLabel& f) { return f.block >= 0 && lot_of_block.count(f.block) ? f.block : -1; });
  city_map.map.relabel_components(group, [&](int, int label) {
    FaceLabel l = city_map.labels[label];
    l.lot = lot_of_block.at(l.block);
    return city_map.label_index(l);
  });
}

// A block none of whose planned lots made a sensible lot (a block a little larger than a
// lot, cut into corners and slivers) is tried whole, as one lot, rather than left empty.
std::vector<Lot> with_refused_blocks_whole(CityMap& city_map, const std::vector<PlannedLot>& planned,
                                           std::vector<Lot> lots, const CitySettings& city, Traced* land) {
  std::set<int> kept_in;
  for (const Lot& lot : lots) kept_in.insert(lot.block);
  std::map<int, int> lot_of_block;
  for (std::size_t l = 0; l < planned.size(); ++l)
    if (!kept_in.count(planned[l].block)) lot_of_block.emplace(planned[l].block, static_cast<int>(l));
  if (lot_of_block.empty()) return lots;
  make_blocks_whole(city_map, lot_of_block);
  return kept_lots(city_map, planned, city, nullptr, land);
}

// Relabels each piece of lot faces (a component as geom::PlanarMap::cells finds them,
// grouped by lot, or by `pieces_of` when given) in `lot_of_piece` to the planned lot it
// maps to (-1: no lot).
void relabel_pieces(CityMap& city_map, const std::map<int, int>& lot_of_piece,
                    const std::vector<int>* pieces_of = nullptr) {
  const std::vector<int> group = pieces_of ? *pieces_of : city_map.per_label([](const FaceLabel& f) { return f.lot; });
  city_map.map.relabel_components(group, [&](int c, int label) {
    auto it = lot_of_piece.find(c);
    if (it == lot_of_piece.end()) return label;
    FaceLabel l = city_map.labels[label];
    l.lot = it->second;
    return city_map.label_index(l);
  });
}

// Pieces of planned lots refused as lots (too shallow, off the street, too small: the
// allocation's cuts meeting a block's odd corners and narrows) join the lot of their block
// they share the longest edge with, of those the joined land keeps within kLotShape, all
// it took so far counted; a piece no lot can take stays refused (lot_land reports it).
std::vector<Lot> with_refused_pieces_joined(CityMap& city_map, const std::vector<PlannedLot>& planned,
                                            std::vector<Lot> lots, const std::vector<Lot>& refused,
                                            const CitySettings& city, std::map<ZoneType, LandShare>* joined,
                                            Traced* land) {
  const std::map<int, std::vector<int>> of_block = lots_by_block(lots);
  std::vector<std::vector<const Lot*>> taken(lots.size());  // per lot: the pieces it takes
  std::map<int, int> lot_of_piece;
  for (const Lot& piece : refused) {
    const auto block = of_block.find(piece.block);
    if (block == of_block.end()) continue;
    const int best = longest_shared(lots, block->second, piece.cell.bounds(), piece.polygon.outer, [&](int k) {
      const Lot& lot = lots[k];
      std::vector<const geom::Cell*> cells{&lot.cell, &piece.cell};
      std::vector<const geom::Ring*> rings{&lot.polygon.outer, &piece.polygon.outer};
      for (const Lot* t : taken[k]) cells.push_back(&t->cell), rings.push_back(&t->polygon.outer);
      return good_shape(lot_shape(cells, rings));
    });
    if (best < 0) continue;
    taken[best].push_back(&piece);
    lot_of_piece[piece.piece] = lots[best].planned;
    if (joined) ++(*joined)[piece.zone].count, (*joined)[piece.zone].area_m2 += geom::area(piece.polygon);
  }
  if (lot_of_piece.empty()) return lots;
  relabel_pieces(city_map, lot_of_piece);
  return kept_lots(city_map, planned, city, nullptr, land);
}

// In zone types that fill their blocks (fills_blocks), each piece of a block's land that
// no planned lot holds (its middle beyond the lots' depth, corners between runs of lots)
// joins the lot of its block it shares the longest edge with (counted in `joined`); a
// piece next to no lot stays open.
std::vector<Lot> with_open_land_joined(CityMap& city_map, const std::vector<PlannedLot>& planned, std::vector<Lot> lots,
                                       const CitySettings& city, std::map<ZoneType, LandShare>* joined,
                                       Traced* land) {
  std::map<int, ZoneType> zone_of_block;
  for (const PlannedLot& p : planned) zone_of_block.emplace(p.block, p.zone);
  const std::vector<int> group = city_map.per_label([&](const FaceLabel& f) {
    if (f.block < 0 || f.lot >= 0 || f.road_surface()) return -1;
    const auto it = zone_of_block.find(f.block);
    return it != zone_of_block.end() && fills_blocks(city, it->second) ? f.block : -1;
  });
  if (std::none_of(group.begin(), group.end(), [](int g) { return g >= 0; })) return lots;
  std::vector<int> block_of, component;
  const std::vector<geom::Cell> open = city_map.map.cells(group, edge_kinds(city_map), &block_of, &component);
  const std::map<int, std::vector<int>> of_block = lots_by_block(lots);
  std::map<int, int> lot_of_piece;
  for (std::size_t i = 0; i < open.size(); ++i) {
    const auto block = of_block.find(block_of[i]);
    if (block == of_block.end()) continue;
    const geom::Polygon piece = open[i].to_plain();
    const int best = longest_shared(lots, block->second, open[i].bounds(), piece.outer, [](int) { return true; });
    if (best < 0) continue;
    lot_of_piece[component[i]] = lots[best].planned;
    if (joined) ++(*joined)[lots[best].zone].count, (*joined)[lots[best].zone].area_m2 += geom::area(piece);
  }
  if (lot_of_piece.empty()) return lots;
  relabel_pieces(city_map, lot_of_piece, &group);
  return kept_lots(city_map, planned, city, nullptr, land);
}

// The planned lots of a block into its map in one batch, which is then snap-rounded, and
// traced into lots; pieces refused as lots join a neighbouring lot where they can.
std::vector<Lot> lots_in_block_map(CityMap& city_map, const std::vector<PlannedLot>& planned,
                                   const CitySettings& city, std::map<ZoneType, LandShare>* joined, Traced* land) {
  city_map.lots = {city_map.generated_roads.end(), static_cast<int>(planned.size())};
  for (std::size_t l = 0; l < planned.size(); ++l) {
    const int counter = city_map.lots.at(static_cast<int>(l));
    if (planned[l].ring.empty()) city_map.map.add_cell_within(planned[l].block, planned[l].cell, counter);
    else city_map.map.add_ring_within(planned[l].block, planned[l].ring, counter);
  }
  city_map.insert_lots();
  // The block's last batch: its map is snap-rounded now, so its lots round without edges
  // crossing (the vertices it put on the block's edges go into the city's map:
  // CityLots::put_into).
  city_map.map.snap_round();

  std::vector<Lot> refused;
  std::vector<Lot> lots = kept_lots(city_map, planned, city, &refused, land);
  lots = with_refused_pieces_joined(city_map, planned, std::move(lots), refused, city, joined, land);
  lots = with_open_land_joined(city_map, planned, std::move(lots), city, joined, land);
  return with_refused_blocks_whole(city_map, planned, std::move(lots), city, land);
}

// CityLots::merge_unbuilt_lots in one block's map.
std::vector<Lot> merged_unbuilt_lots(CityMap& city_map, const std::vector<PlannedLot>& planned,
                                     const std::vector<Lot>& lots, const std::vector<char>& built, bool last,
                                     const CitySettings& city, UnbuiltLots& tally, Traced* land) {
  std::map<int, int> lot_of_piece;  // an unbuilt lot's piece -> the planned lot it joins, or -1
  std::vector<char> settled(lots.size(), 0);  // unbuilt lots joined, or kept for another to join
  // The last time, a block still without a building (a small one, cut into lots too small
  // each, which pairs did not mend) is tried whole, as one lot, rather than left open.
  std::map<int, int> lot_of_block;
  if (last) {
    std::set<int> built_on;
    for (std::size_t i = 0; i < lots.size(); ++i)
      if (built[i]) built_on.insert(lots[i].block);
    for (std::size_t i = 0; i < lots.size(); ++i) {
      if (built_on.count(lots[i].block)) continue;
      settled[i] = 1;
      if (!lot_of_block.emplace(lots[i].block, lots[i].planned).second) ++tally.merged;
    }
  }
  const std::map<int, std::vector<int>> of_block = lots_by_block(lots);
  for (std::size_t i = 0; i < lots.size(); ++i) {
    if (built[i] || settled[i]) continue;
    settled[i] = 1;
    int next = neighbour(lots, of_block, i, [&](std::size_t k) { return built[k]; });
    // Two unbuilt lots together may hold a building (two shallow rows back to back).
    if (next < 0 && !last)
      next = neighbour(lots, of_block, i, [&](std::size_t k) { return !built[k] && !settled[k]; });
    if (next >= 0 && !built[next]) settled[next] = 1;
    if (next < 0 && !last) continue;
    lot_of_piece[lots[i].piece] = next >= 0 ? lots[next].planned : -1;
    if (next >= 0) ++tally.merged;
    else ++tally.left_open, tally.left_open_m2 += geom::area(lots[i].polygon);
  }
  relabel_pieces(city_map, lot_of_piece);
  make_blocks_whole(city_map, lot_of_block);
  return kept_lots(city_map, planned, city, nullptr, land);
}

// A map of the block alone: its faces labelled as a block's (block 0), the outside as
// nothing, and across each edge of its cell a road area where its cell says a road is.
std::unique_ptr<CityMap> block_map(const geom::Cell& cell) {
  auto map = std::make_unique<CityMap>();
  FaceLabel road, inside;
  road.cover = Cover::Road, road.road = 0;
  inside.cover = Cover::Zone, inside.block = 0;
  const int outside = map->label_index(FaceLabel{}), across = map->label_index(road), in = map->label_index(inside);
  map->map = geom::PlanarMap::of_cell(cell, in, outside,
                                      [&](int kind) { return BlockEdge::is_road(kind) ? across : outside; });
  return map;
}

BlockLots first_lots(CityMap& map, const std::vector<PlannedLot>& planned, const CitySettings& city) {
  BlockLots out;
  Traced traced;
  out.lots = lots_in_block_map(map, planned, city, &out.joined, &traced);
  out.pieces = std::move(traced.land);
  out.outline = map.map.outline_as_cut();  // merges relabel faces only: it stays
  return out;
}

BlockLots merged(CityMap& map, const std::vector<PlannedLot>& planned, const BlockLots& before,
                 const std::vector<char>& built, bool last, const CitySettings& city) {
  BlockLots out;
  out.joined = before.joined, out.unbuilt = before.unbuilt;
  Traced traced;
  out.lots = merged_unbuilt_lots(map, planned, before.lots, built, last, city, out.unbuilt, &traced);
  out.pieces = std::move(traced.land), out.outline = before.outline;
  return out;
}

void add_land(PiecesLand& sum, const PiecesLand& land) {
  for (const auto& [zone, l] : land) {
    LotLand& s = sum[zone];
    s.lots.count += l.lots.count, s.lots.area_m2 += l.lots.area_m2;
    for (const auto& [why, share] : l.refused) s.refused[why].count += share.count, s.refused[why].area_m2 += share.area_m2;
  }
}

}  // namespace

struct CityLots::BlockMap {
  int index = 0;          // the block's index in the city's blocks
  int first_planned = 0;  // its first planned lot's index in the city's
  geom::Cell cell;
  std::vector<PlannedLot> planned;  // its own, each of block 0
  std::string key;                  // what its lots so far are made from, with a memo
  std::vector<std::pair<std::vector<char>, bool>> merges;  // each merge so far: its lots built, and `last`
  std::unique_ptr<CityMap> map;     // its map as `made` left it, while a merge made it in this build
  BlockLots made;

  // Its map made again up to `made` (the lots stage keeps none, nor does a memo), from its
  // cell, planned lots and merges.
  void remake(const CitySettings& city) {
    map = block_map(cell);
    BlockLots lots = first_lots(*map, planned, city);
    for (const auto& [built, last] : merges) lots = merged(*map, planned, lots, built, last, city);
  }
};

CityLots::CityLots(const std::vector<Block>& blocks, const std::vector<PlannedLot>& planned, const CitySettings& city,
                   Memo<BlockLots>* memo)
    : city_(&city), memo_(memo) {
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    blocks_.push_back(std::make_unique<BlockMap>());
    blocks_.back()->index = static_cast<int>(b), blocks_.back()->cell = blocks[b].cell;
  }
  for (std::size_t l = 0; l < planned.size(); ++l) {
    BlockMap& b = *blocks_.at(planned[l].block);
    if (b.planned.empty()) b.first_planned = static_cast<int>(l);
    b.planned.push_back(planned[l]);
    b.planned.back().block = 0;
  }
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), blocks_.size(), [&](std::size_t i) {
    cancel.check();
    BlockMap& b = *blocks_[i];
    if (b.planned.empty()) return;
    // The map is not kept: few blocks have lots no placer builds on (about one in twelve
    // in the 10 km city), and every block's map held through the placing was a quarter of
    // the memory; a merge makes it again (BlockMap::remake).
    auto make = [&] { return first_lots(*block_map(b.cell), b.planned, city); };
    if (!memo) {
      b.made = make();
      return;
    }
    // All its lots are made from: its cell (its edges' kinds say where roads are) and its plan.
    b.key = "block " + geom::exact_text(b.cell) + " lots";
    for (const PlannedLot& p : b.planned) {
      b.key += " zone " + std::to_string(static_cast<int>(p.zone)) + " model " + std::to_string(p.model.value_or(-1)) + " ";
      if (p.ring.empty()) b.key += geom::exact_text(p.cell);
      else append_key(b.key, p.ring);
    }
    b.made = memo->get(b.key, make);
  });
}

CityLots::CityLots() = default;
CityLots::~CityLots() = default;
CityLots::CityLots(CityLots&&) noexcept = default;
CityLots& CityLots::operator=(CityLots&&) noexcept = default;

std::vector<Lot> CityLots::lots() const {
  std::vector<Lot> lots;
  for (const auto& b : blocks_)
    for (Lot lot : b->made.lots) {
      lot.block = b->index, lot.planned += b->first_planned;
      lots.push_back(std::move(lot));
    }
  return lots;
}

void CityLots::merge_unbuilt_lots(const std::vector<char>& built, bool last) {
  std::vector<std::size_t> first_lot(blocks_.size(), 0);
  for (std::size_t i = 0, n = 0; i < blocks_.size(); ++i) first_lot[i] = n, n += blocks_[i]->made.lots.size();
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), blocks_.size(), [&](std::size_t i) {
    cancel.check();
    BlockMap& b = *blocks_[i];
    const auto from = built.begin() + static_cast<std::ptrdiff_t>(first_lot[i]);
    const std::vector<char> flags(from, from + static_cast<std::ptrdiff_t>(b.made.lots.size()));
    // A block whose lots are all built keeps them as they are.
    if (std::all_of(flags.begin(), flags.end(), [](char c) { return c != 0; })) return;
    bool made_here = false;
    auto merge = [&] {
      if (!b.map) b.remake(*city_);
      made_here = true;
      return merged(*b.map, b.planned, b.made, flags, last, *city_);
    };
    if (!memo_) {
      b.made = merge();
    } else {
      b.key += last ? " merged last " : " merged ";
      for (char c : flags) b.key += c ? '1' : '0';
      b.made = memo_->get(b.key, merge);
    }
    b.merges.emplace_back(flags, last);
    if (!made_here || last) b.map.reset();  // it is as the merge before left it, or no merge follows
  });
}

PiecesLand CityLots::pieces() const {
  PiecesLand sum;
  for (const auto& b : blocks_) add_land(sum, b->made.pieces);
  return sum;
}

std::map<ZoneType, LandShare> CityLots::joined() const {
  std::map<ZoneType, LandShare> sum;
  for (const auto& b : blocks_)
    for (const auto& [zone, share] : b->made.joined) sum[zone].count += share.count, sum[zone].area_m2 += share.area_m2;
  return sum;
}

UnbuiltLots CityLots::unbuilt() const {
  UnbuiltLots sum;
  for (const auto& b : blocks_) {
    sum.merged += b->made.unbuilt.merged, sum.left_open += b->made.unbuilt.left_open;
    sum.left_open_m2 += b->made.unbuilt.left_open_m2;
  }
  return sum;
}

void CityLots::put_into(CityMap& city_map) {
  std::vector<geom::Cell> outlines(blocks_.size());
  for (const auto& b : blocks_) {
    b->map.reset();
    outlines[b->index] = b->made.outline;
  }
  const std::vector<std::vector<geom::VertexOnEdge>> beyond =
      city_map.map.add_outlines(city_map.per_label([](const FaceLabel& f) { return f.road_surface() ? -1 : f.block; }),
                                outlines);
  // A block's map sees its cell alone: where another block's lots put vertices on an edge
  // they share (no road between them), or the city's snap rounding split one, its lots along
  // that edge take those vertices too, so that written they follow their block's edge.
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), blocks_.size(), [&](std::size_t i) {
    BlockMap& b = *blocks_[i];
    if (beyond[b.index].empty()) return;
    cancel.check();
    for (Lot& lot : b.made.lots) {
      std::optional<geom::Cell> cell = geom::with_vertices_on_edges(lot.cell, beyond[b.index]);
      if (!cell) continue;
      lot.cell = std::move(*cell);
      lot.polygon = lot.cell.to_plain();
    }
  });
}

std::map<ZoneType, LotLand> lot_land(PiecesLand pieces, const std::vector<Block>& blocks,
                                     const std::map<ZoneType, LandShare>& joined) {
  std::map<ZoneType, LotLand> land = std::move(pieces);
  for (const auto& [zone, share] : joined) land[zone].joined = share;
  for (const Block& b : blocks)
    if (!b.green) land[b.zone].blocks_m2 += b.cell.area();
  for (auto& [zone, l] : land) {
    l.open_m2 = l.blocks_m2 - l.lots.area_m2;
    for (const auto& [why, share] : l.refused) l.open_m2 -= share.area_m2;
  }
  return land;
}

}  // namespace exacity
