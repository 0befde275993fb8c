#include "generate/export/validate_clutter.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <unordered_map>
#include <utility>

#include "generate/cancel.h"
#include "generate/cancellable_invoke.h"
#include "generate/placement/model_library.h"
#include "geom/polygon_check.h"
#include "geom/polygon_slabs.h"

namespace exacity {
namespace {

// As many problems as validate.cpp keeps in all.
constexpr std::size_t kMaxProblems = 20;

// A polygon of another layer a point is checked against.
struct Area {
  const geom::Polygon* polygon;
  geom::Box box;      // of its outer ring: a point outside it lies outside the area
  const Layer* layer;  // the area is its features[index]
  std::size_t index;
  bool stands_on;     // a sidewalk or a lot; else clutter keeps off it
  bool park = false;  // a park zone: a tree stands in it, other clutter keeps off it
  // For an area of many vertices (a long carriageway's), its edges by slabs: many points
  // lie in its box.
  std::unique_ptr<geom::PolygonSlabs> slabs = nullptr;
  int side(geom::Vec2 p) const { return slabs ? slabs->side(p) : geom::point_side(*polygon, p); }
  // "road_areas.geojson features[3] (carriageway)": spelt only for a problem.
  std::string name() const {
    std::string s = layer->name + ".geojson features[" + std::to_string(index) + "]";
    if (layer->name != "road_areas") return s;
    const nlohmann::ordered_json& properties = layer->features[index].properties;
    return s + " (" + properties.value("surface", std::string("?")) + (properties.value("bridge", false) ? " of a bridge)" : ")");
  }
};

// Areas of more vertices than this are asked through their slabs.
constexpr std::size_t kSlabbedVertices = 64;

std::unique_ptr<geom::PolygonSlabs> slabs_of(const geom::Polygon& polygon) {
  std::size_t vertices = polygon.outer.size();
  for (const geom::Ring& h : polygon.holes) vertices += h.size();
  return vertices > kSlabbedVertices ? std::make_unique<geom::PolygonSlabs>(polygon) : nullptr;
}

// The areas by the cells of a square grid their boxes meet, kept for the cells that hold a
// point to check only: the cells of a box are past counting where water covers a map of
// 1e6 m, and listing them all ran out of memory.
class AreaCells {
 public:
  static constexpr double kCell = 32;
  explicit AreaCells(const std::vector<geom::Vec2>& points) {
    for (geom::Vec2 p : points)
      if (cells_.try_emplace(key(cell(p.x), cell(p.y))).second) held_.push_back({cell(p.x), cell(p.y)});
  }
  void add(int area, const geom::Box& b) {
    const std::int64_t x0 = cell(b.min_x), x1 = cell(b.max_x), y0 = cell(b.min_y), y1 = cell(b.max_y);
    if (static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) <= static_cast<double>(held_.size())) {
      for (auto x = x0; x <= x1; ++x)
        for (auto y = y0; y <= y1; ++y)
          if (auto it = cells_.find(key(x, y)); it != cells_.end()) it->second.push_back(area);
    } else {
      for (auto [x, y] : held_)
        if (x >= x0 && x <= x1 && y >= y0 && y <= y1) cells_[key(x, y)].push_back(area);
    }
  }
  const std::vector<int>& at(geom::Vec2 p) const {
    static const std::vector<int> none;
    auto it = cells_.find(key(cell(p.x), cell(p.y)));
    return it == cells_.end() ? none : it->second;
  }

 private:
  static std::int64_t cell(double v) { return static_cast<std::int64_t>(std::floor(v / kCell)); }
  static std::int64_t key(std::int64_t x, std::int64_t y) { return x * 0x1000000 + y; }
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
  std::vector<std::pair<std::int64_t, std::int64_t>> held_;  // the cells holding points
};

geom::Box box_of(const geom::Polygon& polygon) {
  geom::Box b = geom::Box::none();
  for (geom::Vec2 q : polygon.outer) b.add(q);
  return b;
}

bool is_clutter_kind(const std::string& kind) {
  for (ModelKind k : kModelKinds)
    if (is_clutter(k) && kind == name(k)) return true;
  return false;
}

}  // namespace

