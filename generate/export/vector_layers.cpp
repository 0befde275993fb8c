#include "generate/export/vector_layers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

#include "generate/cancel.h"
#include "generate/cancellable_invoke.h"
#include "generate/city/stable_ids.h"
#include "generate/export/read_lines.h"
#include "geom/box_index.h"
#include "geom/measure.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using nlohmann::ordered_json;

using Dissolved = std::vector<std::vector<geom::Dissolved>>;

// The faces dissolved into polygons: group_of(label) picks each face's group (-1: none).
template <typename GroupOf>
Dissolved dissolved(const CityMap& city_map, int group_count, GroupOf group_of) {
  CancelCheck().check();
  return city_map.map.dissolve(city_map.per_label(group_of), group_count);
}

// add(group, polygon) receives the polygons in a stable order.
template <typename Add>
void add_each(Dissolved polygons, Add add) {
  const CancelCheck cancel;
  for (std::size_t g = 0; g < polygons.size(); ++g) {
    cancel.check();
    for (geom::Dissolved& d : polygons[g]) add(static_cast<int>(g), std::move(d.polygon));
  }
}

// Dissolves faces into polygons: group_of(label) picks each face's group (-1: none);
// add(group, polygon) receives them in a stable order.
template <typename GroupOf, typename Add>
void dissolve(const CityMap& city_map, int group_count, GroupOf group_of, Add add) {
  add_each(dissolved(city_map, group_count, group_of), add);
}

// A nested model's slabs as the buildings layer writes them (docs/design.md, Outputs):
// heights from its floor, each piece a closed ring, counter-clockwise, as GeoJSON writes one.
ordered_json slabs_json(const std::vector<Slab>& slabs) {
  ordered_json out = ordered_json::array();
  for (const Slab& s : slabs) {
    ordered_json rings = ordered_json::array();
    for (const geom::Ring& r : s.outline) {
      ordered_json ring = ordered_json::array();
      for (geom::Vec2 v : r) ring.push_back({v.x, v.y});
      ring.push_back({r.front().x, r.front().y});
      rings.push_back(std::move(ring));
    }
    out.push_back({{"bottom", s.bottom}, {"top", s.top}, {"outline", std::move(rings)}});
  }
  return out;
}

}  // namespace

namespace {

// The files are read at once, each with its own problems, listed in this order; with
// `known`, each with the ReadLines under its name (made here, so the reads only look them up).
CityLayers read_each_layer(const std::filesystem::path& vector_dir, std::vector<std::string>& problems,
                           std::map<std::string, ReadLines>* known) {
  CityLayers layers;
  const std::vector<Layer*> all{&layers.zones,  &layers.water, &layers.roads,    &layers.road_areas,
                                &layers.blocks, &layers.lots,  &layers.buildings};
  std::vector<ReadLines*> lines(all.size(), nullptr);
  if (known)
    for (std::size_t i = 0; i < all.size(); ++i) lines[i] = &(*known)[all[i]->name];
  std::vector<std::vector<std::string>> read_problems(all.size());
  for_each_cancellable(all.size(), [&](std::size_t i) {
    const std::filesystem::path file = vector_dir / (all[i]->name + ".geojson");
    *all[i] = lines[i] ? read_geojson(file, read_problems[i], *lines[i]) : read_geojson(file, read_problems[i]);
  });
  for (const auto& p : read_problems) problems.insert(problems.end(), p.begin(), p.end());
  return layers;
}

}  // namespace

CityLayers read_layers(const std::filesystem::path& vector_dir, std::vector<std::string>& problems) {
  return read_each_layer(vector_dir, problems, nullptr);
}

CityLayers read_layers(const std::filesystem::path& vector_dir, std::vector<std::string>& problems,
                       std::map<std::string, ReadLines>& known) {
  return read_each_layer(vector_dir, problems, &known);
}

