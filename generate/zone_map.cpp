#include "generate/zone_map.h"

#include <map>

#include "generate/drawn_zones.h"

namespace exacity {

namespace {

// Where road lines meet end to end (GIS editors and OpenStreetMap split roads into many
// lines), their flat ends would leave a notch: two ends of equal width get the mitre a
// single line would have, and other meetings a disc around the node.
void add_end_joints(const Sketch& sketch, int road_base, geom::PlanarMap& map) {
  struct End {
    int road;
    geom::Vec2 inner;  // the nearest other vertex along the line
    double half_width;
  };
  std::map<std::pair<double, double>, std::vector<End>> ends;
  for (int r = 0; r < static_cast<int>(sketch.roads.size()); ++r) {
    for (const geom::Polyline& line : sketch.roads[r].lines) {
      // Lines have at least two distinct points, and consecutive repeats are dropped.
      const double hw = sketch.roads[r].width / 2;
      ends[{line.front().x, line.front().y}].push_back({r, line[1], hw});
      ends[{line.back().x, line.back().y}].push_back({r, line[line.size() - 2], hw});
    }
  }
  for (const auto& [at, meeting] : ends) {
    geom::Vec2 q{at.first, at.second};
    if (meeting.size() == 2 && meeting[0].half_width == meeting[1].half_width) {
      map.add_joint(meeting[0].inner, q, meeting[1].inner, meeting[0].half_width, road_base + meeting[0].road);
    } else if (meeting.size() > 1) {
      for (const End& e : meeting) map.add_disc(q, e.half_width, road_base + e.road);
    }
  }
}

}  // namespace

int ZoneMap::road_of_counter(int counter) const {
  if (counter >= 1 && counter <= sketch_roads) return counter - 1;
  if (counter >= generated_base && counter < generated_base + static_cast<int>(roads.size()) - sketch_roads)
    return sketch_roads + counter - generated_base;
  return -1;
}

void ZoneMap::label(const Sketch& sketch) {
  constexpr int kWater = 0;
  labels.clear();
  index_.clear();
  map.label_faces([&](const geom::Windings& w) {
    FaceLabel l;
    l.zone = drawn->top_zone(w);
    const ZoneType type = l.zone >= 0 ? sketch.zones[l.zone].type : ZoneType::Park;
    const bool water = geom::winding_of(w, kWater) != 0 || (l.zone >= 0 && type == ZoneType::Water);
    // A grown road paves only where roads grow: its flat end stops at the region's edge. A
    // link paves all its way, over open land, parks and water.
    const bool paved_by_growth = l.zone >= 0 && grows_roads(type) && (!water || sketch.zone_params.at(type).bridges);
    for (auto [counter, winding] : w) {
      // Counters grow with road index, so the first road found is the first listed:
      // it owns a crossing.
      int r = road_of_counter(counter);
      if (r >= 0 && (r < sketch_roads || paved_by_growth || roads[r].link)) {
        l.road = r;
        break;
      }
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

int ZoneMap::label_index(const FaceLabel& l) {
  auto [it, added] = index_.emplace(l, static_cast<int>(labels.size()));
  if (added) labels.push_back(l);
  return it->second;
}

void ZoneMap::insert_lots() {
  std::vector<int> block_of_label;
  for (const FaceLabel& l : labels) block_of_label.push_back(l.lot < 0 ? l.block : -1);
  map.insert_within(block_of_label, [&](const geom::Windings& w, int previous) {
    if (w.empty()) return previous;
    FaceLabel l = labels[previous];
    l.lot = w.front().first - lot_base;
    return label_index(l);
  });
}

ZoneMap build_zone_map(const Sketch& sketch, const Terrain* terrain) {
  ZoneMap zm;
  const int road_base = 1;
  zm.sketch_roads = static_cast<int>(sketch.roads.size());
  if (terrain) {
    for (auto [a, b] : terrain->water_boundary()) zm.map.add_edge(a, b, 0);
  }
  int tag = 0;
  for (int r = 0; r < zm.sketch_roads; ++r) {
    const RoadFeature& f = sketch.roads[r];
    MapRoad road{f.road_class, f.width, -1, -1, f.index, {}, tag};
    for (const geom::Polyline& line : f.lines) {
      zm.map.add_stroke(line, f.width / 2, road_base + r);
      road.lines.push_back(geom::Path::from(line));
      zm.map.add_path(road.lines.back(), tag++);
    }
    zm.roads.push_back(std::move(road));
  }
  add_end_joints(sketch, road_base, zm.map);
  zm.drawn = std::make_shared<DrawnZones>(sketch.zones, zm.map, road_base + zm.sketch_roads);
  zm.generated_base = zm.drawn->end_counter();
  zm.map.insert_batch();
  zm.label(sketch);
  return zm;
}

}  // namespace exacity
