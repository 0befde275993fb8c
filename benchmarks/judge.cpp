#include "benchmarks/judge.h"

#include <geos_c.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "benchmarks/geos_handle.h"

namespace exacity::bench {

namespace {
constexpr int kShownPerKind = 5;
}

void Verdict::reject(const std::string& kind, const std::string& detail) {
  if (++rejected[kind] <= kShownPerKind) problems.push_back(kind + ": " + detail);
}

namespace {

// GEOS's reentrant API behind owning handles.
class Geos {
 public:
  Geos() : ctx_(GEOS_init_r()), reader_(GEOSGeoJSONReader_create_r(ctx_)) {}
  ~Geos() {
    GEOSGeoJSONReader_destroy_r(ctx_, reader_);
    GEOS_finish_r(ctx_);
  }
  Geos(const Geos&) = delete;
  Geos& operator=(const Geos&) = delete;

  using Free = GeosFree;
  using Geometry = GeosGeometry;

  GEOSContextHandle_t ctx() const { return ctx_; }
  Geometry own(GEOSGeometry* g) const { return Geometry(g, Free{ctx_}); }
  Geometry read(const nlohmann::json& geometry) const {
    return own(GEOSGeoJSONReader_readGeometry_r(ctx_, reader_, geometry.dump().c_str()));
  }
  double area(const GEOSGeometry* g) const {
    double a = 0;
    return g && GEOSArea_r(ctx_, g, &a) ? a : 0;
  }
  std::string invalid_reason(const GEOSGeometry* g) const {
    if (GEOSisValid_r(ctx_, g) == 1) return {};
    char* why = GEOSisValidReason_r(ctx_, g);
    std::string reason = why ? why : "not valid";
    GEOSFree_r(ctx_, why);
    return reason;
  }
  // The union of the geometries (none of them given away); null when GEOS fails.
  Geometry union_of(const std::vector<const GEOSGeometry*>& parts) const {
    std::vector<GEOSGeometry*> copies;
    for (const GEOSGeometry* g : parts) copies.push_back(GEOSGeom_clone_r(ctx_, g));
    Geometry all = own(GEOSGeom_createCollection_r(ctx_, GEOS_GEOMETRYCOLLECTION, copies.data(),
                                                   static_cast<unsigned>(copies.size())));
    return own(all ? GEOSUnaryUnion_r(ctx_, all.get()) : nullptr);
  }
  Geometry difference(const GEOSGeometry* a, const GEOSGeometry* b) const { return own(GEOSDifference_r(ctx_, a, b)); }
  Geometry intersection(const GEOSGeometry* a, const GEOSGeometry* b) const {
    return own(GEOSIntersection_r(ctx_, a, b));
  }

  // Calls f(i, j), i < j, for every pair whose envelopes meet.
  void for_each_near_pair(const std::vector<const GEOSGeometry*>& geoms, const std::function<void(int, int)>& f) const {
    GEOSSTRtree* tree = GEOSSTRtree_create_r(ctx_, 10);
    std::vector<int> ids(geoms.size());
    std::iota(ids.begin(), ids.end(), 0);
    for (std::size_t i = 0; i < geoms.size(); ++i) GEOSSTRtree_insert_r(ctx_, tree, geoms[i], &ids[i]);
    std::vector<int> near;
    for (std::size_t i = 0; i < geoms.size(); ++i) {
      near.clear();
      GEOSSTRtree_query_r(
          ctx_, tree, geoms[i], [](void* item, void* list) { static_cast<std::vector<int>*>(list)->push_back(*static_cast<int*>(item)); },
          &near);
      std::sort(near.begin(), near.end());
      for (int j : near)
        if (j > static_cast<int>(i)) f(static_cast<int>(i), j);
    }
    GEOSSTRtree_destroy_r(ctx_, tree);
  }

  std::vector<std::pair<double, double>> vertices(const GEOSGeometry* line) const {
    std::vector<std::pair<double, double>> v;
    const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(ctx_, line);
    unsigned n = 0;
    if (!seq || !GEOSCoordSeq_getSize_r(ctx_, seq, &n)) return v;
    for (unsigned k = 0; k < n; ++k) {
      double x = 0, y = 0;
      GEOSCoordSeq_getX_r(ctx_, seq, k, &x);
      GEOSCoordSeq_getY_r(ctx_, seq, k, &y);
      v.push_back({x, y});
    }
    return v;
  }

