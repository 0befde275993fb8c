#include "generate/city_report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>

#include "generate/errors.h"
#include "generate/export/statistics.h"
#include "generate/placement/building_settings.h"
#include "generate/regenerate.h"
#include "generate/sketch/like_place.h"
#include "generate/version.h"
#include "geom/measure.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// report.json's road_network: regions and levels grown, roads and segments per class,
// junctions per degree (1: a dead end at a region's edge), how the sketch's roads met.
ordered_json road_network_report(const RoadNetwork& network, const DrawnFeatures& sketch) {
  ordered_json segments = ordered_json::object(), roads_by_class = ordered_json::object();
  for (const MapRoad& r : network.map.roads) {
    std::string c(name(r.road_class));
    roads_by_class[c] = roads_by_class.value(c, 0) + 1;
    for (const auto& line : r.lines) segments[c] = segments.value(c, 0) + static_cast<int>(line.size()) - 1;
  }
  ordered_json junctions = ordered_json::object();
  for (auto [degree, count] : network.map.map.polyline_degrees())
    if (degree != 2) junctions[std::to_string(degree)] = count;
  ordered_json dead_ends = ordered_json::array();
  for (const DeadEnd& d : sketch.dead_ends) dead_ends.push_back({{"feature", d.feature}, {"at", {d.at.x, d.at.y}}});
  return {{"regions", network.stats.regions},
          {"levels", network.stats.levels},
          {"roads", roads_by_class},
          {"segments", segments},
          {"junctions_by_degree", junctions},
          {"cells_without_access", network.stats.cells_without_access},
          {"links", network.stats.links},
          {"dropped_roads", network.stats.dropped_roads},
          {"sketch_junctions", {{"mitred", network.map.mitred_junctions}, {"discs", network.map.disc_junctions}}},
          {"joined_ends", sketch.joined_ends},
          {"dead_ends", dead_ends}};
}

// Whether a drawn zone holds p as the sketch reads it: its outer ring winds around p and no
// hole does.
bool zone_holds(const ZoneFeature& zone, geom::Vec2 p) {
  for (const geom::Polygon& polygon : zone.polygons) {
    if (geom::winding_number(polygon.outer, p) == 0) continue;
    if (std::none_of(polygon.holes.begin(), polygon.holes.end(), [&](const geom::Ring& h) { return geom::winding_number(h, p) != 0; }))
      return true;
  }
  return false;
}

// The drawn zone a cell lies in (the later of two zones drawn over each other), or -1.
int zone_feature_of(const geom::Cell& cell, const DrawnFeatures& sketch) {
  const std::optional<geom::Vec2> p = cell.point_inside_near(cell.centroid());
  if (!p) return -1;
  for (int z = static_cast<int>(sketch.zones.size()) - 1; z >= 0; --z)
    if (zone_holds(sketch.zones[z], *p)) return z;
  return -1;
}

// report.json's empty_zones: each drawn residential, commercial or industrial zone that got
// no lot, and why, so a zone never stays empty without a word.
ordered_json empty_zones_report(const City& city) {
  const DrawnFeatures& sketch = city.drawn;
  std::vector<char> has_land(sketch.zones.size(), 0), has_lot(sketch.zones.size(), 0), has_street(sketch.zones.size(), 0);
  for (const FaceLabel& label : city.network.map.labels)
    if (label.cover == Cover::Zone && label.zone >= 0) has_land[label.zone] = 1;
  for (const Lot& lot : city.lots)
    if (const int z = zone_feature_of(lot.cell, sketch); z >= 0) has_lot[z] = 1;
  for (const Block& block : city.blocks)
    if (!block.green && !block.roads.empty())
      if (const int z = zone_feature_of(block.cell, sketch); z >= 0) has_street[z] = 1;
  ordered_json empty = ordered_json::array();
  for (std::size_t z = 0; z < sketch.zones.size(); ++z) {
    const ZoneFeature& zone = sketch.zones[z];
    if (has_lot[z] || !grows_roads(zone.type)) continue;
    ordered_json entry{{"feature", zone.index},
                       {"zone", name(zone.type)},
                       {"why", !has_land[z]    ? "no land of its own: zones drawn later, water or roads cover all of it"
                               : has_street[z] ? "its blocks along streets are too small or narrow for a lot"
                                               : "no street reaches its land: draw a road to it, or lay it out by growth"}};
    if (!zone.grid_cell.empty()) entry["grid_cell"] = zone.grid_cell;  // where a grid map's region begins
    if (!zone.source.empty()) entry["source"] = zone.source;  // a feature read from another format
    empty.push_back(std::move(entry));
  }
  return empty;
}

