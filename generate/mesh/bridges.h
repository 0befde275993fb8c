// Bridges as level decks between their abutments, with piers down to the riverbed
// (docs/design.md, Ground meshes): a bridge's road surfaces lie flat at the height of its
// highest end, where draped over the terrain they sank into the water's bed.
#pragma once

#include <vector>

#include "generate/city/ground.h"
#include "generate/city/terrain.h"
#include "generate/mesh/ground_mesh.h"

namespace exacity {

// The deck under a bridge's surface is this thick, or thinner down to kThinnestDeck where
// it lies low over its water (flat land, where water lies just under its banks); its
// piers are this wide at most.
constexpr double kDeckThickness = 1.0;
constexpr double kThinnestDeck = 0.3;
constexpr double kPierWidth = 2.0;
constexpr double kPierSpacing = 30.0;
// Draped roads lie this far over the terrain; a deck's top, which is its road, as far over
// its higher end, so the road runs on to the deck level there.
constexpr double kRoadOverTerrain = 0.1;
// Parapets stand along a deck's sides over water, this high over its road and this thick.
constexpr double kParapetHeight = 1.0;
constexpr double kParapetThickness = 0.3;

struct BridgeDecks {
  // Per road area: the top of its bridge's deck, its road surface (kRoadOverTerrain over the
  // highest terrain along the outlines of the bridge surfaces that touch it: its ends on the
  // banks), NaN off bridges; kRoadOverTerrain for every bridge without terrain.
  std::vector<double> height;
  // Per road area: its deck's thickness, kDeckThickness, or a third of its road's height
  // over the highest water under its bridge (so its underside stays twice as far over the
  // water as the deck is thick), down to kThinnestDeck; NaN off bridges.
  std::vector<double> thickness;

  // The deck of the bridge surface under p, NaN where none is.
  double at(const Ground& ground, geom::Vec2 p) const;
  // The road area of the bridge surface under p, -1 where none is.
  int area_at(const Ground& ground, geom::Vec2 p) const;
};

BridgeDecks bridge_decks(const Ground& ground, const Terrain* terrain);

// Each deck's sides and underside, its thickness under its top; a parapet along each side
// over water (not where it meets another bridge surface or rests on land); and piers along
// each bridge's centre line every kPierSpacing metres (none at its ends, which rest on the
// banks) from the deck's underside down to the bed of the water under them (bed_height).
// Appended to `out`; `area`, when given, gets the road area each new triangle belongs to.
void bridge_structure(const Ground& ground, const Terrain* terrain, const BridgeDecks& decks, GroundMesh& out,
                      std::vector<int>* area = nullptr);

}  // namespace exacity