namespace {

// The drawn zones by type, then the water.
void extract_zones_and_water(const CityMap& city_map, const std::vector<ZoneFeature>& zones, Ground& out) {
  const int zone_types = static_cast<int>(ZoneType::Water);  // water has its own layer
  dissolve(city_map, zone_types,
           [&](const FaceLabel& l) { return l.cover == Cover::Zone ? static_cast<int>(zones[l.zone].type) : -1; },
           [&](int g, geom::Polygon p) { out.zones.push_back({static_cast<ZoneType>(g), std::move(p)}); });
  dissolve(city_map, 1, [](const FaceLabel& l) { return l.cover == Cover::Water ? 0 : -1; },
           [&](int, geom::Polygon p) { out.water.push_back(std::move(p)); });
}

// Centre lines with every junction as a vertex, cut where they go on or off a bridge.
// Returns each map road's first centre line on land and on a bridge: what its areas and
// the blocks along it name.
//
// Each rounded segment is written once, by the first line that has it: two exact edges
// nearer each other than a double's step (roads leaving one point at 1e-11 rad) can round
// to the same segment, and the later line then stops before it and goes on after it, so
// the two meet at its ends, vertices of both, and never overlap. A road all of whose
// segments an earlier line wrote is that line at the output's precision: its areas name it.
std::vector<std::array<int, 2>> extract_centre_lines(const CityMap& city_map, Ground& out) {
  std::vector<std::array<int, 2>> first_line(city_map.roads.size(), {-1, -1});
  auto pieces_of = city_map.map.polyline_pieces();
  std::map<geom::SegmentKey, int> written;  // the line that wrote each segment
  const CancelCheck cancel;
  for (std::size_t r = 0; r < city_map.roads.size(); ++r) {
    cancel.check();
    const MapRoad& road = city_map.roads[r];
    int covering = -1;  // the first earlier line holding one of this road's segments
    for (int k = 0; k < static_cast<int>(road.lines.size()); ++k) {
      geom::Polyline run;
      bool run_bridge = false;
      auto flush = [&] {
        if (run.size() < 2) return;
        int& first = first_line[r][run_bridge];
        if (first < 0) first = static_cast<int>(out.roads.size());
        const int sketch_road = static_cast<int>(r) < city_map.sketch_roads ? static_cast<int>(r) : -1;
        out.roads.push_back({road.road_class, road.width, road.level, road.region, run_bridge, std::move(run), sketch_road, road.osm_tags});
        run.clear();
      };
      for (const geom::PolylinePiece& piece : pieces_of[road.first_tag + k]) {
        if (piece.from == piece.to) continue;  // shorter than a double's step: rounded away
        const geom::SegmentKey key = geom::segment_key(piece.from, piece.to);
        if (const auto at = written.find(key); at != written.end()) {
          flush();
          if (covering < 0) covering = at->second;
          continue;
        }
        bool bridge = city_map.labels[piece.left_label].cover == Cover::Water &&
                      city_map.labels[piece.right_label].cover == Cover::Water;
        if (!run.empty() && (bridge != run_bridge || !(run.back() == piece.from))) flush();
        if (run.empty()) run.push_back(piece.from), run_bridge = bridge;
        run.push_back(piece.to);
        written.emplace(key, static_cast<int>(out.roads.size()));  // the index the run gets at its flush
      }
      flush();
    }
    if (first_line[r][0] < 0 && first_line[r][1] < 0 && covering >= 0) first_line[r][out.roads[covering].bridge] = covering;
  }
  return first_line;
}

// A road face's road area: carriageways and sidewalks per road (groups 4r + 2 sidewalk +
// bridge), then each junction (4 roads + 2j + bridge); -1 for other faces.
int road_area_group(const CityMap& city_map, const FaceLabel& l) {
  if (!l.road_surface()) return -1;
  const int roads = static_cast<int>(city_map.roads.size());
  if (l.surface == RoadSurface::Junction) return 4 * roads + 2 * l.junction + l.bridge;
  return 4 * l.road + 2 * (l.surface == RoadSurface::Sidewalk) + l.bridge;
}

// The road areas' faces dissolved by road, surface and bridge (road_area_group).
Dissolved dissolve_road_areas(const CityMap& city_map) {
  const int roads = static_cast<int>(city_map.roads.size());
  const int junctions = static_cast<int>(city_map.junction_roads.size());
  return dissolved(city_map, 4 * roads + 2 * junctions, [&](const FaceLabel& l) { return road_area_group(city_map, l); });
}

// Road areas from dissolve_road_areas.
void extract_road_areas(const CityMap& city_map, Dissolved areas, const std::function<int(int, bool)>& road_id,
                        Ground& out) {
  const int roads = static_cast<int>(city_map.roads.size());
  add_each(std::move(areas), [&](int g, geom::Polygon p) {
    const bool junction = g >= 4 * roads, bridge = g % 2 == 1;
    const int road = junction ? city_map.junction_roads[(g - 4 * roads) / 2] : g / 4;
    const RoadSurface surface = junction ? RoadSurface::Junction : g % 4 >= 2 ? RoadSurface::Sidewalk : RoadSurface::Carriageway;
    out.road_areas.push_back({road_id(road, bridge), bridge, surface, std::move(p)});
  });
}

// Blocks from the final map, so they share every vertex with the other layers (lots add
// vertices on block edges). Rounding can pinch a block in two: its first polygon keeps
// the block's id, the others take ids after the last block's, and lots name the polygon
// they lie in. Returns each block's pieces, as indices into out.blocks.
// `dissolved_blocks`: the faces dissolved by block.
std::vector<std::vector<std::size_t>> extract_blocks(Dissolved dissolved_blocks, const std::vector<Block>& blocks,
                                                     const std::function<int(int, bool)>& road_id, Ground& out) {
  std::vector<std::vector<geom::Polygon>> block_polygons(blocks.size());
  add_each(std::move(dissolved_blocks), [&](int g, geom::Polygon p) { block_polygons[g].push_back(std::move(p)); });
  std::vector<std::vector<std::size_t>> pieces(blocks.size());
  int next_id = static_cast<int>(blocks.size());
  const CancelCheck cancel;
  for (std::size_t g = 0; g < blocks.size(); ++g) {
    cancel.check();
    for (std::size_t k = 0; k < block_polygons[g].size(); ++k) {
      const Block& b = blocks[g];
      BlockArea area{k > 0 ? next_id++ : static_cast<int>(g), static_cast<int>(g), b.zone, b.green, {},
                     std::move(block_polygons[g][k])};
      for (int r : b.roads) area.roads.push_back(road_id(r, false));
      pieces[g].push_back(out.blocks.size());
      out.blocks.push_back(std::move(area));
    }
  }
  return pieces;
}

// The block piece a lot lies in: the smallest polygon around it, since a piece can lie
// in another's hole.
int block_piece_of(const Lot& lot, const std::vector<std::size_t>& pieces, const Ground& ground) {
  if (pieces.size() < 2) return lot.block;
  int best = lot.block;
  double best_area = INFINITY;
  for (std::size_t i : pieces) {
    const BlockArea& b = ground.blocks[i];
    const double area = geom::area(b.polygon);
    if (area < best_area && geom::ring_within(lot.polygon.outer, b.polygon.outer)) best = b.id, best_area = area;
  }
  return best;
}

ordered_json id_or_null(int id) { return id >= 0 ? ordered_json(id) : ordered_json(nullptr); }

// Each feature's id in the outputs (stable_ids.h), from what its layer writes of it but ids
// and what it names; a road's region's from the region (CityMap::region_hashes).
void give_stable_ids(const CityMap& city_map, Ground& out) {
  enum Kind : std::uint64_t { kZone = 1, kWater, kRoad, kRoadArea, kBlock, kLot };
  auto give = [](auto& features, auto hash, auto set) {
    std::vector<std::uint64_t> hashes;
    hashes.reserve(features.size());
    for (const auto& f : features) hashes.push_back(hash(f));
    const std::vector<int> ids = stable_ids(hashes);
    for (std::size_t i = 0; i < features.size(); ++i) set(features[i], ids[i]);
  };
  give(out.zones, [](const ZoneArea& z) { return ContentHash(kZone).add(static_cast<int>(z.type)).add(z.polygon).value(); },
       [](ZoneArea& z, int id) { z.stable_id = id; });
  out.water_stable_ids.assign(out.water.size(), -1);
  give(out.water, [](const geom::Polygon& w) { return ContentHash(kWater).add(w).value(); },
       [&](const geom::Polygon& w, int id) { out.water_stable_ids[&w - out.water.data()] = id; });
  const std::vector<int> regions = stable_ids(city_map.region_hashes);
  give(out.roads,
       [](const RoadLine& r) {
         ContentHash h(kRoad);
         h.add(static_cast<int>(r.road_class)).add(r.width).add(r.level).add(static_cast<int>(r.bridge)).add(r.line);
         for (const auto& [key, value] : r.osm_tags) h.add(std::string_view(key)).add(std::string_view(value));
         return h.value();
       },
       [&](RoadLine& r, int id) {
         r.stable_id = id;
         r.region_stable_id = r.region >= 0 ? regions.at(r.region) : -1;
       });
  give(out.road_areas,
       [](const RoadArea& a) {
         return ContentHash(kRoadArea).add(static_cast<int>(a.surface)).add(static_cast<int>(a.bridge)).add(a.polygon).value();
       },
       [](RoadArea& a, int id) { a.stable_id = id; });
  give(out.blocks,
       [](const BlockArea& b) {
         return ContentHash(kBlock).add(static_cast<int>(b.zone)).add(static_cast<int>(b.green)).add(b.polygon).value();
       },
       [](BlockArea& b, int id) { b.stable_id = id; });
  give(out.lots, [](const LotArea& l) { return ContentHash(kLot).add(static_cast<int>(l.zone)).add(l.polygon).value(); },
       [](LotArea& l, int id) { l.stable_id = id; });
}

}  // namespace

