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
  int held_lots = 0;                    // lots not built again
};

// The mapped footprints the city keeps, as drawn: each polygon's rings simple (else
// mended by GEOS's MakeValid where that leaves one polygon), outer ring counter-clockwise
// and holes clockwise, over no road surface of the map, and overlapping no footprint kept
// before it. `mapped` is each one's index in `drawn`; zone, heights and roof come later.
std::vector<Building> mapped_footprints(const std::vector<MappedBuilding>& drawn, const CityMap& map, MappedTally& tally);

// The lots mapped footprints stand on: their interiors meet (exactly).
struct HeldLots {
  std::vector<char> held;   // per lot: no placer builds on it
  std::vector<int> lot_of;  // per footprint: the first lot it stands on, or -1
};
HeldLots lots_holding(const std::vector<Lot>& lots, const std::vector<Building>& footprints);

// Raises the kept footprints: each takes the zone and id of the first lot it stands on (else
// the drawn zone under it, else residential), the height of its `height` tag, else its
// `building:levels` × the zone's storey_height (plus its roof), else one drawn from the
// zone's heights as an extruded building's; its roof from `roof:shape` and `roof:height`
// where geom/roof.h makes that shape, else flat (counted). Ids run on from `first_id`.
void raise_mapped_buildings(std::vector<Building>& footprints, const std::vector<MappedBuilding>& drawn,
                            const HeldLots& held, const std::vector<Lot>& lots, const CityMap& map, const std::vector<ZoneFeature>& zones,
                            const CitySettings& city, const Channels& channels, const Terrain* terrain, int first_id,
                            MappedTally& tally);

}  // namespace exacity
