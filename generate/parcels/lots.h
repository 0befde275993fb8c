// Lots inside blocks (docs/design.md, Lots), exact, each block's in a map of the block alone;
// the city's map takes only the vertices they put on the blocks' edges.
// Lot corners are computed in doubles and rounded to the grid, so every lot edge is a grid
// line; a lot is labelled only on faces of its own block, so where it would cross a road it
// is cut back exactly there, and where lots overlap the first one listed owns the overlap.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "generate/city/city_map.h"
#include "generate/city/memo.h"
#include "generate/city/zone_settings.h"
#include "generate/parcels/blocks.h"
#include "generate/parcels/lot_layout.h"

namespace exacity {

// A lot as it ended up in the map: one piece of a planned lot, cut back at roads and at
// the lots planned before it, that touches a road area, is at least the zone's
// `min_lot_area` and keeps its depth over width within kLotShape. Its index in the city's
// lots is its id.
struct Lot {
  int block = -1;
  ZoneType zone = ZoneType::Residential;
  std::string density;     // its block's (a grammar's): "" for the zone's own
  geom::Cell cell;         // as written (doubles); edge kinds are LotEdge's
  geom::Polygon polygon;   // the same, as a plain polygon
  int planned = -1;        // the planned lot it is a piece of (its faces' FaceLabel::lot)
  int rank = 0;            // its order among the planned lot's pieces kept as lots
  int piece = -1;          // its component among its block's map's lot faces (geom::PlanarMap::cells)
  std::optional<int> model = std::nullopt;  // a library lot's model
};
// The kind of a lot cell's edge (its geom::Cell edge tag).
struct LotEdge {
  static constexpr int kInner = 0;   // another lot, the block's open middle, or no road
  static constexpr int kStreet = 1;  // along a road area: the lot's frontage
};
inline constexpr Range kLotShape{0.5, 5};  // a lot's depth over its width (across and along its street)

// The lots of every block that is not green space, block by block in parallel, each by its
// zone's LotLayout. `library` may be null unless a zone's lots come from it.
// Each block draws from a stream of its exact cell (content_id), not of its index. With a
// memo, a block's plan is taken from it when the block (its zone, density, roads and exact
// cell) is as before (docs/design.md, Regions and regenerating).
std::vector<PlannedLot> plan_lots(const std::vector<Block>& blocks, const CitySettings& city, const ModelLibrary* library,
                                  const Channels& channels, Memo<std::vector<PlannedLot>>* memo = nullptr);

// Refuses a zone type whose "lots" is "library" when the library holds no building entry
// with a "lot" for it, or one whose lot no lot of the zone may be (under its min_lot_area,
// or of a shape outside kLotShape): UserError
// naming the sketch's setting or the library's entry.
void check_lot_library(const CitySettings& city, const ModelLibrary* library);

// A number of pieces of land and their area (report.json's lot_land).
struct LandShare {
  int count = 0;
  double area_m2 = 0;
};

// Where the land of a zone type's blocks (those not green space) went, for report.json's
// lot_land: into lots, into pieces of planned lots refused as lots (by why, as kept_lots
// refuses them), or into no lot (the open middle, land no lot was planned on, and lots
// given back by merge_unbuilt_lots).
struct LotLand {
  double blocks_m2 = 0;
  LandShare lots;
  LandShare joined;  // pieces refused as lots that a neighbouring lot took (part of `lots`)
  std::map<std::string, LandShare> refused;
  double open_m2 = 0;
};

// The map's pieces of lot land as they were last traced into lots, per zone type: LotLand's
// `lots` and `refused` only. Each block's map makes it from the tracing that made its lots,
// so lot_land needs no tracing of its own.
using PiecesLand = std::map<ZoneType, LotLand>;

// What merge_unbuilt_lots did, for report.json.
struct UnbuiltLots {
  int merged = 0;     // lots joined to a neighbour
  int left_open = 0;  // lots with no built neighbour, given back to their block's open land
  double left_open_m2 = 0;  // their land
};

// A block's lots as a map of the block alone makes them (docs/design.md, Lots): a pure
// function of the block's exact cell, its planned lots and, after a merge, which of its lots
// were built on, kept in a memo by those (RegionCache::block_lots). Its indices are the
// block's own: every Lot::block is 0, and Lot::planned and the faces' lots count the block's
// planned lots.
struct BlockLots {
  std::vector<Lot> lots;  // in the block's map's face order
  PiecesLand pieces;      // the land of the pieces of its map's last tracing into lots
  std::map<ZoneType, LandShare> joined;  // pieces refused as lots that a neighbouring lot took
  UnbuiltLots unbuilt;    // what its merges of unbuilt lots did, all of them
  // The block's cell as its map cut it (geom::PlanarMap::outline_as_cut): with the vertices
  // its lots put on its edges, which the city's map takes (CityLots::put_into).
  geom::Cell outline;
};

// The lots of every block: each block's planned lots cut, snap-rounded, traced and merged in
// a map of the block alone (geom::PlanarMap::of_cell), blocks in parallel. The city's map
// never holds them: once they are final it takes the vertices they put on the blocks' edges
// (put_into). Pieces refused as lots join a neighbouring lot where they can.
// (docs/design.md, Lots.)
class CityLots {
 public:
  // `planned`: plan_lots' lots, block by block in order. With a memo, a block whose cell and
  // planned lots are as before takes its lots from it, and so after each merge.
  CityLots(const std::vector<Block>& blocks, const std::vector<PlannedLot>& planned, const CitySettings& city,
           Memo<BlockLots>* memo = nullptr);
  CityLots();  // no blocks
  ~CityLots();
  CityLots(CityLots&&) noexcept;
  CityLots& operator=(CityLots&&) noexcept;