int give_covered_roads_their_carriageway(CityMap& city_map) {
  const int roads = static_cast<int>(city_map.roads.size());
  // Each road's area as the map's faces give it; taken marks a face given to a covered road
  // until its owner's loss is known (the block field, -1 on every road face, holds -2 -
  // the face's label before).
  auto taken = [](const FaceLabel& l) { return l.block <= -2; };
  auto road_areas = [&] {
    const std::vector<int> road_of_label =
        city_map.per_label([](const FaceLabel& l) { return l.road_surface() ? l.road : -1; });
    std::vector<int> groups;
    const std::vector<geom::Cell> cells =
        city_map.map.cells(road_of_label, std::vector<int>(road_of_label.size(), 0), &groups);
    std::vector<double> area(roads, 0);
    for (std::size_t c = 0; c < cells.size(); ++c) area[groups[c]] += cells[c].area();
    return area;
  };
  std::vector<char> covered(roads, 0);
  {
    const std::vector<double> area = road_areas();
    for (int r = 0; r < roads; ++r) covered[r] = area[r] == 0 && !city_map.roads[r].lines.empty();
  }
  if (std::none_of(covered.begin(), covered.end(), [](char c) { return c != 0; })) return 0;
  const std::vector<FaceLabel> before = city_map.labels;
  city_map.map.relabel_faces(0, [&](const geom::Windings& windings, int label) {
    FaceLabel l = city_map.labels[label];  // a copy: label_index may grow the labels
    if (!l.road_surface() || covered[l.road]) return label;
    for (auto [counter, winding] : windings)
      if (const int r = city_map.road_of_counter(counter); winding != 0 && r >= 0 && covered[r]) {
        l.road = r, l.surface = RoadSurface::Carriageway, l.junction = -1, l.block = -2 - label;
        return city_map.label_index(l);
      }
    return label;
  });
  // An owner left with less than a sliver's area takes back what it gave.
  const std::vector<double> kept = road_areas();
  std::set<int> took;
  city_map.map.relabel_faces(0, [&](const geom::Windings&, int label) {
    const FaceLabel l = city_map.labels[label];
    if (!taken(l)) return label;
    const int was = -2 - l.block;
    if (kept[before[was].road] < kSliverRoadArea) return was;
    FaceLabel given = before[was];
    given.road = l.road, given.surface = RoadSurface::Carriageway, given.junction = -1;
    took.insert(l.road);
    return city_map.label_index(given);
  });
  return static_cast<int>(took.size());
}

