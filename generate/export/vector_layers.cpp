#include "generate/export/vector_layers.h"

#include <array>
#include <cmath>

#include "geom/measure.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using nlohmann::ordered_json;

// Dissolves faces into polygons: group_of(label) picks each face's group (-1: none);
// add(group, polygon) receives them in a stable order.
template <typename GroupOf, typename Add>
void dissolve(const CityMap& zm, int group_count, GroupOf group_of, Add add) {
  std::vector<int> groups;
  for (const FaceLabel& l : zm.labels) groups.push_back(group_of(l));
  auto polygons = zm.map.dissolve(groups, group_count);
  for (int g = 0; g < group_count; ++g)
    for (geom::Dissolved& d : polygons[g]) add(g, std::move(d.polygon));
}

void add_polygon(Layer& layer, const ordered_json& props, geom::Polygon p) {
  ordered_json full{{"id", static_cast<int>(layer.features.size())}};
  if (props.is_object()) full.update(props);
  layer.features.push_back({std::move(full), std::move(p), {}});
}

ordered_json or_null(int v) { return v >= 0 ? ordered_json(v) : ordered_json(nullptr); }

}  // namespace

CityLayers read_layers(const std::filesystem::path& vector_dir, std::vector<std::string>& problems) {
  CityLayers layers;
  for (Layer* l : {&layers.zones, &layers.water, &layers.roads, &layers.road_areas, &layers.blocks, &layers.lots,
                   &layers.buildings})
    *l = read_geojson(vector_dir / (l->name + ".geojson"), problems);
  return layers;
}