  // The city's lots: block by block, each block's in its map's order; Lot::block and
  // Lot::planned are the city's, Lot::piece its block map's.
  std::vector<Lot> lots() const;

  // Lots no placer could build on (built[i] is 0 for lots()[i]), too small or too sharp for
  // the zone's smallest building: each is joined, in its block's map, to the built lot of its
  // block it shares the longest edge with (its neighbour along the street, mostly); else,
  // unless `last`, to such an unbuilt lot, since the two may hold a building together; else,
  // when `last`, it is no lot and its land is open. The last time, a block still without a
  // building is tried whole, as one lot. lots() are then the lots as they now are.
  void merge_unbuilt_lots(const std::vector<char>& built, bool last);

  // The pieces' land of every block's last tracing, the pieces joined to a neighbour, and
  // what the merges did, summed over the blocks in order.
  PiecesLand pieces() const;
  std::map<ZoneType, LandShare> joined() const;
  UnbuiltLots unbuilt() const;

  // Puts into the city's map the vertices each block's map has on the block's edges (the
  // lots' corners and crossings there, and its snap rounding's), and snap-rounds it, so the
  // zones, road areas and blocks written from it share every vertex with the lots along
  // them; the lots themselves stay out of it. A block's lots then take the vertices the
  // city's map has on their block's edges that its own map lacked (another block's, across
  // an edge with no road; lots() changes for them). The blocks' maps are freed.
  void put_into(CityMap& city_map);

  struct BlockMap;  // one block's map and lots (lots.cpp)

 private:
  std::vector<std::unique_ptr<BlockMap>> blocks_;
  const CitySettings* city_ = nullptr;
  Memo<BlockLots>* memo_ = nullptr;
};

// The blocks' land (LotLand) from the pieces' land of the map's last tracing, the blocks and
// the pieces joined to a neighbour.
std::map<ZoneType, LotLand> lot_land(PiecesLand pieces, const std::vector<Block>& blocks,
                                     const std::map<ZoneType, LandShare>& joined);

}  // namespace exacity