int merge_sliver_road_areas(CityMap& city_map) {
  const int roads = static_cast<int>(city_map.roads.size());
  const std::vector<int> group = city_map.per_label([&](const FaceLabel& l) { return road_area_group(city_map, l); });
  // An edge's kind: the road area across it, 1 + its group (0: no road area).
  std::vector<int> kind(group.size());
  for (std::size_t l = 0; l < group.size(); ++l) kind[l] = group[l] + 1;
  std::vector<int> groups, components;
  const std::vector<geom::Cell> cells = city_map.map.cells(group, kind, &groups, &components);
  const int count = components.empty() ? 0 : components.back() + 1;
  std::vector<double> area(count, 0);
  std::vector<int> group_of(count, -1);
  for (std::size_t c = 0; c < cells.size(); ++c) area[components[c]] += cells[c].area(), group_of[components[c]] = groups[c];
  auto road_of = [&](int g) { return g >= 4 * roads ? city_map.junction_roads[(g - 4 * roads) / 2] : g / 4; };
  std::map<int, int> real_areas;  // per road, its areas that are no sliver
  for (int c = 0; c < count; ++c)
    if (area[c] >= kSliverRoadArea) ++real_areas[road_of(group_of[c])];
  // Each sliver goes to the road area it shares the longest boundary with. (One that no
  // road area touches along an edge stays: the faces beside it are of other zones or
  // outside the city, and taking their label would move a zone's edge.)
  std::vector<int> target(count, 0);  // an edge kind; 0: stays
  std::vector<double> shared(count, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const int component = components[c];
    if (area[component] >= kSliverRoadArea) continue;
    for (int k : cells[c].edge_kinds()) {
      if (k == 0 || k == group_of[component] + 1) continue;
      double length = 0;
      for (const auto& [a, b] : cells[c].edges_of_kind(k)) length += std::hypot(b.x - a.x, b.y - a.y);
      if (length > shared[component]) shared[component] = length, target[component] = k;
    }
  }
  // A road keeps a surface: the sliver that is all of it takes in instead the road area
  // beside it (a piece of a road that keeps another), else stays.
  // Whether a road keeps an area that is no sliver (asked without adding it to the map).
  auto keeps = [&](int road, int at_least) {
    const auto it = real_areas.find(road);
    return it != real_areas.end() && it->second >= at_least;
  };
  std::vector<char> without(roads, 0);  // roads whose areas are all slivers, as they came
  for (int r = 0; r < roads; ++r) without[r] = !keeps(r, 1);
  // The road areas beside a sliver, found by their boxes: cells that share an edge share its
  // vertices, which round alike, so their boxes meet.
  // Indexed when the first such sliver asks: most maps have none, and indexing every road
  // area's cell took a quarter of this function.
  std::optional<geom::BoxIndex> near;
  auto cells_near = [&](const geom::Box& b) {
    if (!near) {
      near.emplace(10);
      for (std::size_t n = 0; n < cells.size(); ++n) near->add(static_cast<int>(n), cells[n].bounds());
    }
    return near->meeting(b);
  };
  std::vector<geom::Box> box(count, geom::Box::none());
  for (std::size_t n = 0; n < cells.size(); ++n) box[components[n]].add(cells[n].bounds());
  std::vector<int> taken_by(count, -1);  // a road area given to a sliver's group
  for (int c = 0; c < count; ++c) {
    if (area[c] >= kSliverRoadArea || !without[road_of(group_of[c])] || keeps(road_of(group_of[c]), 1)) continue;
    const int beside = target[c] - 1;
    target[c] = 0;
    if (beside < 0) continue;
    for (const int n : cells_near(box[c])) {
      const int other = components[n];
      if (group_of[other] != beside || area[other] < kSliverRoadArea || taken_by[other] >= 0 ||
          !keeps(road_of(beside), 2) || cells[n].edges_of_kind(group_of[c] + 1).empty())
        continue;
      taken_by[other] = group_of[c];
      --real_areas[road_of(beside)];
      ++real_areas[road_of(group_of[c])];
      break;
    }
  }
  int merged = 0;
  for (int c = 0; c < count; ++c) merged += target[c] != 0 || taken_by[c] >= 0;
  if (merged == 0) return 0;
  auto in_group = [&](FaceLabel l, int g) {
    const bool junction = g >= 4 * roads;
    l.road = road_of(g);
    l.bridge = g % 2 == 1;
    l.surface = junction ? RoadSurface::Junction : g % 4 >= 2 ? RoadSurface::Sidewalk : RoadSurface::Carriageway;
    l.junction = junction ? (g - 4 * roads) / 2 : -1;
    if (!l.bridge) l.cover = Cover::Road;  // a bridge's sliver over water joins the land's road
    return city_map.label_index(l);
  };
  city_map.map.relabel_components(group, [&](int c, int label) {
    if (taken_by[c] >= 0) return in_group(city_map.labels[label], taken_by[c]);
    if (target[c] > 0) return in_group(city_map.labels[label], target[c] - 1);
    return label;
  });
  return merged;
}