// report.json's roads_without_area: each road with a centre line but no road area, so no
// road is left out of road_areas and CityJSON without a word.
ordered_json roads_without_area_report(const City& city) {
  ordered_json out = ordered_json::array();
  for (int id : city.ground.roads_without_area) {
    ordered_json entry{{"road", city.ground.roads[id].stable_id},
                       {"why", "its carriageway lies wholly on other roads' surfaces, which have too little to spare "
                               "for it, or rounding left it none"}};
    // Its position in OUT/sketch.geojson's features, for a road drawn in the sketch.
    if (const int road = city.ground.roads[id].sketch_road; road >= 0) entry["feature"] = city.drawn.roads[road].index;
    out.push_back(std::move(entry));
  }
  return out;
}

// report.json's placement_fallbacks: zone types whose lots ask for grid filling but whose
// lots are built with extruded footprints in rows, as the library has no building for them.
ordered_json placement_fallbacks_report(const City& city) {
  ordered_json fallbacks = ordered_json::array();
  for (const auto& [zone, settings] : city.settings.zone_settings) {
    // The default placer falls back without a word: extruded footprints are what it asks for then.
    if (settings.buildings.placement->name() == placer_types().front().name || !grows_roads(zone)) continue;
    const ModelLibrary* library = city.model_library();
    if (library && !library->choices(zone, ModelKind::Building).empty()) continue;
    fallbacks.push_back({{"zone", name(zone)},
                         {"why", library && !library->file.empty() ? "the model library has no building for this zone type"
                                         : "the sketch names no model library (\"exacity\".models, or --models)"}});
  }
  return fallbacks;
}

// report.json's counts: features per layer, the map's size and the 3D exports'.
// The 3D exports' counts are placeholders here, in their place, for complete_report.
ordered_json counts_report(const City& city) {
  const CityLayers& layers = city.layers;
  const ordered_json& exact = city.exact_report;
  // The buildings layer holds every structure: buildings, and models of other kinds (trees).
  ordered_json by_kind = ordered_json::object();
  for (const VectorFeature& f : layers.buildings.features) {
    const std::string kind = f.properties.value("kind", std::string("building"));
    by_kind[kind] = by_kind.value(kind, 0) + 1;
  }
  return {{"zones", layers.zones.features.size()},
          {"water", layers.water.features.size()},
          {"roads", layers.roads.features.size()},
          {"road_areas", layers.road_areas.features.size()},
          {"blocks", exact.at("blocks")},
          {"green_spaces", exact.at("green_spaces")},
          {"lots", layers.lots.features.size()},
          {"buildings", layers.buildings.features.size()},
          {"buildings_by_kind", by_kind},
          {"clutter", city.clutter.items.size()},
          {"map", exact.at("map")},
          {"mesh", nullptr},
          {"gltf", nullptr}};
}

// report.json's clutter: what stands by kind, and the spots that found no place by kind and
// why, so no spot is dropped without a word (docs/design.md, Placement).
ordered_json clutter_report(const ClutterTally& tally) {
  ordered_json placed = ordered_json::object(), missed = ordered_json::array();
  for (const auto& [kind, n] : tally.placed) placed[kind] = n;
  for (const auto& [key, n] : tally.missed) missed.push_back({{"kind", key.first}, {"why", key.second}, {"spots", n}});
  return {{"placed", placed}, {"not_placed", missed}};
}

