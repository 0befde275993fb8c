#include "generate/layout/road_network.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>

#include <tbb/parallel_for.h>

#include "generate/cancel.h"
#include "generate/layout/growth.h"
#include "generate/layout/road_layout.h"
#include "generate/city/random.h"
#include "generate/city/stable_ids.h"
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


// What the layouts laid so far, besides the map's roads.
struct Laid {
  std::vector<char> joined;  // per region: its roads run on to a sketch road
  std::vector<Junction> junctions;
};

void add_road(CityMap& city_map, const LaidRoad& road, int region) {
  MapRoad m;
  m.road_class = road.road_class;
  m.width = road.width;
  m.level = road.level;
  m.region = region;
  m.lines.push_back(road.path);
  city_map.roads.push_back(std::move(m));
}

// Each region's plan, in parallel: region i takes the stream mix(stage, i) (a stream of its
// exact cell would draw a region of growth afresh after any edit of it, where the town's
// market edit keeps most of its roads: 45 block plans of 1,408 reused against 1,439). With a
// memo, a
// plan is reused when its region is the same cell with the same stream, laid out by the same
// layout (`layout_key`) over the same drawn zones (which say the zone at each point).
// Each region's hash (CityMap::region_hashes) is of its layout and exact cell.
std::vector<RoadPlan> plan_regions(const std::vector<geom::Cell>& cells, std::uint64_t stage,
                                   const std::function<const RoadLayout&(std::size_t)>& layout_of,
                                   const std::function<std::string(std::size_t)>& layout_key,
                                   const std::vector<ZoneFeature>& zones, Memo<RoadPlan>* memo,
                                   std::vector<std::uint64_t>& hashes) {
  std::vector<RoadPlan> plans(cells.size());
  hashes.assign(cells.size(), 0);
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), cells.size(), [&](std::size_t i) {
    cancel.check();
    const std::string cell_text = geom::exact_text(cells[i]);
    const Region region{cells[i], mix(stage, i)};
    auto plan = [&] { return layout_of(i).plan(region); };
    hashes[i] = ContentHash(content_id(layout_key(i))).add(std::string_view(cell_text)).value();
    if (!memo) {
      plans[i] = plan();
      return;
    }
    std::string key = layout_key(i) + " stream " + std::to_string(region.stream) + " " + cell_text;
    append_zones_over(key, zones, region.cell.bounds());
    plans[i] = memo->get(key, plan);
  });
  return plans;
}

// The type of the zone at a point, where roads grow in it.
ZoneAt zone_at(const CityMap& city_map, const std::vector<ZoneFeature>& zones) {
  return [&](geom::Vec2 p) -> std::optional<ZoneType> {
    const int l = city_map.map.label_at(p);
    if (l < 0 || city_map.labels[l].zone < 0) return std::nullopt;
    const ZoneType t = zones[city_map.labels[l].zone].type;
    return grows_roads(t) ? std::optional<ZoneType>(t) : std::nullopt;
  };
}

// The regions of growth, the layout whose regions span zone types: connected faces of
// zones laid out by it (and the water under them where the zone lets roads bridge it), one
// piece each. Their roads take ids a level at a time across regions, every region's main
// roads first.
void lay_out_growth(CityMap& city_map, const CitySettings& settings, const std::vector<ZoneFeature>& zones,
                    const SketchLines& sketch_lines, const std::vector<int>& kind, Laid& laid, RoadNetworkStats& stats,
                    Memo<RoadPlan>* memo) {
  auto params = [&](ZoneType t) -> const RoadSettings& { return settings.zone_settings.at(t).roads; };
  const RoadLayoutChoice* spanning = nullptr;
  for (const auto& [t, z] : settings.zone_settings)
    if (grows_roads(t) && z.roads.layout->spans_zone_types() && !spanning) spanning = z.roads.layout.get();
  if (!spanning) return;
  const std::vector<int> group = city_map.per_label([&](const FaceLabel& f) {
    ZoneType t = f.zone >= 0 ? zones[f.zone].type : ZoneType::Park;
    bool growable = f.zone >= 0 && grows_roads(t) && params(t).layout->spans_zone_types();
    return (f.cover == Cover::Zone && growable) || (f.cover == Cover::Water && growable && params(t).bridges) ? 0 : -1;
  });
  const std::unique_ptr<RoadLayout> growth =
      spanning->make({settings, ZoneType::Residential, sketch_lines, zone_at(city_map, zones)});
  std::vector<std::uint64_t> hashes;
  const std::vector<RoadPlan> plans = plan_regions(city_map.map.cells(group, kind), mix(settings.seed, static_cast<std::uint64_t>(Stage::Roads)),
                                                   [&](std::size_t) -> const RoadLayout& { return *growth; },
                                                   [](std::size_t) { return std::string("growth"); }, zones, memo, hashes);
  const int first_region = static_cast<int>(laid.joined.size());
  city_map.region_hashes.insert(city_map.region_hashes.end(), hashes.begin(), hashes.end());
  for (const RoadPlan& plan : plans) {
    laid.joined.push_back(plan.piece_reaches_sketch[0]);
    stats.levels = std::max(stats.levels, plan.levels);
    stats.cells_without_access += plan.cells_without_access;
  }
  stats.regions += static_cast<int>(plans.size());
  std::vector<std::size_t> road(plans.size(), 0), junction(plans.size(), 0);  // each plan's next
  for (int level = 0; level < stats.levels; ++level)
    for (std::size_t i = 0; i < plans.size(); ++i)
      for (const auto& roads = plans[i].roads; road[i] < roads.size() && roads[road[i]].level == level; ++road[i]) {
        for (const auto& js = plans[i].junctions; junction[i] < js.size() && js[junction[i]].first_road == static_cast<int>(road[i]); ++junction[i])
          laid.junctions.push_back({js[junction[i]].at, static_cast<int>(city_map.roads.size())});
        add_road(city_map, roads[road[i]], first_region + static_cast<int>(i));
      }
}

