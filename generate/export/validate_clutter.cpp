#include "generate/export/validate_clutter.h"

#include <cmath>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "generate/cancel.h"
#include "generate/export/read_lines.h"
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
  std::string name;   // "road_areas.geojson features[3] (carriageway)"
  bool stands_on;     // a sidewalk or a lot; else clutter keeps off it
  bool park = false;  // a park zone: a tree stands in it, other clutter keeps off it
  // For an area of many vertices (a long carriageway's), its edges by slabs: many points
  // lie in its box.
  std::unique_ptr<geom::PolygonSlabs> slabs = nullptr;
  int side(geom::Vec2 p) const { return slabs ? slabs->side(p) : geom::point_side(*polygon, p); }
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

void validate_clutter(const std::filesystem::path& dir, const CityLayers& layers, Validation& v, ReadLines* known) {
  auto problem = [&](const std::string& p) {
    if (v.problems.size() < kMaxProblems) v.problems.push_back(p);
  };
  std::vector<std::string> read_problems;
  const std::filesystem::path file = dir / "vector" / "clutter.geojson";
  const Layer clutter = known ? read_geojson(file, read_problems, *known) : read_geojson(file, read_problems);
  for (const std::string& p : read_problems) problem(p);
  v.features["clutter"] = static_cast<int>(clutter.features.size());

  std::vector<Area> areas;
  std::vector<geom::Vec2> points;
  for (const VectorFeature& f : clutter.features)
    if (f.line.size() == 1) points.push_back(f.line[0]);
  AreaCells cells(points);
  const CancelCheck cancel;
  auto add = [&](const Layer& layer, auto&& stands_on, auto&& what) {
    for (std::size_t i = 0; i < layer.features.size(); ++i) {
      cancel.check();
      const VectorFeature& f = layer.features[i];
      areas.push_back({&f.polygon, box_of(f.polygon), layer.name + ".geojson features[" + std::to_string(i) + "]" + what(f),
                       stands_on(f), false, slabs_of(f.polygon)});
      cells.add(static_cast<int>(areas.size()) - 1, areas.back().box);
    }
  };
  const auto no_note = [](const VectorFeature&) { return std::string(); };
  add(
      layers.road_areas,
      [](const VectorFeature& f) {
        return f.properties.value("surface", "") == "sidewalk" && !f.properties.value("bridge", false);
      },
      [](const VectorFeature& f) {
        return " (" + f.properties.value("surface", std::string("?")) +
               (f.properties.value("bridge", false) ? " of a bridge)" : ")");
      });
  add(
      layers.lots, [](const VectorFeature&) { return true; }, no_note);
  add(
      layers.water, [](const VectorFeature&) { return false; }, no_note);
  // Parks, where only a park's trees stand (zones lie under sidewalks and lots too).
  for (std::size_t i = 0; i < layers.zones.features.size(); ++i) {
    const VectorFeature& f = layers.zones.features[i];
    if (f.properties.value("zone", "") != "park") continue;
    areas.push_back({&f.polygon, box_of(f.polygon), "zones.geojson features[" + std::to_string(i) + "]", false, true,
                     slabs_of(f.polygon)});
    cells.add(static_cast<int>(areas.size()) - 1, areas.back().box);
  }
  add(
      layers.buildings, [](const VectorFeature&) { return false; }, no_note);

  // Hashed: a sorted set's insertions of 300,000 clutter ids were 2% of validating the 10 km city.
  std::unordered_set<int> roads, ids;
  ids.reserve(clutter.features.size());
  for (const VectorFeature& f : layers.roads.features) roads.insert(f.properties.value("id", -1));
  for (std::size_t i = 0; i < clutter.features.size(); ++i) {
    cancel.check();
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
    if (!props.contains("id") || !props["id"].is_number_integer() || !ids.insert(props["id"].get<int>()).second)
      problem(name() + ": its id is missing or not unique");
    if (!props.contains("kind") || !props["kind"].is_string() || !is_clutter_kind(props["kind"].get<std::string>()))
      problem(name() + ": \"kind\" is " + props.value("kind", nlohmann::ordered_json()).dump() + ", no clutter kind");
    if (!props.contains("model") || !props["model"].is_string()) problem(name() + ": no \"model\"");
    const bool tree = props.value("kind", nlohmann::ordered_json()) == "tree";
    // A park's tree dresses no street: its road is null.
    const bool park_tree = tree && props.contains("road") && props["road"].is_null();
    if (!park_tree &&
        (!props.contains("road") || !props["road"].is_number_integer() || !roads.count(props["road"].get<int>())))
      problem(name() + ": \"road\" " + props.value("road", nlohmann::ordered_json()).dump() +
              " names no feature of roads.geojson");
    const double heading =
        props.contains("heading") && props["heading"].is_number() ? props["heading"].get<double>() : -1;
    if (!(heading >= 0 && heading < 360)) problem(name() + ": \"heading\" is not degrees in [0, 360)");
    bool stands = false;
    for (int a : cells.at(p)) {
      const geom::Box& box = areas[a].box;
      if (p.x < box.min_x || p.x > box.max_x || p.y < box.min_y || p.y > box.max_y) continue;  // outside: no verdict
      const int side = areas[a].side(p);
      if (areas[a].park) {
        if (park_tree)
          stands |= side > 0;
        else if (side > 0 && tree)
          problem(name() + at() + " stands in " + areas[a].name + ", a park, but names a road");
        continue;
      }
      if (areas[a].stands_on)
        stands |= side > 0;
      else if (side >= 0)
        problem(name() + at() + (side > 0 ? " stands in " : " stands on the edge of ") + areas[a].name);
    }
    if (!stands)
      problem(name() + at() +
              (park_tree ? " is a park's tree but stands strictly inside no park"
                         : " stands strictly inside no sidewalk and no lot"));
  }
}

}  // namespace exacity