// report.json's mapped_buildings: what became of each building the sketch maps (kept,
// repaired, refused and why), the generated buildings beside them and the share of the
// built-up land (footprint area) each holds.
// The footprints of each built-up zone type, mapped and generated apart (docs/gis.md,
// Looking like the place): how many, their areas' median and 90th percentile, and two
// coverages. Over the land use: footprint area over the area the zone type's drawn zones
// cover. Over their lots: footprint area over the land of the lots mapped buildings stand
// on, and of the other lots, each lot's land its area and its share of its block's open
// middle (in proportion to the lots' areas), so the land generated on is measured as the
// land mapped is. A mapped building counts in the land use its centre lies in, as --like
// measures it.
ordered_json footprints_by_zone(const City& city) {
  struct Side {
    std::vector<double> areas;
    double land_m2 = 0;
  };
  std::map<ZoneType, std::array<Side, 2>> zones;  // [0] mapped, [1] generated
  for (const Building& b : city.buildings) {
    if (b.mapped < 0) {
      zones[b.zone][1].areas.push_back(geom::area(b.polygon));
    } else if (const std::optional<ZoneType> t = built_up_zone_at(city.drawn.zones, b.polygon.outer)) {
      zones[*t][0].areas.push_back(geom::area(b.polygon));
    }
  }
  for (const ModelInstance& m : city.models)
    if (m.kind == ModelKind::Building) zones[m.zone][1].areas.push_back(geom::area(m.polygon));
  std::vector<double> lots_in_block(city.blocks.size(), 0);
  for (const Lot& lot : city.lots)
    if (lot.block >= 0) lots_in_block[lot.block] += geom::area(lot.polygon);
  std::vector<double> generated_on(city.lots.size(), 0);  // generated footprint area per lot
  for (const Building& b : city.buildings)
    if (b.mapped < 0 && b.lot >= 0) generated_on[b.lot] += geom::area(b.polygon);
  for (const ModelInstance& m : city.models)
    if (m.kind == ModelKind::Building && m.lot >= 0) generated_on[m.lot] += geom::area(m.polygon);
  for (std::size_t i = 0; i < city.lots.size(); ++i) {
    const Lot& lot = city.lots[i];
    const double area = geom::area(lot.polygon);
    const double land = lot.block >= 0 && lots_in_block[lot.block] > 0
                            ? area * geom::area(city.blocks[lot.block].polygon) / lots_in_block[lot.block]
                            : area;
    // A lot mapped buildings stand on is the mapped ones' land, shared with the generated
    // ones built around them (lot_coverage) in proportion to their footprint areas on it.
    const bool held = i < city.held_lots.size() && city.held_lots[i];
    const double mapped = held ? city.held_m2[i] : 0;
    const double mapped_share = !held ? 0 : generated_on[i] > 0 ? mapped / (mapped + generated_on[i]) : 1;
    zones[lot.zone][0].land_m2 += land * mapped_share;
    zones[lot.zone][1].land_m2 += land * (1 - mapped_share);
  }
  std::map<ZoneType, double> land_use = land_by_zone(city.drawn.zones);
  ordered_json out = ordered_json::object();
  for (ZoneType t : {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial}) {
    if (!zones.count(t)) continue;
    ordered_json zone{{"land_use_m2", std::round(land_use[t])}};
    for (int k = 0; k < 2; ++k) {
      Side& side = zones[t][k];
      std::sort(side.areas.begin(), side.areas.end());
      double total = 0;
      for (double a : side.areas) total += a;
      auto at = [&](double q) {
        const std::size_t i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(side.areas.size())));
        return std::round(side.areas[std::max<std::size_t>(i, 1) - 1] * 10) / 10;
      };
      ordered_json figures{{"footprints", side.areas.size()}};
      if (!side.areas.empty()) figures["median_m2"] = at(0.5), figures["p90_m2"] = at(0.9);
      figures["footprint_m2"] = std::round(total);
      figures["coverage_of_land_use"] = land_use[t] > 0 ? std::round(total / land_use[t] * 1e4) / 1e4 : 0.0;
      figures["lots_land_m2"] = std::round(side.land_m2);
      figures["coverage_of_lots"] = side.land_m2 > 0 ? std::round(total / side.land_m2 * 1e4) / 1e4 : 0.0;
      zone[k == 0 ? "mapped" : "generated"] = figures;
    }
    out[std::string(name(t))] = zone;
  }
  return out;
}

