// The zone map: drawn zones, heightmap water and highway road areas in one exact planar
// map, every face labelled with what covers it (seed 000, 3.1).
#pragma once

#include <compare>
#include <cstdint>
#include <vector>

#include "generate/sketch.h"
#include "generate/terrain.h"
#include "geom/planar_map.h"

namespace exacity {

// What the user sees at a face: water beats road beats drawn zone.
enum class Cover : std::uint8_t { Outside, Zone, Water, Road };

struct FaceLabel {
  Cover cover = Cover::Outside;
  int zone = -1;        // index into Sketch::zones of the drawn zone on top, -1 if none
  int road = -1;        // index into Sketch::roads of the road whose surface this is, -1 if none
  bool bridge = false;  // a road surface over water
  friend auto operator<=>(const FaceLabel&, const FaceLabel&) = default;
};

struct ZoneMap {
  geom::PlanarMap map;
  std::vector<FaceLabel> labels;   // indexed by face label
  std::vector<int> first_line_tag; // per road: tag of its first centre line
};

ZoneMap build_zone_map(const Sketch& sketch, const Terrain* terrain);

}  // namespace exacity