void validate_clutter(const Layer& clutter, const std::vector<std::string>& read_problems, const CityLayers& layers,
                      Validation& v) {
  auto problem = [&](const std::string& p) {
    if (v.problems.size() < kMaxProblems) v.problems.push_back(p);
  };
  for (const std::string& p : read_problems) problem(p);
  v.features["clutter"] = static_cast<int>(clutter.features.size());

  std::vector<Area> areas;
  std::vector<geom::Vec2> points;
  for (const VectorFeature& f : clutter.features)
    if (f.line.size() == 1) points.push_back(f.line[0]);
  AreaCells cells(points);
  const CancelCheck cancel;
  areas.reserve(layers.road_areas.features.size() + layers.lots.features.size() + layers.water.features.size() +
                layers.zones.features.size() + layers.buildings.features.size());
  auto add = [&](const Layer& layer, auto&& stands_on) {
    for (std::size_t i = 0; i < layer.features.size(); ++i) {
      cancel.check();
      const VectorFeature& f = layer.features[i];
      areas.push_back({&f.polygon, box_of(f.polygon), &layer, i, stands_on(f), false, slabs_of(f.polygon)});
      cells.add(static_cast<int>(areas.size()) - 1, areas.back().box);
    }
  };
  add(layers.road_areas, [](const VectorFeature& f) {
    return f.properties.value("surface", "") == "sidewalk" && !f.properties.value("bridge", false);
  });
  add(layers.lots, [](const VectorFeature&) { return true; });
  add(layers.water, [](const VectorFeature&) { return false; });
  // Parks, where only a park's trees stand (zones lie under sidewalks and lots too).
  for (std::size_t i = 0; i < layers.zones.features.size(); ++i) {
    const VectorFeature& f = layers.zones.features[i];
    if (f.properties.value("zone", "") != "park") continue;
    areas.push_back({&f.polygon, box_of(f.polygon), &layers.zones, i, false, true, slabs_of(f.polygon)});
    cells.add(static_cast<int>(areas.size()) - 1, areas.back().box);
  }
  add(layers.buildings, [](const VectorFeature&) { return false; });

  // Sorted arrays, not hashed sets: a node per id of 300,000 was 2% of validating the 10 km
  // city. A piece's id is not unique when an earlier piece has it.
  std::vector<int> roads;
  roads.reserve(layers.roads.features.size());
  for (const VectorFeature& f : layers.roads.features) roads.push_back(f.properties.value("id", -1));
  std::sort(roads.begin(), roads.end());
  const std::size_t n = clutter.features.size();
  std::vector<char> id_taken(n, 0);  // an earlier piece has this one's id
  {
    std::vector<std::pair<int, std::size_t>> ids;  // (id, piece) of those with an integer id
    ids.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& props = clutter.features[i].properties;
      if (clutter.features[i].line.size() != 1 || !clutter.features[i].polygon.outer.empty()) continue;  // not a Point: not checked
      if (const auto id = props.find("id"); id != props.end() && id->is_number_integer()) ids.push_back({id->get<int>(), i});
    }
    std::sort(ids.begin(), ids.end());
    for (std::size_t k = 1; k < ids.size(); ++k) id_taken[ids[k].second] = ids[k].first == ids[k - 1].first;
  }
  // Each piece on its own, at once, in runs whose problems (the first few of each) are
  // taken in the pieces' order.
  constexpr std::size_t kRun = 4096;
  std::vector<std::vector<std::string>> run_problems((n + kRun - 1) / kRun);
  for_each_cancellable(run_problems.size(), [&](std::size_t r) {
    std::vector<std::string>& found = run_problems[r];
    auto problem = [&](const std::string& p) {
      if (found.size() < kMaxProblems) found.push_back(p);
    };
    for (std::size_t i = r * kRun; i < std::min(n, (r + 1) * kRun); ++i) {
      const VectorFeature& f = clutter.features[i];
      // The feature's name and place, spelt only for a problem.
      const auto name = [&] { return "clutter.geojson features[" + std::to_string(i) + "]"; };
      if (f.line.size() != 1 || !f.polygon.outer.empty()) {
        problem(name() + ": not a Point");
        continue;
      }
      const geom::Vec2 p = f.line[0];
      const auto at = [&] { return " at (" + format_number(p.x) + ", " + format_number(p.y) + ")"; };
      const auto& props = f.properties;
      // Each member looked up once (as find finds it: the first of its key).
      const nlohmann::ordered_json *id = nullptr, *kind = nullptr, *model = nullptr, *road = nullptr, *heading = nullptr;
      if (props.is_object())
        for (const auto& [key, value] : props.items()) {
          const nlohmann::ordered_json** member = key == "id"        ? &id
                                                  : key == "kind"    ? &kind
                                                  : key == "model"   ? &model
                                                  : key == "road"    ? &road
                                                  : key == "heading" ? &heading
                                                                     : nullptr;
          if (member && !*member) *member = &value;
        }
      const nlohmann::ordered_json null;
      if (!props.is_object()) (void)props.value("kind", null);  // throws, as the lookups by key did
      if (!id || !id->is_number_integer() || id_taken[i]) problem(name() + ": its id is missing or not unique");
      if (!kind || !kind->is_string() || !is_clutter_kind(kind->get_ref<const std::string&>()))
        problem(name() + ": \"kind\" is " + (kind ? *kind : null).dump() + ", no clutter kind");
      if (!model || !model->is_string()) problem(name() + ": no \"model\"");
      const bool tree = kind && *kind == "tree";
      // A park's tree dresses no street: its road is null.
      const bool park_tree = tree && road && road->is_null();
      if (!park_tree && (!road || !road->is_number_integer() || !std::binary_search(roads.begin(), roads.end(), road->get<int>())))
        problem(name() + ": \"road\" " + (road ? *road : null).dump() + " names no feature of roads.geojson");
      const double angle = heading && heading->is_number() ? heading->get<double>() : -1;
      if (!(angle >= 0 && angle < 360)) problem(name() + ": \"heading\" is not degrees in [0, 360)");
      bool stands = false;
      for (int a : cells.at(p)) {
        const geom::Box& box = areas[a].box;
        if (p.x < box.min_x || p.x > box.max_x || p.y < box.min_y || p.y > box.max_y) continue;  // outside: no verdict
        const int side = areas[a].side(p);
        if (areas[a].park) {
          if (park_tree)
            stands |= side > 0;
          else if (side > 0 && tree)
            problem(name() + at() + " stands in " + areas[a].name() + ", a park, but names a road");
          continue;
        }
        if (areas[a].stands_on)
          stands |= side > 0;
        else if (side >= 0)
          problem(name() + at() + (side > 0 ? " stands in " : " stands on the edge of ") + areas[a].name());
      }
      if (!stands)
        problem(name() + at() +
                (park_tree ? " is a park's tree but stands strictly inside no park"
                           : " stands strictly inside no sidewalk and no lot"));
    }
  });
  for (const auto& found : run_problems)
    for (const std::string& p : found) problem(p);
}

}  // namespace exacity