ordered_json mapped_buildings_report(const City& city) {
  const MappedTally& t = city.mapped;
  double mapped_area = 0, generated_area = 0;
  int generated = 0;
  for (const Building& b : city.buildings) {
    if (b.mapped >= 0) {
      mapped_area += geom::area(b.polygon);
    } else {
      ++generated;
      generated_area += geom::area(b.polygon);
    }
  }
  for (const ModelInstance& m : city.models)
    if (m.kind == ModelKind::Building) ++generated, generated_area += geom::area(m.polygon);
  // Those the files' readers left out (a building way not closed) are refused too.
  std::map<std::string, int> refused_why = t.refused;
  for (const auto& [why, n] : city.drawn.buildings_left_out) refused_why[why] += n;
  int refused = 0;
  for (const auto& [why, n] : refused_why) refused += n;
  std::vector<std::string> named = city.drawn.buildings_left_out_named;
  named.insert(named.end(), t.named.begin(), t.named.end());
  const double built = mapped_area + generated_area;
  auto share = [&](double a) { return built > 0 ? std::round(a / built * 1e4) / 1e4 : 0.0; };
  std::map<std::string, int> parts_refused_why = t.parts_refused;
  for (const auto& [why, n] : city.drawn.building_parts_left_out) parts_refused_why[why] += n;
  int parts_refused = 0;
  for (const auto& [why, n] : parts_refused_why) parts_refused += n;
  return {{"in_sketch", city.drawn.buildings.size()},
          {"kept", t.kept},
          {"repaired", t.repaired},
          {"refused", refused},
          {"refused_why", refused_why},
          {"repairs", t.repairs},
          {"named", named},
          {"heights_from", t.heights},
          {"roofs", t.roofs},
          {"roofs_made_flat", t.made_flat},
          {"building_parts",
           {{"in_sketch", city.drawn.building_parts.size()},
            {"kept", t.parts},
            {"refused", parts_refused},
            {"refused_why", parts_refused_why},
            {"roofs", t.part_roofs}}},
          {"roads_narrowed", t.roads_narrowed},
          {"roads_narrowed_named", t.narrowed},
          {"lots_not_built_again", t.held_lots - t.held_lots_built_on},
          {"lots_built_around_them", t.held_lots_built_on},
          {"generated", generated},
          {"built_up_m2", {{"mapped", std::round(mapped_area * 100) / 100}, {"generated", std::round(generated_area * 100) / 100}}},
          {"built_up_share", {{"mapped", share(mapped_area)}, {"generated", share(generated_area)}}}};
}

// report.json's osm: what the readers of OpenStreetMap's files (or GIS exports of them)
// took, left out by why, and mended, so no feature of theirs goes without a count; null for
// a sketch of none.
ordered_json osm_report(const Sketch& sketch) {
  if (sketch.osm_counts.empty() && sketch.osm_taken.empty()) return nullptr;
  ordered_json files = ordered_json::array();
  for (const Sketch::OsmCounts& file : sketch.osm_counts) {
    int left_out = 0;
    for (const auto& [why, n] : file.left_out) left_out += n;
    files.push_back({{"file", file.file}, {"left_out", left_out}, {"left_out_why", file.left_out}, {"repaired", file.repaired}});
  }
  return {{"taken", sketch.osm_taken}, {"files", files}};
}

// report.json's sketch_roads: what became of the roads the sketch draws (an extract's taken
// highways): every one is in the map; those narrowed to clear a mapped building, and those
// whose surface other roads cover (no road area: roads_without_area names them).
ordered_json sketch_roads_report(const City& city) {
  int without_area = 0;
  for (int id : city.ground.roads_without_area) without_area += city.ground.roads[id].sketch_road >= 0;
  const int drawn = static_cast<int>(city.drawn.roads.size());
  return {{"in_sketch", drawn},
          {"with_road_area", drawn - without_area},
          {"without_road_area", without_area},
          {"narrowed_for_mapped_buildings", city.mapped.roads_narrowed},
          {"generated", city.exact_report.at("generated_roads")}};
}

// Per zone type, where its blocks' land went (LotLand): m² and the share of the blocks' land.
ordered_json lot_land_report(const std::map<ZoneType, LotLand>& land) {
  ordered_json out = ordered_json::object();
  for (const auto& [zone, l] : land) {
    auto share = [&](double m2) { return l.blocks_m2 > 0 ? std::round(m2 / l.blocks_m2 * 1e4) / 1e4 : 0.0; };
    auto figures = [&](const LandShare& s) {
      return ordered_json{{"count", s.count}, {"area_m2", std::round(s.area_m2)}, {"share", share(s.area_m2)}};
    };
    ordered_json refused = ordered_json::object();
    for (const auto& [why, s] : l.refused) refused[why] = figures(s);
    out[std::string(name(zone))] = {{"blocks_m2", std::round(l.blocks_m2)},
                                    {"lots", figures(l.lots)},
                                    {"pieces_joined_to_a_lot", figures(l.joined)},
                                    {"refused", refused},
                                    {"no_lot", {{"area_m2", std::round(l.open_m2)}, {"share", share(l.open_m2)}}}};
  }
  return out;
}

}  // namespace

ordered_json exact_work_report(const City& city) {
  int green = 0;
  for (const Block& b : city.blocks) green += b.green;
  const auto counts = city.network.map.map.counts();
  return {{"road_network", road_network_report(city.network, city.drawn)},
          {"generated_roads", static_cast<int>(city.network.map.roads.size()) - city.network.map.sketch_roads},
          {"blocks", city.blocks.size() - green},
          {"green_spaces", green},
          {"map", {{"vertices", counts.vertices}, {"edges", counts.edges}, {"faces", counts.faces}}},
          {"empty_zones", empty_zones_report(city)},
          {"footprints_by_zone", footprints_by_zone(city)}};
}