 private:
  GEOSContextHandle_t ctx_;
  GEOSGeoJSONReader* reader_;
};

struct Feature {
  std::string name;  // layer[index]
  nlohmann::json properties;
  Geos::Geometry geometry;
  bool valid = false;
};

// A layer's features; those GEOS finds invalid are rejected when `judged` (a sketch is
// input, not output: its rings may cross themselves).
std::vector<Feature> read_layer(const Geos& geos, const std::filesystem::path& file, const std::string& layer,
                                Verdict& verdict, bool judged = true) {
  std::vector<Feature> features;
  std::ifstream in(file);
  nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  if (!in || doc.is_discarded() || !doc.contains("features") || !doc["features"].is_array()) {
    verdict.reject("unreadable", file.string() + ": not a GeoJSON FeatureCollection");
    return features;
  }
  for (std::size_t i = 0; i < doc["features"].size(); ++i) {
    const nlohmann::json& f = doc["features"][i];
    Feature feature{layer + "[" + std::to_string(i) + "]", f.value("properties", nlohmann::json::object()),
                    geos.read(f.value("geometry", nlohmann::json())), false};
    if (!feature.geometry) {
      verdict.reject("unreadable", feature.name + ": GEOS cannot read its geometry");
    } else if (std::string why = judged ? geos.invalid_reason(feature.geometry.get()) : ""; !why.empty()) {
      verdict.reject("invalid", feature.name + ": " + why);
    } else {
      feature.valid = true;
    }
    features.push_back(std::move(feature));
  }
  return features;
}

std::vector<const GEOSGeometry*> valid_geometries(const std::vector<const Feature*>& features) {
  std::vector<const GEOSGeometry*> g;
  for (const Feature* f : features)
    if (f->valid) g.push_back(f->geometry.get());
  return g;
}

// The parts of a tiling overlap nowhere: the area of their union is the sum of theirs.
void check_tiling(const Geos& geos, const std::string& name, const std::vector<const Feature*>& parts, Verdict& verdict) {
  std::vector<const GEOSGeometry*> g = valid_geometries(parts);
  double sum = 0;
  for (const GEOSGeometry* p : g) sum += geos.area(p);
  Geos::Geometry all = geos.union_of(g);
  if (!all) {
    verdict.reject("overlap", name + ": GEOS could not form the union");
    return;
  }
  const double excess = sum - geos.area(all.get());
  if (excess > kRelativeArea * sum) {
    std::ostringstream why;
    why << name << ": the parts cover " << excess << " m2 more than their union";
    verdict.reject("overlap", why.str());
  }
}

// `inner` lies inside the feature of `outer` its property `key` names.
void check_inside(const Geos& geos, const std::vector<Feature>& inner, const std::vector<Feature>& outer,
                  const std::string& key, Verdict& verdict) {
  std::map<long long, const Feature*> by_id;
  for (const Feature& f : outer)
    if (f.properties.contains("id") && f.properties["id"].is_number_integer()) by_id[f.properties["id"].get<long long>()] = &f;
  for (const Feature& f : inner) {
    if (!f.valid) continue;
    const nlohmann::json& ref = f.properties.value(key, nlohmann::json());
    auto it = ref.is_number_integer() ? by_id.find(ref.get<long long>()) : by_id.end();
    if (it == by_id.end()) {
      verdict.reject("outside", f.name + ": its " + key + " names no feature");
      continue;
    }
    if (!it->second->valid) continue;
    Geos::Geometry rest = geos.difference(f.geometry.get(), it->second->geometry.get());
    const double a = geos.area(f.geometry.get());
    if (!rest || geos.area(rest.get()) > kRelativeArea * a) {
      std::ostringstream why;
      why << f.name << ": " << (rest ? geos.area(rest.get()) : a) << " m2 outside its " << key << " " << ref;
      verdict.reject("outside", why.str());
    }
  }
}

// Centre lines meet only at vertices of both, and make one connected network.
void check_network(const Geos& geos, const std::vector<Feature>& roads, Verdict& verdict) {
  std::vector<const GEOSGeometry*> lines;
  std::vector<std::vector<std::pair<double, double>>> vertices;
  for (const Feature& r : roads)
    if (r.valid) lines.push_back(r.geometry.get()), vertices.push_back(geos.vertices(r.geometry.get()));
  auto has_vertex = [&](int line, double x, double y) {
    return std::find(vertices[line].begin(), vertices[line].end(), std::make_pair(x, y)) != vertices[line].end();
  };
  std::vector<int> parent(lines.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int i) { return parent[i] == i ? i : parent[i] = root(parent[i]); };
  geos.for_each_near_pair(lines, [&](int i, int j) {
    Geos::Geometry meet = geos.intersection(lines[i], lines[j]);
    if (!meet || GEOSisEmpty_r(geos.ctx(), meet.get())) return;
    const int n = GEOSGetNumGeometries_r(geos.ctx(), meet.get());
    for (int k = 0; k < n; ++k) {
      const GEOSGeometry* part = GEOSGetGeometryN_r(geos.ctx(), meet.get(), k);
      const std::string pair = "roads[" + std::to_string(i) + "] and roads[" + std::to_string(j) + "]";
      if (GEOSGeomTypeId_r(geos.ctx(), part) != GEOS_POINT) {
        verdict.reject("network", pair + " overlap");
        continue;
      }
      double x = 0, y = 0;
      GEOSGeomGetX_r(geos.ctx(), part, &x);
      GEOSGeomGetY_r(geos.ctx(), part, &y);
      if (!has_vertex(i, x, y) || !has_vertex(j, x, y)) {
        verdict.reject("network", pair + " cross between vertices");
        continue;
      }
      parent[root(i)] = root(j);
    }
  });
  // One piece, or pieces that each hold a road the sketch drew (its `level` null): the
  // sketch's own roads need not meet, but every grown street must reach one of them.
  std::vector<int> roots;
  std::set<int> drawn;
  for (std::size_t i = 0; i < roads.size(); ++i) {
    if (!roads[i].valid) continue;
    const int r = root(static_cast<int>(roots.size()));
    roots.push_back(r);
    const auto level = roads[i].properties.find("level");
    if (level != roads[i].properties.end() && level->is_null()) drawn.insert(r);
  }
  std::set<int> pieces(roots.begin(), roots.end());
  int apart = 0;
  for (int p : pieces) apart += !drawn.count(p);
  if (pieces.size() > 1 && apart > 0)
    verdict.reject("network", "the centre lines fall apart in " + std::to_string(pieces.size()) + " pieces, " +
                                  std::to_string(apart) + " of them reaching no road of the sketch");
}

// Each zone written has the type of the zone the sketch has on top where it lies (the last
// drawn, water zones too): a face given the windings of the wrong side of an edge, as when
// a vertex or a hole silently crosses an edge, is labelled with another zone's type, which
// the tilings and the coverage cannot see. Areas compare to the drawn area.
void check_labels(const Geos& geos, const std::vector<const GEOSGeometry*>& drawn, const std::vector<std::string>& types,
                  const std::vector<Feature>& zones, double drawn_area, Verdict& verdict) {
  std::map<std::string, std::vector<Geos::Geometry>> visible;  // per type, the parts of its zones on top
  Geos::Geometry above;  // the zones drawn after the one at hand
  for (std::size_t i = drawn.size(); i-- > 0;) {
    Geos::Geometry part = above ? geos.difference(drawn[i], above.get()) : geos.own(GEOSGeom_clone_r(geos.ctx(), drawn[i]));
    if (part) visible[types[i]].push_back(std::move(part));
    above = above ? geos.union_of({above.get(), drawn[i]}) : geos.own(GEOSGeom_clone_r(geos.ctx(), drawn[i]));
  }
  std::map<std::string, std::vector<const GEOSGeometry*>> written;
  for (const Feature& z : zones)
    if (z.valid) written[z.properties.value("zone", "")].push_back(z.geometry.get());
  for (const auto& [type, parts] : written) {
    Geos::Geometry out = geos.union_of(parts);
    std::vector<const GEOSGeometry*> on_top;
    for (const Geos::Geometry& g : visible[type]) on_top.push_back(g.get());
    Geos::Geometry drawn_type = geos.union_of(on_top);
    Geos::Geometry wrong;
    if (out && drawn_type) wrong = geos.difference(out.get(), drawn_type.get());
    const double area = wrong ? geos.area(wrong.get()) : out ? geos.area(out.get()) : 0;
    if (area > kRelativeArea * drawn_area) {
      std::ostringstream why;
      why << area << " m2 of zones written as " << type << " where the sketch's zone on top is not " << type;
      verdict.reject("label", why.str());
    }
  }
}

}  // namespace

Verdict judge(const std::filesystem::path& out) {
  Verdict verdict;
  Geos geos;
  std::map<std::string, std::vector<Feature>> layers;
  for (const char* layer : {"zones", "water", "road_areas", "blocks", "lots", "buildings", "roads"})
    layers[layer] = read_layer(geos, out / "vector" / (std::string(layer) + ".geojson"), layer, verdict);
  std::vector<Feature> drawn = read_layer(geos, out / "sketch.geojson", "sketch", verdict, false);
  if (verdict.rejected.count("unreadable")) return verdict;

  auto all_of = [&](std::initializer_list<const char*> names, const std::function<bool(const Feature&)>& keep) {
    std::vector<const Feature*> list;
    for (const char* n : names)
      for (const Feature& f : layers[n])
        if (keep(f)) list.push_back(&f);
    return list;
  };
  auto any = [](const Feature&) { return true; };
  auto on_land = [](const Feature& f) { return !f.properties.value("bridge", false); };
  auto park = [](const Feature& f) { return f.properties.value("zone", "") == "park"; };
  std::vector<const Feature*> ground = all_of({"zones", "water"}, any), roads_on_land = all_of({"road_areas"}, on_land);
  ground.insert(ground.end(), roads_on_land.begin(), roads_on_land.end());
  check_tiling(geos, "zones, water and road areas", ground, verdict);
  std::vector<const Feature*> blocks = all_of({"blocks", "water"}, any), parks = all_of({"zones"}, park);
  blocks.insert(blocks.end(), parks.begin(), parks.end());
  blocks.insert(blocks.end(), roads_on_land.begin(), roads_on_land.end());
  check_tiling(geos, "blocks, parks, water and road areas", blocks, verdict);
  for (const char* inner : {"lots", "buildings"}) {
    std::vector<const Feature*> parts = all_of({inner}, any);
    parts.insert(parts.end(), roads_on_land.begin(), roads_on_land.end());
    check_tiling(geos, std::string(inner) + " and road areas", parts, verdict);
  }

  // Every drawn zone is covered by the zones, water and road areas written.
  std::vector<const GEOSGeometry*> zones_drawn;
  std::vector<std::string> types_drawn;
  std::vector<Geos::Geometry> repaired;
  for (const Feature& f : drawn) {
    if (!f.properties.contains("zone")) continue;
    repaired.push_back(geos.own(GEOSMakeValid_r(geos.ctx(), f.geometry.get())));
    if (repaired.back())
      zones_drawn.push_back(repaired.back().get()), types_drawn.push_back(f.properties.value("zone", ""));
  }
  Geos::Geometry sketch_area = geos.union_of(zones_drawn), covered = geos.union_of(valid_geometries(ground));
  if (sketch_area && covered) {
    Geos::Geometry uncovered = geos.difference(sketch_area.get(), covered.get());
    const double gap = uncovered ? geos.area(uncovered.get()) : geos.area(sketch_area.get());
    if (gap > kRelativeArea * geos.area(sketch_area.get())) {
      std::ostringstream why;
      why << gap << " m2 of the drawn zones covered by no zone, water or road area";
      verdict.reject("gap", why.str());
    }
  }
  if (sketch_area) check_labels(geos, zones_drawn, types_drawn, layers["zones"], geos.area(sketch_area.get()), verdict);

  check_inside(geos, layers["lots"], layers["blocks"], "block", verdict);
  check_inside(geos, layers["buildings"], layers["lots"], "lot", verdict);
  check_network(geos, layers["roads"], verdict);
  return verdict;
}

nlohmann::ordered_json judge_invariants() {
  using json = nlohmann::ordered_json;
  auto invariant = [](const char* kind, json layers, const char* rule, double tolerance) {
    return json{{"kind", kind}, {"layers", std::move(layers)}, {"rule", rule}, {"relative_area_tolerance", tolerance}};
  };
  const json polygons = {"zones", "water", "road_areas", "blocks", "lots", "buildings"};
  return {
      {"output",
       {{"sketch", "OUT/sketch.geojson, the sketch the output was made from"},
        {"layers", "OUT/vector/LAYER.geojson, GeoJSON FeatureCollections in the sketch's metres: zones (property "
                   "zone), water, road_areas (bridge: true for those over water), blocks (id), lots (id, block), "
                   "buildings (id, lot), roads (centre lines; level null for a road the sketch drew)"}}},
      {"invariants",
       json::array({invariant("invalid", polygons, "every polygon is valid by OGC rules", 0),
                    invariant("overlap", {"zones", "water", "road_areas not bridges"},
                              "a tiling: the parts' areas sum to their union's", kRelativeArea),
                    invariant("overlap", {"blocks", "parks of zones", "water", "road_areas not bridges"},
                              "a tiling: the parts' areas sum to their union's", kRelativeArea),
                    invariant("overlap", {"lots", "road_areas not bridges"}, "a tiling", kRelativeArea),
                    invariant("overlap", {"buildings", "road_areas not bridges"}, "a tiling", kRelativeArea),
                    invariant("gap", {"sketch zones (made valid)", "zones", "water", "road_areas not bridges"},
                              "the drawn zones are covered by the zones, water and road areas", kRelativeArea),
                    invariant("label", {"zones", "sketch zones (made valid)"},
                              "each zone written has the type of the sketch's zone on top where it lies (the last "
                              "drawn, water zones too)",
                              kRelativeArea),
                    invariant("outside", {"lots", "blocks"}, "each lot lies in the block its property block names",
                              kRelativeArea),
                    invariant("outside", {"buildings", "lots"},
                              "each building lies in the lot its property lot names", kRelativeArea),
                    invariant("network", {"roads"},
                              "centre lines meet only at vertices of both, never overlap, and every connected piece "
                              "holds a road the sketch drew (or there is one piece)",
                              0)})}};
}

}  // namespace exacity::bench