// The regions of zones laid out otherwise, a region per connected set of faces of one zone
// type; each plan's pieces count as regions of their own, so link_islands joins every piece
// to the rest.
void lay_out_regions(CityMap& city_map, const CitySettings& settings, const std::vector<ZoneFeature>& zones,
                     const SketchLines& sketch_lines, const std::vector<int>& kind, Laid& laid,
                     std::vector<PlannedUse>& uses, RoadNetworkStats& stats, Memo<RoadPlan>* memo) {
  std::map<ZoneType, std::unique_ptr<RoadLayout>> layouts;
  for (const auto& [t, p] : settings.zone_settings)
    if (grows_roads(t) && !p.roads.layout->spans_zone_types()) layouts[t] = p.roads.layout->make({settings, t, sketch_lines, {}});
  if (layouts.empty()) return;
  const std::vector<int> group = city_map.per_label([&](const FaceLabel& f) {
    return f.cover == Cover::Zone && f.zone >= 0 && layouts.count(zones[f.zone].type)
               ? static_cast<int>(zones[f.zone].type)
               : -1;
  });
  std::vector<int> types;
  const std::vector<geom::Cell> cells = city_map.map.cells(group, kind, &types);
  const std::uint64_t stage = mix(mix(settings.seed, static_cast<std::uint64_t>(Stage::Roads)), 0x1a1047);
  std::vector<std::uint64_t> hashes;
  std::vector<RoadPlan> plans = plan_regions(cells, stage, [&](std::size_t i) -> const RoadLayout& {
    return *layouts.at(static_cast<ZoneType>(types[i]));
  }, [&](std::size_t i) { return "layout of " + std::to_string(types[i]); }, zones, memo, hashes);
  for (std::size_t i = 0; i < plans.size(); ++i) {
    RoadPlan& plan = plans[i];
    for (PlannedUse& u : plan.uses) uses.push_back(std::move(u));
    const int first_region = static_cast<int>(laid.joined.size());
    laid.joined.insert(laid.joined.end(), plan.piece_reaches_sketch.begin(), plan.piece_reaches_sketch.end());
    for (std::size_t piece = 0; piece < plan.piece_reaches_sketch.size(); ++piece)
      city_map.region_hashes.push_back(mix(hashes[i], piece));
    stats.regions += static_cast<int>(plan.piece_reaches_sketch.size());
    stats.dropped_roads += plan.dropped_roads;
    const int first = static_cast<int>(city_map.roads.size());
    for (const LaidRoad& r : plan.roads) add_road(city_map, r, first_region + r.piece);
    for (const Junction& j : plan.junctions) laid.junctions.push_back({j.at, first + j.first_road});
  }
}

// Every generated road into the map in one batch: centre line, area, and a disc where
// roads meet; then the map is labelled again.
void insert_generated_roads(CityMap& city_map, const std::vector<Junction>& junctions) {
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
  city_map.label();
}

}  // namespace

RoadNetwork grow_road_network(CityMap city_map, const CitySettings& settings, const std::vector<ZoneFeature>& zones,
                              Memo<RoadPlan>* memo) {
  RoadNetwork net;
  const std::vector<int> kind = city_map.per_label([&](const FaceLabel& f) {
    return f.road_surface() && f.road < city_map.sketch_roads ? GrowthEdge::sketch_road(f.road) : GrowthEdge::kRegionEdge;
  });
  SketchLines sketch_lines;
  for (int r = 0; r < city_map.sketch_roads; ++r) sketch_lines.push_back({city_map.roads[r].lines, city_map.roads[r].width});

  Laid laid;
  lay_out_growth(city_map, settings, zones, sketch_lines, kind, laid, net.stats, memo);
  lay_out_regions(city_map, settings, zones, sketch_lines, kind, laid, net.uses, net.stats, memo);
  net.stats.links = link_islands(city_map, laid.joined, laid.junctions);
  insert_generated_roads(city_map, laid.junctions);
  net.map = std::move(city_map);
  return net;
}

}  // namespace exacity
