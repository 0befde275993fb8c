#include "generate/city/city_map.h"

#include <cmath>
#include <map>

#include "generate/cancel.h"
#include "generate/city/drawn_zones.h"
#include "generate/city/street_graph.h"

namespace exacity {

namespace {

// Where sketch roads meet (generate/city/street_graph.h), one mitred junction polygon (seed
// 004) instead of the notches their flat ends would leave; and, where the streets have
// sidewalks, an outer one of their sidewalks' width. A meeting too sharp for a mitre gets
// a disc of each road's width, as before junctions were mitred.
void add_junctions(const DrawnFeatures& features, CityMap& city_map) {
  for (const StreetNode& node : street_nodes(features.roads)) {
    std::vector<geom::JunctionArm> carriageway, outer;
    bool sidewalks = false;
    for (const StreetArm& arm : node.arms) {
      const RoadFeature& r = features.roads[arm.road];
      const double sidewalk = r.widest_sidewalk();
      carriageway.push_back({arm.toward, r.width / 2, arm.length});
      outer.push_back({arm.toward, r.width / 2 + sidewalk, arm.length});
      sidewalks |= sidewalk > 0;
    }
    const int first = node.arms.front().road;
    const int junction = static_cast<int>(city_map.junction_roads.size());
    if (city_map.map.add_junction(node.at, carriageway, city_map.junctions.at(junction))) {
      city_map.junction_roads.push_back(first);
      ++city_map.junctions.size;
      ++city_map.mitred_junctions;
      if (sidewalks) city_map.map.add_junction(node.at, outer, city_map.sidewalks.at(first));
      continue;
    }
    // Straight on (nothing needed) or too sharp.
    if (node.arms.size() == 2 && carriageway[0].half_width == carriageway[1].half_width &&
        outer[0].half_width == outer[1].half_width)
      continue;
    ++city_map.disc_junctions;
    for (const StreetArm& arm : node.arms) {
      const RoadFeature& r = features.roads[arm.road];
      city_map.map.add_disc(node.at, r.width / 2, city_map.sketch_carriageways.at(arm.road));
      if (sidewalks)
        city_map.map.add_disc(node.at, r.width / 2 + r.widest_sidewalk(), city_map.sidewalks.at(arm.road));
    }
  }
}

// The ground between a line and its offset by `d` (to its left; right where negative),
// mitred as a stroke's side (bevelled past the same limit of 4): where a road has a sidewalk
// on one side only (OSM's sidewalk=left or right), what its carriageway leaves of it is that
// sidewalk. A sharp bend can fold the offset over itself; the fold still winds around the
// counter, under the carriageway.
geom::Ring one_side(const geom::Polyline& line, double d) {
  auto normal = [&](std::size_t i) {  // of segment i -> i + 1, to its left
    const double dx = line[i + 1].x - line[i].x, dy = line[i + 1].y - line[i].y, length = std::hypot(dx, dy);
    return length > 0 ? geom::Vec2{-dy / length, dx / length} : geom::Vec2{0, 0};
  };
  geom::Ring ring(line.begin(), line.end());
  std::vector<geom::Vec2> offset;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const geom::Vec2 before = normal(i > 0 ? i - 1 : i), after = normal(i + 1 < line.size() ? i : i - 1);
    const geom::Vec2 mitre{before.x + after.x, before.y + after.y};
    const double cosine = (mitre.x * before.x + mitre.y * before.y);  // |mitre| cos(half the turn)
    const double scale = cosine > 0 ? d / cosine : 0;
    if (cosine > 0 && std::hypot(mitre.x, mitre.y) * std::abs(scale) <= 4 * std::abs(d)) {
      offset.push_back({line[i].x + mitre.x * scale, line[i].y + mitre.y * scale});
    } else {
      offset.push_back({line[i].x + before.x * d, line[i].y + before.y * d});
      offset.push_back({line[i].x + after.x * d, line[i].y + after.y * d});
    }
  }
  ring.insert(ring.end(), offset.rbegin(), offset.rend());
  return ring;
}

}  // namespace

int CityMap::road_of_counter(int counter) const {
  if (sketch_carriageways.holds(counter)) return sketch_carriageways.index_of(counter);
  if (generated_roads.holds(counter)) return sketch_roads + generated_roads.index_of(counter);
  return -1;
}

