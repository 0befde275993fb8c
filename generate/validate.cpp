#include "generate/validate.h"

#include <fstream>
#include <sstream>

#include "generate/drawn_zones.h"
#include "generate/errors.h"
#include "generate/geojson.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxProblems = 20;

// Written coordinates are the exact vertices rounded to doubles, so where a constructed
// vertex lies on a drawn edge, the written edge and the drawn edge bound a sliver about
// 1e-13 m wide (1e-9 m at UTM-sized coordinates). Comparisons with the drawn sketch
// accept faces thinner than this; every other check is exact without tolerance.
constexpr double kRoundingSliver = 1e-6;

enum class Kind { Zone, Water, Road, Bridge };

struct PolygonRef {
  Kind kind;
  std::string name;  // "zones.geojson features[3]"
  std::string zone;  // for zones
};

std::string near(geom::Vec2 p) { return " near (" + format_number(p.x) + ", " + format_number(p.y) + ")"; }

}  // namespace

Validation validate_output(const fs::path& dir) {
  Validation v;
  auto problem = [&](const std::string& p) {
    if (v.problems.size() < kMaxProblems) v.problems.push_back(p);
  };

  Sketch sketch;
  try {
    sketch = load_sketch(dir / "sketch.geojson");
  } catch (const UserError& e) {
    problem(std::string("sketch copy: ") + e.what());
    return v;
  }

  std::vector<std::string> read_problems;
  Layer zones = read_geojson(dir / "vector" / "zones.geojson", read_problems);
  Layer water = read_geojson(dir / "vector" / "water.geojson", read_problems);
  Layer road_areas = read_geojson(dir / "vector" / "road_areas.geojson", read_problems);
  Layer roads = read_geojson(dir / "vector" / "roads.geojson", read_problems);
  for (auto& p : read_problems) problem(p);

  // Each polygon alone: simple rings, outer counter-clockwise, holes clockwise.
  std::vector<PolygonRef> refs;
  std::vector<const geom::Polygon*> polygons;
  auto check_layer = [&](const Layer& layer, auto kind_of) {
    v.features[layer.name] = static_cast<int>(layer.features.size());
    for (std::size_t i = 0; i < layer.features.size(); ++i) {
      const VectorFeature& f = layer.features[i];
      std::string name = layer.name + ".geojson features[" + std::to_string(i) + "]";
      if (!f.properties.contains("id")) problem(name + ": no \"id\"");
      if (geom::ring_orientation(f.polygon.outer) != 1)
        problem(name + ": outer ring is not simple and counter-clockwise" + near(f.polygon.outer[0]));
      for (const auto& h : f.polygon.holes)
        if (geom::ring_orientation(h) != -1) problem(name + ": a hole is not simple and clockwise" + near(h[0]));
      refs.push_back({kind_of(f), name, f.properties.value("zone", "")});
      polygons.push_back(&f.polygon);
    }
  };
  check_layer(zones, [](const VectorFeature&) { return Kind::Zone; });
  check_layer(water, [](const VectorFeature&) { return Kind::Water; });
  check_layer(road_areas,
              [](const VectorFeature& f) { return f.properties.value("bridge", false) ? Kind::Bridge : Kind::Road; });
  v.features["roads"] = static_cast<int>(roads.features.size());
  for (std::size_t i = 0; i < roads.features.size(); ++i) {
    const VectorFeature& f = roads.features[i];
    for (const char* key : {"id", "class", "width", "level", "bridge"})
      if (!f.properties.contains(key)) problem("roads.geojson features[" + std::to_string(i) + "]: no \"" + key + "\"");
    if (f.line.size() < 2) problem("roads.geojson features[" + std::to_string(i) + "]: fewer than 2 positions");
  }
  if (!v.ok()) return v;

  // All polygons and the drawn zones in one exact map: polygon p's outer ring winds
  // around counter 2p, its holes around 2p + 1.
  geom::PlanarMap map;
  const int P = static_cast<int>(polygons.size());
  for (int p = 0; p < P; ++p) {
    map.add_ring(polygons[p]->outer, 2 * p, 0);
    for (std::size_t h = 0; h < polygons[p]->holes.size(); ++h)
      map.add_ring(polygons[p]->holes[h], 2 * p + 1, static_cast<int>(h) + 1);
  }
  DrawnZones drawn(sketch.zones, map, 2 * P);
  map.insert_batch();

  // A face's label is the index of what is wrong there; 0 where nothing is.
  std::vector<std::string> messages{""};
  std::vector<bool> against_sketch{false};
  std::map<std::string, int> message_index{{"", 0}};
  auto intern = [&](const std::string& m, bool sketch_check = false) {
    auto [it, added] = message_index.emplace(m, static_cast<int>(messages.size()));
    if (added) messages.push_back(m), against_sketch.push_back(sketch_check);
    return it->second;
  };
  map.label_faces([&](const geom::Windings& w) -> int {
    std::vector<int> inside;
    for (std::size_t i = 0; i < w.size() && w[i].first < 2 * P;) {
      int p = w[i].first / 2, outer = 0, holes = 0;
      for (; i < w.size() && w[i].first < 2 * P && w[i].first / 2 == p; ++i)
        (w[i].first % 2 == 0 ? outer : holes) = w[i].second;
      if (outer != 0 && outer != 1) return intern(refs[p].name + ": outer ring winds " + std::to_string(outer) + " times");
      if (holes != 0 && (holes != -1 || outer != 1)) return intern(refs[p].name + ": holes overlap or leave the outer ring");
      if (outer == 1 && holes == 0) inside.push_back(p);
    }
    int surface = 0, bridges = 0, water_here = 0, zone_here = -1;
    std::vector<std::string> names;
    for (int p : inside) {
      Kind k = refs[p].kind;
      if (k == Kind::Bridge) ++bridges;
      else ++surface, names.push_back(refs[p].name);
      if (k == Kind::Water) ++water_here;
      if (k == Kind::Zone) zone_here = p;
    }
    int top = drawn.top_zone(w);
    if (surface > 1) return intern(names[0] + " and " + names[1] + " overlap");
    if (bridges > 1) return intern("two bridges overlap");
    if (bridges == 1 && water_here == 0) return intern("a bridge lies outside the water");
    if (top >= 0 && surface == 0)
      return intern("the drawn zone features[" + std::to_string(sketch.zones[top].index) +
                    "] is not covered by a zone, water or road area", true);
    if (zone_here >= 0 && top < 0) return intern(refs[zone_here].name + " lies outside every drawn zone", true);
    if (zone_here >= 0 && refs[zone_here].zone != name(sketch.zones[top].type))
      return intern(refs[zone_here].name + " says zone \"" + refs[zone_here].zone + "\" where the sketch draws \"" +
                    std::string(name(sketch.zones[top].type)) + "\"", true);
    return 0;
  });
  for (std::size_t m = 1; m < messages.size(); ++m) {
    if (against_sketch[m]) {
      double width = map.widest_face(static_cast<int>(m));
      if (width <= kRoundingSliver) {
        v.widest_sliver = std::max(v.widest_sliver, width);
        continue;
      }
    }
    geom::Vec2 at;
    problem(messages[m] + (map.point_near_label(static_cast<int>(m), at) ? near(at) : ""));
  }

  // Two rings of one polygon may touch at a vertex but not run along each other.
  map.for_each_edge([&](const std::vector<geom::CurveTag>& tags, geom::Vec2 a, geom::Vec2) {
    for (std::size_t i = 0; i < tags.size(); ++i)
      for (std::size_t j = i + 1; j < tags.size(); ++j)
        if (tags[i].counter < 2 * P && tags[i].counter / 2 == tags[j].counter / 2 && tags[j].counter < 2 * P)
          problem(refs[tags[i].counter / 2].name + ": two of its rings share an edge" + near(a));
  });
  return v;
}

}  // namespace exacity