ordered_json city_report(const Sketch& sketch, const City& city, const std::vector<std::string>& vector_formats,
                         bool city_osm) {
  const CitySettings& settings = city.settings;
  ordered_json report{
      {"generator", "exacity"},
      {"version", kVersion},
      {"kernel", geom::kernel_name()},
      {"sketch", settings.path.filename().string()},
      // Where the sketch's relative paths (heightmap, models) resolve, for `exacity render`.
      {"sketch_path", fs::absolute(settings.path).lexically_normal().string()},
      {"seed", settings.seed},
      {"counts", counts_report(city)},
      {"exports",
       {{"vector_formats", vector_formats.empty() ? std::vector<std::string>{"geojson"} : vector_formats},
        {"city_osm", city_osm ? "city.osm" : "not written: the sketch has no CRS (EPSG) to place it on Earth"}}},
      {"road_network", city.exact_report.at("road_network")},
      {"sketch_roads", sketch_roads_report(city)},
      {"unbuilt_lots", {{"merged", city.unbuilt_lots.merged}, {"left_open", city.unbuilt_lots.left_open},
                        {"left_open_m2", std::round(city.unbuilt_lots.left_open_m2)}}},
      {"lot_land", lot_land_report(city.lot_land)},
      {"empty_zones", city.exact_report.at("empty_zones")},
      {"roads_without_area", roads_without_area_report(city)},
      {"placement_fallbacks", placement_fallbacks_report(city)},
      {"clutter", clutter_report(city.clutter.tally)},
      {"statistics", city_statistics(city.layers, &settings, &city.drawn)},
      {"footprints_by_zone", city.exact_report.at("footprints_by_zone")},
      {"validation", nullptr},  // these two by complete_report
      {"timings_s", nullptr},
  };
  if (!city.drawn.buildings.empty() || !city.drawn.buildings_left_out.empty()) report["mapped_buildings"] = mapped_buildings_report(city);
  if (ordered_json osm = osm_report(sketch); !osm.is_null()) report["osm"] = std::move(osm);
  if (const LandUseTally& l = city.drawn.land_use; l.closed_along_bounds > 0 || l.infer_zones) {
    report["land_use"] = {{"closed_along_bounds", l.closed_along_bounds}};
    if (l.infer_zones)
      report["land_use"]["infer_zones"] = {{"street_faces", l.street_faces}, {"faces_with_land_use", l.faces_with_land_use},
                                          {"inferred", l.inferred}, {"left_open", l.left_open}};
  }
  return report;
}

void complete_report(ordered_json& report, const City& city, const WrittenCity& written, const ordered_json& timings) {
  ordered_json& counts = report["counts"];
  if (written.three_d) {
    const auto& [mesh, gltf] = *written.three_d;
    counts["mesh"] = {{"vertices", mesh.vertices}, {"faces", mesh.faces}};
    counts["gltf"] = {{"meshes", gltf.meshes}, {"instances", gltf.instances}, {"triangles", gltf.triangles}};
  } else {
    counts.erase("mesh"), counts.erase("gltf");
  }
  report_validation(report, written);
  report["timings_s"] = timings;
  // A generation with a cache (exacity serve's) says what it reused of the one before, the 3D export's meshes too.
  if (city.regions) report["reused"] = reuse_report(*city.regions);
}

void report_validation(ordered_json& report, const WrittenCity& written) {
  if (written.validation)
    report["validation"] = {{"ok", written.validation->ok()},
                            {"problems", written.validation->problems},
                            {"widest_sliver_m", written.validation->widest_sliver}};
  else if (written.validation_later)
    report["validation"] = {{"under_way", true}};
  else
    report["validation"] = {{"skipped", std::string("this build's kernel (") + geom::kernel_name() +
                                            ") cannot check its own output: run the exact build's exacity validate"}};
}

void write_report(const ordered_json& report, const fs::path& dir) {
  const fs::path aside = dir / ".report.json.partial";
  bool written = false;
  {
    std::ofstream out(aside, std::ios::binary);
    out << report.dump(2) << "\n";
    written = static_cast<bool>(out.flush());
  }
  if (!written) {
    std::error_code ignored;
    fs::remove(aside, ignored);  // nothing half-written left in the folder
    throw UserError((dir / "report.json").string() + ": write failed (disk full?)");
  }
  fs::rename(aside, dir / "report.json");
}

}  // namespace exacity