void CityMap::label() {
  labels.clear();
  index_.clear();
  map.label_faces([&](const geom::Windings& w) {
    FaceLabel l;
    l.zone = drawn->top_zone(w);
    const ZonePaving zone = l.zone >= 0 ? zones[l.zone] : ZonePaving{};
    const ZoneType type = zone.type;
    const bool water = geom::winding_of(w, heightmap_water.first) != 0 || (l.zone >= 0 && type == ZoneType::Water);
    // A generated road paves only where roads are generated (not in a zone laid out as
    // "streets"): its flat end stops at the region's edge. A link paves all its way, over
    // open land, parks and water.
    const bool paved_by_growth = l.zone >= 0 && grows_roads(type) && zone.generated_roads && (!water || zone.bridges);
    // Counters grow with road index, so the first road found is the first listed: it owns
    // a crossing.
    int carriageway = -1, sidewalk = -1, junction = -1;
    for (auto [counter, winding] : w) {
      if (junctions.holds(counter)) {
        if (junction < 0) junction = junctions.index_of(counter);
      } else if (sidewalks.holds(counter)) {
        if (sidewalk < 0) sidewalk = sidewalks.index_of(counter);
      } else if (int r = road_of_counter(counter); carriageway < 0 && r >= 0) {
        if (r < sketch_roads || paved_by_growth || roads[r].link) carriageway = r;
      }
    }
    if (junction >= 0) {
      l.road = junction_roads[junction], l.junction = junction, l.surface = RoadSurface::Junction;
    } else if (carriageway >= 0) {
      l.road = carriageway, l.surface = RoadSurface::Carriageway;
    } else if (sidewalk >= 0) {
      l.road = sidewalk, l.surface = RoadSurface::Sidewalk;
    }
    if (water) {
      l.cover = Cover::Water;
      l.bridge = l.road >= 0;
    } else if (l.road >= 0) {
      l.cover = Cover::Road;
    } else if (l.zone >= 0) {
      l.cover = Cover::Zone;
    }
    return label_index(l);
  });
}

int CityMap::label_index(const FaceLabel& l) {
  auto [it, added] = index_.emplace(l, static_cast<int>(labels.size()));
  if (added) labels.push_back(l);
  return it->second;
}

void CityMap::insert_lots() {
  std::vector<int> block_of_label;
  for (const FaceLabel& l : labels) block_of_label.push_back(l.lot < 0 ? l.block : -1);
  // Every face inserted is labelled here: the one place a cancel reaches inside the insertion
  // (docs/design.md, Serving: cancelling); the map is dropped with the build.
  const CancelCheck cancel;
  map.insert_within(block_of_label, [&](const geom::Windings& w, int previous) {
    cancel.check();
    if (w.empty()) return previous;
    FaceLabel l = labels[previous];
    l.lot = lots.index_of(w.front().first);
    return label_index(l);
  });
}

CityMap build_city_map(const CitySettings& settings, const DrawnFeatures& features, const Terrain* terrain) {
  CityMap city_map;
  for (const ZoneFeature& z : features.zones) {
    const RoadSettings& roads = settings.zone_settings.at(z.type).roads;
    city_map.zones.push_back({z.type, roads.layout->generates_roads(), roads.bridges});
  }
  city_map.sketch_roads = static_cast<int>(features.roads.size());
  city_map.sketch_carriageways = {city_map.heightmap_water.end(), city_map.sketch_roads};
  if (terrain) {
    for (const geom::Ring& r : terrain->water_boundary()) city_map.map.add_ring(r, city_map.heightmap_water.first);
  }
  int tag = 0;
  for (int r = 0; r < city_map.sketch_roads; ++r) {
    const RoadFeature& f = features.roads[r];
    MapRoad road{f.road_class, f.width, -1, -1, f.index, {}, tag, false, f.osm_tags};
    for (const geom::Polyline& line : f.lines) {
      city_map.map.add_stroke(line, f.width / 2, city_map.sketch_carriageways.at(r));
      road.lines.push_back(geom::Path::from(line));
      city_map.map.add_path(road.lines.back(), tag++);
    }
    city_map.roads.push_back(std::move(road));
  }
  city_map.drawn = std::make_shared<DrawnZones>(features.zones, city_map.map, city_map.sketch_carriageways.end());
  city_map.sidewalks = {city_map.drawn->end_counter(), city_map.sketch_roads};
  city_map.junctions = {city_map.sidewalks.end(), 0};
  for (int r = 0; r < city_map.sketch_roads; ++r) {
    const RoadFeature& f = features.roads[r];
    for (const geom::Polyline& line : f.lines) {
      if (f.sidewalk_left == f.sidewalk_right) {
        if (f.sidewalk_left > 0) city_map.map.add_stroke(line, f.width / 2 + f.sidewalk_left, city_map.sidewalks.at(r));
      } else {
        for (const double side : {f.sidewalk_left, -f.sidewalk_right})
          if (side != 0) city_map.map.add_ring(one_side(line, side > 0 ? f.width / 2 + side : side - f.width / 2), city_map.sidewalks.at(r));
      }
    }
  }
  add_junctions(features, city_map);
  city_map.generated_roads = {city_map.junctions.end(), 0};
  city_map.map.insert_batch();
  city_map.label();
  return city_map;
}

}  // namespace exacity
