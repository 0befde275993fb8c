// Mapped buildings (docs/design.md, Mapped buildings): the footprints a sketch maps
// (OpenStreetMap's building=*) kept as drawn and raised from their tags; the lots they
// stand on are not built again.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "generate/city/channels.h"
#include "generate/city/city_map.h"
#include "generate/city/features.h"
#include "generate/city/terrain.h"
#include "generate/city/zone_settings.h"
#include "generate/parcels/lots.h"
#include "generate/placement/buildings.h"

namespace exacity {

// What became of the sketch's mapped buildings, for report.json: nothing is left out
// without a count and a reason.
struct MappedTally {
  int kept = 0;                         // as mapped
  int repaired = 0;                     // kept after a repair
  std::map<std::string, int> refused;   // by why
  std::map<std::string, int> repairs;   // by what was done
  std::map<std::string, int> heights;   // by where the height came from: "height", "building:levels", "zone"
  std::map<std::string, int> roofs;     // by the roof built
  std::map<std::string, int> made_flat;  // roof:shape values made flat, and why
  std::vector<std::string> named;       // the first refusals and repairs, each naming its building
  int held_lots = 0;                    // lots mapped buildings stand on
  int held_lots_built_on = 0;           // of those, lots generated buildings stand on too (lot_coverage)
  // building:parts: those raised in a kept building, and those refused by why.
  int parts = 0;
  std::map<std::string, int> parts_refused, part_roofs;
  // Roads narrowed to give way to mapped buildings, and the first few, each named with what
  // was narrowed and for which building.
  int roads_narrowed = 0;
  std::vector<std::string> narrowed;
};

// Roads give way to the mapped buildings (a mapped building is what stands there; a road's
// surface is as wide as its width tag, else its lanes, else its class's guess): a road whose
// surface reaches over a mapped footprint loses the sidewalk on that building's side, then
// width, down to its carriageway as mapped (`carriageway`; else one lane of 3.5 m where it
// is one-way or a service road, else two, at most its width) and no further: a building on
// that carriageway is still refused. Decided by GEOS's distance from the road's centre line
// to each footprint, 1 cm clear. Before the map is built; each road narrowed counted.
void give_way_to_mapped_buildings(DrawnFeatures& drawn, MappedTally& tally);

// The mapped footprints the city keeps, as drawn: each polygon's rings simple (else
// mended by GEOS's MakeValid, each polygon it leaves a piece), outer ring counter-clockwise
// and holes clockwise, over no road surface of the map, and overlapping no footprint kept
// before it: one that does is cut back from them, 1 cm clear, where at least half of it
// stands clear, else refused. A building's pieces are consecutive, each a Building whose
// `mapped` is its index in `drawn`; zone, heights and roof come later.
std::vector<Building> mapped_footprints(const std::vector<MappedBuilding>& drawn, const CityMap& map, MappedTally& tally);

// Gives each kept footprint the building:parts (`drawn`) that lie in it: a point inside the
// part (simple, else made valid as a footprint is, each piece a part) inside its outline; the others are
// counted as refused, as are all of a refused building's. Raised with their building.
void attach_building_parts(std::vector<Building>& footprints, const std::vector<MappedBuilding>& drawn, MappedTally& tally);

// The lots mapped footprints stand on (HeldLots, generate/placement/buildings.h): their
// interiors meet (exactly); each footprint's area on a lot its intersection's (GEOS's, in
// doubles: a measure, not a test).
HeldLots lots_holding(const std::vector<Lot>& lots, const std::vector<Building>& footprints);

// Raises the kept footprints: each takes the zone and id of the first lot it stands on (else
// the drawn zone under it, else residential), the height of its `height` tag, else its
// `building:levels` × the zone's storey_height (plus its roof), else one drawn from the
// zone's heights as an extruded building's; its roof from `roof:shape` and `roof:height`
// where geom/roof.h makes that shape, else flat (counted). Ids run on from `first_id`.
// Its building:parts (Simple 3D Buildings) each rise from `min_height` (else
// `building:min_level` storeys) to their own height, found as the building's, under their
// own roof; the building's height is then their highest top.
void raise_mapped_buildings(std::vector<Building>& footprints, const std::vector<MappedBuilding>& drawn,
                            const std::vector<MappedBuilding>& drawn_parts,
                            const HeldLots& held, const std::vector<Lot>& lots, const CityMap& map, const std::vector<ZoneFeature>& zones,
                            const CitySettings& city, const Channels& channels, const Terrain* terrain, int first_id,
                            MappedTally& tally);

}  // namespace exacity
