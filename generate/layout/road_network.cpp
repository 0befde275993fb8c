#include "generate/layout/road_network.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <tbb/parallel_for.h>

#include "generate/layout/growth.h"
#include "generate/layout/road_layout.h"
#include "generate/layout/settle.h"
#include "generate/city/random.h"
#include "geom/grid.h"
#include "geom/measure.h"

namespace exacity {
namespace {

// A region whose roads run on to no sketch road (a zone drawn a metre short of a highway,
// a lobe touching one at a point, a sketch without roads) is an island of streets. Each
// island is linked by the shortest straight road to the network joined so far, nearest
// island first, so the city's streets are one network; the sketch's roads start it, or
// the island with most roads when there are none. Returns the links added.
int link_islands(CityMap& city_map, const std::vector<char>& joined, std::vector<Junction>& junctions) {
  std::vector<std::vector<geom::Path>> network(joined.size());
  std::vector<double> width(joined.size());
  for (int r = city_map.sketch_roads; r < static_cast<int>(city_map.roads.size()); ++r) {
    const MapRoad& road = city_map.roads[r];
    if (network[road.region].empty()) width[road.region] = road.width;
    network[road.region].push_back(road.lines[0]);
  }
  std::vector<geom::Path> linked;
  for (int r = 0; r < city_map.sketch_roads; ++r)
    linked.insert(linked.end(), city_map.roads[r].lines.begin(), city_map.roads[r].lines.end());
  std::vector<int> islands;
  for (std::size_t r = 0; r < network.size(); ++r) {
    if (network[r].empty()) continue;
    if (joined[r]) linked.insert(linked.end(), network[r].begin(), network[r].end());
    else islands.push_back(static_cast<int>(r));
  }
  if (linked.empty() && !islands.empty()) {
    auto root = std::max_element(islands.begin(), islands.end(),
                                 [&](int a, int b) { return network[a].size() < network[b].size(); });
    linked = network[*root];
    islands.erase(root);
  }
  std::vector<geom::Link> nearest;
  for (int r : islands) nearest.push_back(*geom::shortest_link(network[r], linked));
  int links = 0;
  while (!islands.empty()) {
    const std::size_t k = std::min_element(nearest.begin(), nearest.end(),
                                           [](const auto& a, const auto& b) { return a.length < b.length; }) -
                          nearest.begin();
    const int region = islands[k];
    std::vector<geom::Path> added = network[region];
    if (!nearest[k].path.empty()) {
      MapRoad road;
      road.road_class = RoadClass::Main;
      road.width = width[region];
      road.level = 0;
      road.region = region;
      road.link = true;
      road.lines.push_back(nearest[k].path);
      for (std::size_t end : {0u, 1u}) junctions.push_back({nearest[k].path.point(end), static_cast<int>(city_map.roads.size())});
      city_map.roads.push_back(std::move(road));
      added.push_back(nearest[k].path);
      ++links;
    }
    islands.erase(islands.begin() + k);
    nearest.erase(nearest.begin() + k);
    for (std::size_t i = 0; i < islands.size(); ++i) {
      geom::Link l = *geom::shortest_link(network[islands[i]], added);
      if (l.length < nearest[i].length) nearest[i] = std::move(l);
    }
  }
  return links;
}


// The regions of zones whose layout is not growth (generate/layout), each planned alone,
// in parallel, then settled into the map's roads. Each connected piece of a region's roads
// counts as a region of its own, so link_islands joins every piece to the rest.
// `kind` is the growth's, by face label.
void lay_out_regions(CityMap& city_map, const Sketch& sketch, const SketchLines& sketch_lines, const std::vector<int>& kind,
                     std::vector<char>& joined, std::vector<Junction>& junctions, std::vector<PlannedUse>& uses,
                     RoadNetworkStats& stats) {
  std::map<ZoneType, std::unique_ptr<RoadLayout>> layouts;
  for (const auto& [t, p] : sketch.zone_params)
    if (grows_roads(t))
      if (std::unique_ptr<RoadLayout> layout = make_road_layout(p, t)) layouts[t] = std::move(layout);
  if (layouts.empty()) return;
  const std::vector<int> group = city_map.per_label([&](const FaceLabel& f) {
    return f.cover == Cover::Zone && f.zone >= 0 && layouts.count(sketch.zones[f.zone].type)
               ? static_cast<int>(sketch.zones[f.zone].type)
               : -1;
  });
  std::vector<int> types;
  std::vector<geom::Cell> cells = city_map.map.cells(group, kind, &types);
  const std::uint64_t stage = mix(mix(sketch.seed, static_cast<std::uint64_t>(Stage::Roads)), 0x1a1047);
  std::vector<geom::Path> sketch_roads;
  double sketch_width = 0;
  for (const SketchRoad& s : sketch_lines) {
    sketch_roads.insert(sketch_roads.end(), s.lines.begin(), s.lines.end());
    sketch_width = std::max(sketch_width, s.width);
  }
  std::vector<std::vector<SettledRoad>> settled(cells.size());
  std::vector<RoadPlan> plans(cells.size());
  tbb::parallel_for(std::size_t(0), cells.size(), [&](std::size_t i) {
    Random rng(mix(stage, i));
    plans[i] = layouts.at(static_cast<ZoneType>(types[i]))->plan({cells[i], edges_to_reach(cells[i], true)}, rng);
    settled[i] = settle(plans[i], cells[i], sketch_roads, sketch_width);
  });
  for (std::size_t i = 0; i < cells.size(); ++i) {
    for (PlannedUse& u : plans[i].uses) uses.push_back(std::move(u));
    const std::vector<SettledRoad>& roads = settled[i];
    std::map<int, int> region_of_piece;
    for (const SettledRoad& r : roads) {
      auto [it, added] = region_of_piece.emplace(r.piece, static_cast<int>(joined.size()));
      if (added) joined.push_back(r.reaches_sketch), ++stats.regions;
    }
    std::map<std::pair<double, double>, std::vector<int>> at;  // where roads meet end to end or at a shared vertex
    for (std::size_t r = 0; r < roads.size(); ++r)
      for (std::size_t k = 0; k < roads[r].path.size(); ++k) {
        const geom::Vec2 p = roads[r].path.point(k);
        at[{p.x, p.y}].push_back(static_cast<int>(r));
      }
    const int first = static_cast<int>(city_map.roads.size());
    for (std::size_t r = 0; r < roads.size(); ++r) {
      MapRoad m;
      m.road_class = roads[r].road_class;
      m.width = roads[r].width;
      m.level = roads[r].road_class == RoadClass::Main ? 0 : 1;
      m.region = region_of_piece[roads[r].piece];
      m.lines.push_back(roads[r].path);
      city_map.roads.push_back(std::move(m));
    }
    for (const auto& [p, here] : at)
      if (here.size() > 1) junctions.push_back({{p.first, p.second}, first + here.front()});
  }
}

// Every generated road into the map in one batch: centre line, area, and a disc where
// roads meet; then the map is labelled again.
void insert_generated_roads(CityMap& city_map, const std::vector<Junction>& junctions, const Sketch& sketch) {
  int tag = 0;
  for (const MapRoad& r : city_map.roads) tag = std::max(tag, r.first_tag + static_cast<int>(r.lines.size()));
  city_map.generated_roads.size = static_cast<int>(city_map.roads.size()) - city_map.sketch_roads;
  for (int r = city_map.sketch_roads; r < static_cast<int>(city_map.roads.size()); ++r) {
    MapRoad& road = city_map.roads[r];
    road.first_tag = tag;
    city_map.map.add_path(road.lines[0], tag++);
    city_map.map.add_path_stroke(road.lines[0], road.width / 2, city_map.road_counter(r));
  }
  for (const Junction& s : junctions) city_map.map.add_disc(s.at, city_map.roads[s.first_road].width / 2, city_map.road_counter(s.first_road));
  city_map.map.insert_batch();
  city_map.label(sketch);
}

}  // namespace

RoadNetwork grow_road_network(CityMap city_map, const Sketch& sketch) {
  RoadNetwork net;
  const std::vector<int> kind = city_map.per_label([&](const FaceLabel& f) {
    return f.road_surface() && f.road < city_map.sketch_roads ? GrowthEdge::sketch_road(f.road) : GrowthEdge::kRegionEdge;
  });
  SketchLines sketch_lines;
  for (int r = 0; r < city_map.sketch_roads; ++r) sketch_lines.push_back({city_map.roads[r].lines, city_map.roads[r].width});

  GrownRegions grown = grow_regions(city_map, sketch, sketch_lines, kind);
  net.stats.regions = grown.regions;
  net.stats.levels = grown.levels;
  net.stats.cells_without_access = grown.cells_without_access;
  lay_out_regions(city_map, sketch, sketch_lines, kind, grown.joined, grown.junctions, net.uses, net.stats);
  net.stats.links = link_islands(city_map, grown.joined, grown.junctions);
  insert_generated_roads(city_map, grown.junctions, sketch);
  net.map = std::move(city_map);
  return net;
}

}  // namespace exacity
