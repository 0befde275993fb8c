// The city's planar map: drawn zones, heightmap water and road areas in one exact
// arrangement, every face labelled with what covers it (docs/design.md, The city model). The road-network
// stage refines the same map.
#pragma once

#include <compare>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "generate/city/drawn_zones.h"
#include "generate/city/features.h"
#include "generate/city/terrain.h"
#include "generate/city/zone_settings.h"
#include "geom/planar_map.h"

namespace exacity {

// What the user sees at a face: water beats road beats drawn zone.
enum class Cover : std::uint8_t { Outside, Zone, Water, Road };

// Which part of a road a road face is: its carriageway, a sidewalk beside it, or
// the junction where streets meet. A junction beats a carriageway beats a sidewalk.
enum class RoadSurface : std::uint8_t { None, Carriageway, Sidewalk, Junction };
inline const char* name(RoadSurface s) {
  return s == RoadSurface::Sidewalk ? "sidewalk" : s == RoadSurface::Junction ? "junction" : "carriageway";
}

struct FaceLabel {
  Cover cover = Cover::Outside;
  int zone = -1;        // index into Sketch::zones of the drawn zone on top, -1 if none
  int road = -1;        // index into CityMap::roads of the road whose surface this is, -1 if none
  bool bridge = false;  // a road surface over water
  int block = -1;       // index of the block it lies in, once blocks are in the map
  int lot = -1;         // index of the lot it lies in, once lots are in the map
  RoadSurface surface = RoadSurface::None;  // on a road face
  int junction = -1;    // index into CityMap::junction_roads of the junction it lies in
  // The surface of road `road`: on land, or a bridge's over water.
  bool road_surface() const { return road >= 0 && (cover == Cover::Road || bridge); }
  friend auto operator<=>(const FaceLabel&, const FaceLabel&) = default;
};

// A road in the map: a sketch road (level -1) or a generated one.
struct MapRoad {
  RoadClass road_class = RoadClass::Highway;
  double width = 0;
  int level = -1;    // growth level; -1 for roads drawn in the sketch
  int region = -1;   // the region it was grown in; -1 for roads drawn in the sketch
  int feature = -1;  // its index in the sketch's features; -1 for generated roads
  std::vector<geom::Path> lines;
  int first_tag = 0;  // polyline tag of lines[0]; the others follow
  bool link = false;  // joins a region's streets to the rest (road_network.cpp): paved wherever it runs
  std::vector<std::pair<std::string, std::string>> osm_tags;  // a sketch road's (RoadFeature::osm_tags)
};

// A run of the map's winding counters that one kind of thing winds around: thing i
// around first + i.
struct CounterRange {
  int first = 0, size = 0;
  int at(int i) const { return first + i; }
  bool holds(int counter) const { return counter >= first && counter < first + size; }
  int index_of(int counter) const { return counter - first; }
  int end() const { return first + size; }
};

// What labelling a face reads of the drawn zone on top: its type, and whether a generated
// road paves it (its layout lays roads) and the water in it (its roads bridge water).
struct ZonePaving {
  ZoneType type = ZoneType::Park;
  bool generated_roads = false;
  bool bridges = false;
};

struct CityMap {
  geom::PlanarMap map;
  std::vector<FaceLabel> labels;  // indexed by face label
  std::vector<MapRoad> roads;     // sketch roads first, in sketch order
  int sketch_roads = 0;
  // Per region of the road stage (MapRoad::region), a hash of what it is: its layout and
  // exact cell, and its piece of the plan; its id in the outputs is drawn from it.
  std::vector<std::uint64_t> region_hashes;

  // The map's counters, range after range; each range is sized before the next opens.
  // The map owns them: every stage takes its counters from here.
  CounterRange heightmap_water{0, 1};  // the heightmap's water edges
  CounterRange sketch_carriageways;  // sketch road r's carriageway
  std::shared_ptr<DrawnZones> drawn;  // the drawn zones' rings come next (DrawnZones)
  CounterRange sidewalks;             // sketch road r's sidewalks
  CounterRange junctions;             // junction j, a polygon where sketch roads meet
  CounterRange generated_roads;       // road sketch_roads + i, grown or laid out, with its discs
  CounterRange lots;                  // lot l, once the lots stage has run
  std::vector<ZonePaving> zones;      // per drawn zone
  std::vector<int> junction_roads;  // per junction, the road it belongs to: the first to meet there
  int mitred_junctions = 0, disc_junctions = 0;  // how the sketch's road meetings were drawn

  // The carriageway counter of road r (sketch or generated).
  int road_counter(int r) const {
    return r < sketch_roads ? sketch_carriageways.at(r) : generated_roads.at(r - sketch_roads);
  }
  // The road whose carriageway winds around `counter`, or -1.
  int road_of_counter(int counter) const;
  // (Re)labels every face from its windings.
  void label();
  // The index of this label in `labels`, added if new.
  int label_index(const FaceLabel& l);
  // f(label) for every face label: how a stage picks faces (a group, -1 for none) and
  // names the edges between them (a kind) for geom::PlanarMap's cells and dissolve.
  template <typename F>
  std::vector<int> per_label(F&& f) const {
    std::vector<int> out;
    out.reserve(labels.size());
    for (const FaceLabel& l : labels) out.push_back(f(l));
    return out;
  }
  // Inserts the lots queued with map.add_*_within(block, ring, lots.at(lot)), each
  // within its block's faces: a face of a block lies in the first lot around it planned in
  // that block, so a lot that would cross a road or another block stops there.
  void insert_lots();

 private:
  std::map<FaceLabel, int> index_;
};

// The zone-map stage.
CityMap build_city_map(const CitySettings& settings, const DrawnFeatures& features, const Terrain* terrain);

}  // namespace exacity
