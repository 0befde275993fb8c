// Drawn roads and heightmap rivers carried on past the city into the land beyond
// (docs/rendering.md, The land around the city): a highway ended where the city's ground
// ended, in the middle of a field, and a river at the map's edge, in a bank across it.
// City coordinates.
#pragma once

#include <cstddef>
#include <vector>

#include "generate/city/ground.h"
#include "generate/city/terrain.h"

namespace render {

// How far past the city roads and rivers run on: into the haze at the horizon.
constexpr double kOnward = 30000;

// A sketch road leaving the city, carried straight on along its last segment.
struct RoadOnward {
  std::size_t road = 0;    // its centre line in Ground::roads
  exacity::RoadLine line;  // from the road's end outwards, kOnward long, as wide
};
// Every end of a centre line drawn in the sketch that no other centre line meets and
// from which the road runs off the city (20 m on lies in no zone, road area or water),
// kOnward on, or to 20 m short of where it would come back onto the city's ground.
std::vector<RoadOnward> roads_onward(const exacity::Ground& ground);

// Heightmap water at the map's edge, carried on past it. Past the map the terrain is the
// map mirrored, sinking to lowest() over fade() (Terrain::height_at), and water pixels hold
// the land's height: without water there the river ended in a bank along the map's edge.
struct WaterOnward {
  // The water polygons, each stretch of outline along a bound pushed out fade() past it
  // (the terrain mesh's banks follow it; the level stays the polygon's own).
  std::vector<geom::Polygon> near;
  // On from there, kOnward out over the plane beyond, each beside its water's index.
  std::vector<std::pair<std::size_t, geom::Polygon>> far;
  // Where that far water starts: fade() past the bound, less this overlap, so its
  // surface covers the near water's end bank.
  static constexpr double kOverlap = 5;
};
WaterOnward water_onward(const std::vector<geom::Polygon>& water, const exacity::Terrain* terrain);

}  // namespace render
