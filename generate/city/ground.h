// The ground as the city map leaves it, typed: zones, water, roads and their surfaces,
// blocks and lots, each as the vector layers write it (docs/design.md, The city model).
// The exports and the renderer read these, never the layers' GeoJSON properties. Inside the
// program a feature is named by its index in its list (blocks carry their own); the outputs
// write its stable_id instead (generate/city/stable_ids.h), drawn from what it is.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "generate/city/city_map.h"
#include "generate/city/zone_type.h"
#include "geom/plain.h"

namespace exacity {

struct ZoneArea {
  ZoneType type = ZoneType::Residential;
  geom::Polygon polygon;
  int stable_id = -1;  // its id in the outputs
};

// A centre line, cut where it goes on or off a bridge.
struct RoadLine {
  RoadClass road_class = RoadClass::Highway;
  double width = 0;
  int level = -1;   // growth level; -1 for roads drawn in the sketch
  int region = -1;  // the region it was laid out in; -1 for roads drawn in the sketch
  bool bridge = false;
  geom::Polyline line;
  int sketch_road = -1;  // its road in Sketch::roads; -1 for roads laid out
  // Its road's OpenStreetMap tags as read (RoadFeature::osm_tags): every piece of a way the
  // map cuts keeps the way's.
  std::vector<std::pair<std::string, std::string>> osm_tags;
  int stable_id = -1;         // its id in the outputs
  int region_stable_id = -1;  // its region's id in the outputs, -1 for roads drawn in the sketch
};

// A piece of a road's surface: carriageway, sidewalk or junction.
struct RoadArea {
  int road = -1;  // the id of the first centre line of its road, -1 if it has none
  bool bridge = false;
  RoadSurface surface = RoadSurface::Carriageway;
  geom::Polygon polygon;
  int stable_id = -1;  // its id in the outputs
};

// A block as written: rounding can pinch a block in two, and each piece is a feature.
struct BlockArea {
  int id = 0;     // the block's index for its first piece, ids after the last block's for others
  int block = 0;  // the Block it is a piece of
  ZoneType zone = ZoneType::Residential;
  bool green = false;
  std::vector<int> roads;  // the ids of the centre lines it fronts, -1 for a road with none
  geom::Polygon polygon;
  int stable_id = -1;  // its id in the outputs
};

struct LotArea {
  int block = 0;  // the id of the block piece it lies in
  ZoneType zone = ZoneType::Residential;
  geom::Polygon polygon;
  int stable_id = -1;  // its id in the outputs
};

struct Ground {
  std::vector<ZoneArea> zones;
  std::vector<geom::Polygon> water;
  std::vector<int> water_stable_ids;  // each water polygon's id in the outputs
  std::vector<RoadLine> roads;
  std::vector<RoadArea> road_areas;
  std::vector<BlockArea> blocks;
  std::vector<LotArea> lots;
  // The ids of the first centre lines of roads no road area names (report.json names
  // them): what every face a road's carriageway covers is in is another's and could not be
  // given to it, or rounding took all it had.
  std::vector<int> roads_without_area;

  // The box around zones, water and road areas (what covers the ground); holds nothing
  // for an empty city.
  geom::Box bounds() const {
    geom::Box box = geom::Box::none();
    for (const auto& z : zones)
      for (geom::Vec2 p : z.polygon.outer) box.add(p);
    for (const auto& w : water)
      for (geom::Vec2 p : w.outer) box.add(p);
    for (const auto& r : road_areas)
      for (geom::Vec2 p : r.polygon.outer) box.add(p);
    return box;
  }
};

}  // namespace exacity