Ground extract_ground(const CityMap& city_map, const std::vector<Block>& blocks, const std::vector<Lot>& lots,
                      const std::vector<ZoneFeature>& zones) {
  Ground out;
  // The centre lines at once with the dissolves (which take turns at the map's vertices'
  // roundings, PlanarMap::dissolve), each into its own part of `out` or its own polygons,
  // put together after in one order: the same ground whatever the thread count.
  Dissolved road_areas, block_polygons;
  std::vector<std::array<int, 2>> first_line;
  invoke_cancellable(
      [&] {
        extract_zones_and_water(city_map, zones, out);
        road_areas = dissolve_road_areas(city_map);
        block_polygons = dissolved(city_map, static_cast<int>(blocks.size()), [](const FaceLabel& l) { return l.block; });
      },
      [&] { first_line = extract_centre_lines(city_map, out); });
  const std::function<int(int, bool)> road_id = [&](int r, bool bridge) {
    const auto& f = first_line[r];
    return f[bridge] >= 0 ? f[bridge] : f[!bridge];
  };
  extract_road_areas(city_map, std::move(road_areas), road_id, out);
  std::set<int> named;
  for (const RoadArea& a : out.road_areas) named.insert(a.road);
  for (const auto& f : first_line)
    if ((f[0] >= 0 || f[1] >= 0) && !named.count(f[0]) && !named.count(f[1])) out.roads_without_area.push_back(f[0] >= 0 ? f[0] : f[1]);
  const std::vector<std::vector<std::size_t>> pieces = extract_blocks(std::move(block_polygons), blocks, road_id, out);
  // Lots as they ended up in the map; a lot's id is its index, which buildings name.
  const CancelCheck cancel;
  for (const Lot& lot : lots) {
    cancel.check();
    out.lots.push_back({block_piece_of(lot, pieces[lot.block], out), lot.zone, lot.polygon});
  }
  give_stable_ids(city_map, out);
  return out;
}