CityLayers extract_layers(const CityMap& zm, const std::vector<Block>& blocks, const std::vector<Lot>& lots,
                          const std::vector<Building>& buildings, const Sketch& sketch, const ModelLibrary* library) {
  CityLayers out;
  const int zone_types = static_cast<int>(ZoneType::Water);  // water has its own layer
  dissolve(zm, zone_types,
           [&](const FaceLabel& l) { return l.cover == Cover::Zone ? static_cast<int>(sketch.zones[l.zone].type) : -1; },
           [&](int g, geom::Polygon p) {
             add_polygon(out.zones, {{"zone", name(static_cast<ZoneType>(g))}}, std::move(p));
           });
  dissolve(zm, 1, [](const FaceLabel& l) { return l.cover == Cover::Water ? 0 : -1; },
           [&](int, geom::Polygon p) { add_polygon(out.water, {}, std::move(p)); });

  const int roads = static_cast<int>(zm.roads.size());
  // Centre lines with every junction as a vertex, cut where they go on or off a bridge.
  // A road's first centre-line feature on land and on a bridge: what its areas and the
  // blocks along it name.
  std::vector<std::array<int, 2>> first_feature(zm.roads.size(), {-1, -1});
  auto pieces_of = zm.map.polyline_pieces();
  for (int r = 0; r < roads; ++r) {
    const MapRoad& road = zm.roads[r];
    for (int k = 0; k < static_cast<int>(road.lines.size()); ++k) {
      geom::Polyline run;
      bool run_bridge = false;
      auto flush = [&] {
        if (run.size() < 2) return;
        const int id = static_cast<int>(out.roads.features.size());
        int& first = first_feature[r][run_bridge];
        if (first < 0) first = id;
        ordered_json props{{"id", id}, {"class", name(road.road_class)}, {"width", road.width}, {"level", or_null(road.level)},
                           {"region", or_null(road.region)}, {"bridge", run_bridge}};
        out.roads.features.push_back({std::move(props), {}, std::move(run)});
        run.clear();
      };
      for (const geom::PolylinePiece& piece : pieces_of[road.first_tag + k]) {
        if (piece.from == piece.to) continue;  // shorter than a double's step: rounded away
        bool bridge = zm.labels[piece.left_label].cover == Cover::Water &&
                      zm.labels[piece.right_label].cover == Cover::Water;
        if (!run.empty() && (bridge != run_bridge || !(run.back() == piece.from))) flush();
        if (run.empty()) run.push_back(piece.from), run_bridge = bridge;
        run.push_back(piece.to);
      }
      flush();
    }
  }
  auto road_id = [&](int r, bool bridge) {
    const auto& f = first_feature[r];
    return f[bridge] >= 0 ? f[bridge] : f[!bridge];
  };
  // Road areas by road, surface and bridge: carriageways and sidewalks per road (groups
  // 4r + 2 sidewalk + bridge), then each junction (4 roads + 2j + bridge).
  const int junctions = static_cast<int>(zm.junction_roads.size());
  dissolve(zm, 4 * roads + 2 * junctions,
           [&](const FaceLabel& l) {
             if (!l.road_surface()) return -1;
             if (l.surface == RoadSurface::Junction) return 4 * roads + 2 * l.junction + l.bridge;
             return 4 * l.road + 2 * (l.surface == RoadSurface::Sidewalk) + l.bridge;
           },
           [&](int g, geom::Polygon p) {
             const bool junction = g >= 4 * roads, bridge = g % 2 == 1;
             const int road = junction ? zm.junction_roads[(g - 4 * roads) / 2] : g / 4;
             const RoadSurface surface = junction ? RoadSurface::Junction : g % 4 >= 2 ? RoadSurface::Sidewalk : RoadSurface::Carriageway;
             add_polygon(out.road_areas, {{"road", or_null(road_id(road, bridge))}, {"bridge", bridge}, {"surface", name(surface)}},
                         std::move(p));
           });

  // Blocks from the final map, so they share every vertex with the other layers (lots add
  // vertices on block edges). A block's id is its index, which lots name.
  auto block_properties = [&](int g) {
    const Block& b = blocks[g];
    ordered_json ids = ordered_json::array();
    for (int r : b.roads) ids.push_back(or_null(road_id(r, false)));
    return ordered_json{{"id", g}, {"zone", name(b.zone)}, {"green", b.green}, {"roads", ids}};
  };
  // Rounding can pinch a block in two: its first polygon keeps the block's id, the others
  // take ids after the last block's, and lots name the polygon they lie in.
  std::vector<std::vector<geom::Polygon>> block_polygons(blocks.size());
  dissolve(zm, static_cast<int>(blocks.size()), [](const FaceLabel& l) { return l.block; },
           [&](int g, geom::Polygon p) { block_polygons[g].push_back(std::move(p)); });
  std::vector<std::vector<std::size_t>> block_features(blocks.size());  // each block's features
  int next_id = static_cast<int>(blocks.size());
  for (std::size_t g = 0; g < blocks.size(); ++g)
    for (std::size_t k = 0; k < block_polygons[g].size(); ++k) {
      ordered_json props = block_properties(static_cast<int>(g));
      if (k > 0) props["id"] = next_id++;
      block_features[g].push_back(out.blocks.features.size());
      out.blocks.features.push_back({std::move(props), std::move(block_polygons[g][k]), {}});
    }
  auto block_of = [&](const Lot& lot) {
    const auto& features = block_features[lot.block];
    if (features.size() < 2) return lot.block;
    // The smallest polygon around the lot: a piece can lie in another's hole.
    int best = lot.block;
    double best_area = INFINITY;
    for (std::size_t i : features) {
      const VectorFeature& f = out.blocks.features[i];
      const double area = geom::area(f.polygon);
      if (area < best_area && geom::ring_within(lot.polygon.outer, f.polygon.outer))
        best = f.properties["id"].get<int>(), best_area = area;
    }
    return best;
  };

  // Lots as they ended up in the map; a lot's id is its index, which buildings name.
  for (const Lot& lot : lots)
    add_polygon(out.lots, {{"block", block_of(lot)}, {"zone", name(lot.zone)}}, lot.polygon);

  for (const Building& b : buildings) {
    nlohmann::ordered_json model = nullptr, kind = "building";
    if (b.placed.model >= 0) {
      const Model& m = library->models[b.placed.model];
      model = m.name;
      kind = m.kind == ModelKind::Tree ? "tree" : m.kind == ModelKind::Street ? "street" : "building";
    }
    add_polygon(out.buildings,
                {{"lot", b.lot}, {"zone", name(b.zone)}, {"height", b.height}, {"roof", b.roof}, {"model", model}, {"kind", kind}},
                b.polygon);
  }

  return out;
}

}  // namespace exacity