ordered_json mapped_attributes(const Building& b) {
  ordered_json out{{"mapped", true}, {"osm_id", b.osm_id.empty() ? ordered_json(nullptr) : ordered_json(b.osm_id)},
                   {"building", b.building_tag}};
  if (!b.source_id.first.empty()) out[b.source_id.first] = b.source_id.second;
  return out;
}

ordered_json road_attributes(const RoadLine& road) {
  ordered_json out = ordered_json::object();
  for (const auto& [key, value] : road.osm_tags) out[key == "bridge" ? "osm_bridge" : key] = value;
  return out;
}

CityLayers layers_of(const Ground& ground, const std::vector<Building>& buildings,
                     const std::vector<ModelInstance>& models, const ModelLibrary* library) {
  CityLayers out;
  // Every feature writes its stable id, and names others by theirs. Every polygon feature
  // passes here: the place to stop a cancelled build.
  auto add = [](Layer& layer, int id, ordered_json props, const geom::Polygon& p) {
    CancelCheck().check();
    ordered_json full{{"id", id}};
    full.update(props);
    layer.features.push_back({std::move(full), p, {}});
  };
  auto road_id = [&](int r) { return r >= 0 ? ordered_json(ground.roads[r].stable_id) : ordered_json(nullptr); };
  std::unordered_map<int, int> block_id;  // a block piece's id in the program -> its stable id
  for (const BlockArea& b : ground.blocks) block_id.emplace(b.id, b.stable_id);
  for (const ZoneArea& z : ground.zones) add(out.zones, z.stable_id, {{"zone", name(z.type)}}, z.polygon);
  for (std::size_t w = 0; w < ground.water.size(); ++w)
    add(out.water, ground.water_stable_ids[w], ordered_json::object(), ground.water[w]);
  for (const RoadLine& r : ground.roads) {
    CancelCheck().check();
    ordered_json props{{"id", r.stable_id}, {"class", name(r.road_class)},
                       {"width", r.width},  {"level", id_or_null(r.level)},
                       {"region", id_or_null(r.region_stable_id)}, {"bridge", r.bridge}};
    props.update(road_attributes(r));
    out.roads.features.push_back({std::move(props), {}, r.line});
  }
  for (const RoadArea& a : ground.road_areas)
    add(out.road_areas, a.stable_id, {{"road", road_id(a.road)}, {"bridge", a.bridge}, {"surface", name(a.surface)}},
        a.polygon);
  for (const BlockArea& b : ground.blocks) {
    ordered_json roads = ordered_json::array();
    for (int r : b.roads) roads.push_back(road_id(r));
    add(out.blocks, b.stable_id, {{"zone", name(b.zone)}, {"green", b.green}, {"roads", roads}}, b.polygon);
  }
  for (const LotArea& lot : ground.lots)
    add(out.lots, lot.stable_id, {{"block", block_id.at(lot.block)}, {"zone", name(lot.zone)}}, lot.polygon);
  auto lot_id = [&](int lot) { return lot >= 0 ? ordered_json(ground.lots[lot].stable_id) : ordered_json(nullptr); };
  for_each_by_id(
      buildings, models,
      [&](const Building& b) {
        ordered_json props{{"lot", lot_id(b.lot)}, {"zone", name(b.zone)}, {"height", b.height}, {"roof", b.roof},
                           {"model", nullptr}, {"kind", "building"}};
        if (b.mapped >= 0) props.update(mapped_attributes(b));
        add(out.buildings, b.stable_id, std::move(props), b.polygon);
      },
      [&](const ModelInstance& m) {
        ordered_json props{{"lot", lot_id(m.lot)}, {"zone", name(m.zone)}, {"height", m.height}, {"roof", "model"},
                           {"model", library->models[m.placed.model].name}, {"kind", name(m.kind)}};
        if (!m.slabs.empty()) props["floor"] = m.floor, props["slabs"] = slabs_json(m.slabs);
        add(out.buildings, m.stable_id, std::move(props), m.polygon);
      });
  return out;
}

CityLayers extract_layers(const CityMap& city_map, const std::vector<Block>& blocks, const std::vector<Lot>& lots,
                          const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                          const std::vector<ZoneFeature>& zones, const ModelLibrary* library) {
  return layers_of(extract_ground(city_map, blocks, lots, zones), buildings, models, library);
}

}  // namespace exacity
