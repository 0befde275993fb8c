#include "generate/placement/clutter.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>
#include <unordered_map>

#include "generate/cancel.h"
#include "generate/city/stable_ids.h"
#include "generate/errors.h"
#include "generate/export/geojson.h"
#include "generate/placement/model_placement.h"
#include "generate/placement/street_nodes.h"
#include "geom/grid.h"
#include "geom/measure.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::Vec2;

// Why a spot found no place (report.json's clutter.not_placed).
constexpr const char* kOnRoad = "on a carriageway or in a junction";
constexpr const char* kOnWater = "on water or a bridge";
constexpr const char* kNoGround = "no sidewalk or lot there (a park, green space or open land)";
constexpr const char* kOnEdge = "on an edge between two faces of the map";
constexpr const char* kBaseLeaves = "its base leaves the sidewalk or lot";
constexpr const char* kBuilding = "a building or lot furniture stands there";
constexpr const char* kOtherClutter = "other clutter stands there";
constexpr const char* kChannels = "no entry of the kind suits the channels there";
constexpr const char* kNearCrown = "a lamp's head would hang in or near a tree's crown";

// How far a lamp's head keeps from a tree's crown (docs/design.md, Placement: street
// clutter): a lamp a metre from leaves lights them with about its whole intensity, some
// forty times what reaches the road under it, and at night such crowns glowed.
constexpr double kCrownClearance = 1.5;

// A model's base: its outline where it meets the ground (the convex hull of its vertices in
// the lowest 30 cm, or quarter of its height), so a lamp's arm or a tree's crown may reach
// over the kerb or a garden while its pole or trunk stands on the sidewalk or in the lot.
struct Base {
  geom::Ring ring;  // in the model's frame, counter-clockwise
  Vec2 centre;      // its bounding box's centre: where the model stands
};

Base base_of(const Model& m) {
  const double top = std::min(0.3, m.height / 4);
  std::vector<Vec2> low;
  for (const Vec3& v : m.mesh.vertices)
    if (v[2] <= top) low.push_back({v[0], v[1]});
  Base b;
  b.ring = low.size() >= 3 ? geom::convex_hull(low) : geom::Ring{};
  if (b.ring.size() < 3) b.ring = {{-0.1, -0.1}, {0.1, -0.1}, {0.1, 0.1}, {-0.1, 0.1}};
  geom::Box box = geom::Box::none();
  for (Vec2 p : b.ring) box.add(p);
  b.centre = {(box.min_x + box.max_x) / 2, (box.min_y + box.max_y) / 2};
  return b;
}

// What of a model hangs where other clutter may reach it: a tree's crown (what stands
// wider than its base), a lamp's head (its light's triangles, else its top half metre), as
// a vertical cylinder around it in the model's frame. Doubles: a clearance, not a rule the
// map decides.
struct Canopy {
  enum Part { kNone, kCrown, kHead } part = kNone;
  Vec2 centre;             // in the model's frame, or placed
  double radius = 0;       // around the centre
  double low = 0, high = 0;  // over the model's base, or placed
};

Canopy canopy_of(const Model& m, const Base& base) {
  std::vector<Vec3> parts;
  if (m.kind == ModelKind::Tree) {
    double reach = 0;  // the base's, from its centre
    for (Vec2 p : base.ring) reach = std::max(reach, geom::distance(p, base.centre));
    for (const Vec3& v : m.mesh.vertices)
      if (geom::distance({v[0], v[1]}, base.centre) > reach + 0.05) parts.push_back(v);
  } else if (m.kind == ModelKind::Lamp) {
    for (std::size_t t = 0; t < m.mesh.triangles.size(); ++t)
      if (is_lamp_light_material(m.mesh.materials[static_cast<std::size_t>(m.mesh.material[t])].name))
        for (int c : m.mesh.triangles[t]) parts.push_back(m.mesh.vertices[static_cast<std::size_t>(c)]);
    if (parts.empty())
      for (const Vec3& v : m.mesh.vertices)
        if (v[2] >= m.height - 0.5) parts.push_back(v);
  }
  if (parts.empty()) return {};
  Canopy c;
  c.part = m.kind == ModelKind::Tree ? Canopy::kCrown : Canopy::kHead;
  geom::Box box = geom::Box::none();
  c.low = INFINITY, c.high = -INFINITY;
  for (const Vec3& v : parts) box.add(Vec2{v[0], v[1]}), c.low = std::min(c.low, v[2]), c.high = std::max(c.high, v[2]);
  c.centre = {(box.min_x + box.max_x) / 2, (box.min_y + box.max_y) / 2};
  for (const Vec3& v : parts) c.radius = std::max(c.radius, geom::distance({v[0], v[1]}, c.centre));
  return c;
}

// Rings by the cells of a square grid their boxes meet, to find the few near a point or ring.
class RingBuckets {
 public:
  explicit RingBuckets(double cell) : cell_(cell) {}
  void add(const geom::Ring& ring, int value) {
    for_cells(box_of(ring), [&](std::int64_t key) { cells_[key].push_back(value); });
  }
  // Values whose rings' boxes share a cell with the box, each once, in ascending order.
  std::vector<int> near(const geom::Box& box) const {
    std::vector<int> out;
    for_cells(box, [&](std::int64_t key) {
      if (auto it = cells_.find(key); it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  static geom::Box box_of(const geom::Ring& ring) {
    geom::Box b = geom::Box::none();
    for (Vec2 p : ring) b.add(p);
    return b;
  }

 private:
  template <typename F>
  void for_cells(const geom::Box& b, F&& f) const {
    const auto lo_x = static_cast<std::int64_t>(std::floor(b.min_x / cell_)),
               hi_x = static_cast<std::int64_t>(std::floor(b.max_x / cell_));
    const auto lo_y = static_cast<std::int64_t>(std::floor(b.min_y / cell_)),
               hi_y = static_cast<std::int64_t>(std::floor(b.max_y / cell_));
    for (auto x = lo_x; x <= hi_x; ++x)
      for (auto y = lo_y; y <= hi_y; ++y) f(x * 0x100000 + y);
  }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

bool meets_any(const geom::Ring& ring, const std::vector<int>& near, const std::vector<const geom::Ring*>& rings) {
  return std::any_of(near.begin(), near.end(), [&](int i) { return geom::rings_meet(ring, *rings[i]); });
}

// The clutter kept so far: its bases, which no other base may meet, and its crowns and lamp
// heads, under which a head may not hang within kCrownClearance of a crown. The pieces are
// `kept`'s, whose bases it reads there (a copy of each was tens of MB of the 10 km city's).
class TakenClutter {
 public:
  explicit TakenClutter(const std::vector<Clutter>& kept) : kept_(kept) {}
  // Why a piece with this base and canopy cannot stand (kOtherClutter, kNearCrown), or null.
  const char* refuses(const geom::Ring& base, const Canopy& c) const {
    if (meets_base(base)) return kOtherClutter;
    if (near_crown(c)) return kNearCrown;
    return nullptr;
  }
  // Takes the piece last put into `kept`, whose canopy is c.
  void take_last(const Canopy& c) {
    const int i = static_cast<int>(kept_.size()) - 1;
    bases_.add(kept_[static_cast<std::size_t>(i)].instance.polygon.outer, i);
    if (c.part == Canopy::kNone) return;
    const double r = c.radius + kCrownClearance;
    crowns_.add({{c.centre.x - r, c.centre.y - r}, {c.centre.x + r, c.centre.y + r}}, static_cast<int>(canopies_.size()));
    canopies_.push_back(c);
  }

 private:
  bool meets_base(const geom::Ring& ring) const {
    const std::vector<int> near = bases_.near(RingBuckets::box_of(ring));
    return std::any_of(near.begin(), near.end(), [&](int i) {
      return geom::rings_meet(ring, kept_[static_cast<std::size_t>(i)].instance.polygon.outer);
    });
  }
  bool near_crown(const Canopy& c) const {
    if (c.part == Canopy::kNone) return false;
    const double r = c.radius + kCrownClearance;
    const std::vector<int> near = crowns_.near({c.centre.x - r, c.centre.y - r, c.centre.x + r, c.centre.y + r});
    return std::any_of(near.begin(), near.end(), [&](int i) {
      const Canopy& o = canopies_[i];
      return o.part != c.part && o.low - kCrownClearance < c.high && c.low - kCrownClearance < o.high &&
             geom::distance(o.centre, c.centre) < o.radius + c.radius + kCrownClearance;
    });
  }

  const std::vector<Clutter>& kept_;
  RingBuckets bases_{8}, crowns_{8};
  std::vector<Canopy> canopies_;
};

// A model's canopy where the placement puts it, over its floor.
Canopy placed(const Canopy& local, const Placement& p, double floor) {
  Canopy c = local;
  if (c.part == Canopy::kNone) return c;
  const Vec3 low = p.apply({local.centre.x, local.centre.y, local.low}, floor);
  c.centre = {low[0], low[1]}, c.low = low[2];
  c.radius = local.radius * p.scale, c.high = floor + local.high * p.scale;
  return c;
}

// Whether an entry stands at a station (Dresser::dress).
enum Fit { kNotHere, kNotNow, kHere };

// What lies at a spot, decided exactly: a lot (its index), a sidewalk, or why neither.
struct Where {
  int lot = -1;
  bool sidewalk = false;
  const char* blocked = nullptr;  // why it is no place for clutter
  std::optional<ZoneType> zone;   // the zone there, where the map knows one
  bool park = false;              // open land of a park zone: no ground for street clutter, but for park trees
  bool ok() const { return !blocked; }
};

// The city the clutter stands in, with indices to find lots and footprints near a spot.
class StandingGround {
 public:
  StandingGround(const ClutterGround& g, const std::vector<ZoneFeature>& zones)
      : g_(g), zones_(zones), lot_rings_(32), footprints_(8) {
    // The ground's lots are the city's, in order, as rounded.
    for (std::size_t i = 0; i < g.ground.lots.size(); ++i) lot_rings_.add(g.ground.lots[i].polygon.outer, static_cast<int>(i));
    auto add = [&](const geom::Polygon& p) {
      footprints_.add(p.outer, static_cast<int>(footprint_rings_.size()));
      footprint_rings_.push_back(&p.outer);
    };
    for (const Building& b : g.buildings) add(b.polygon);
    for (const ModelInstance& m : g.models) add(m.polygon);
  }

  Where at(Vec2 p) const {
    for (int i : lot_rings_.near({p.x, p.y, p.x, p.y}))
      if (g_.map.lot_cells[i].contains(p)) return {i, false, nullptr, g_.ground.lots[i].zone};
    const int label = g_.map.faces.label_at(p);
    if (label < 0) return {-1, false, kOnEdge, std::nullopt};
    const FaceLabel& l = g_.map.labels[label];
    Where w;
    if (l.zone >= 0) w.zone = zones_[l.zone].type;
    if (l.bridge || l.cover == Cover::Water)
      w.blocked = kOnWater;
    else if (l.cover == Cover::Road && l.surface == RoadSurface::Sidewalk)
      w.sidewalk = true;
    else if (l.cover == Cover::Road)
      w.blocked = kOnRoad;
    else
      w.blocked = kNoGround, w.park = l.cover == Cover::Zone && w.zone == ZoneType::Park;
    return w;
  }

  // Why the base cannot stand where `w` says its spot is; null when it can.
  const char* refuse(const geom::Ring& base, const Where& w) const {
    if (geom::ring_orientation(base) != 1) return kBaseLeaves;  // too small to stay a ring on the grid
    if (w.sidewalk || w.park) {
      for (Vec2 p : base) {
        const Where c = at(p);
        if (w.sidewalk ? !c.sidewalk : !c.park) return kBaseLeaves;
      }
      // A park's open land may hold mapped buildings; no road surface does.
      if (w.park && meets_any(base, footprints_.near(RingBuckets::box_of(base)), footprint_rings_)) return kBuilding;
      return nullptr;
    }
    if (!g_.map.lot_cells[w.lot].holds(base)) return kBaseLeaves;
    if (meets_any(base, footprints_.near(RingBuckets::box_of(base)), footprint_rings_)) return kBuilding;
    return nullptr;
  }

 private:
  const ClutterGround& g_;
  const std::vector<ZoneFeature>& zones_;
  RingBuckets lot_rings_, footprints_;
  std::vector<const geom::Ring*> footprint_rings_;
};

// The clutter one street or junction proposes, before it is checked against the others'.
struct Proposals {
  std::vector<Clutter> items;
  ClutterTally tally;
};

// Places clutter for one street or junction: picks each spot's model, tries the spot and a
// few shifted ones, checks each exactly, and counts the spots that find no place.
class Dresser {
 public:
  Dresser(const StandingGround& side, const ModelLibrary& lib, const std::vector<Base>& bases,
          const std::vector<Canopy>& canopies, const Channels& channels, const Terrain* terrain, Random& rng,
          Proposals& out)
      : side_(side), lib_(lib), bases_(bases), canopies_(canopies), channels_(channels), terrain_(terrain), rng_(rng),
        out_(out), taken_(out.items) {}

  // Park trees stand on a park's open land, where street clutter finds no ground.
  void in_parks() { parks_ = true; }

  // Whether the library has entries of the kind.
  bool has(ModelKind kind) const { return !of_kind(kind).empty(); }

  // A model of `kind` for the spot: the spot is `from` plus `out` times (the model's offset
  // from the kerb), tried again moved by each of `shifts` along `shift`; its front faces
  // `front`. `fits(model, zone)` says whether an entry may stand here (kHere), stands in the
  // zone there but not at this station (kNotNow: the other side's turn), or not (kNotHere).
  // Returns the spacing the chosen model keeps; 0 when no entry stands in the zone there.
  template <typename Fits>
  double dress(ModelKind kind, Vec2 from, Vec2 out, Vec2 shift, std::initializer_list<double> shifts, Vec2 front,
               int road, Fits&& fits) {
    const std::vector<int> kind_models = of_kind(kind);
    if (kind_models.empty()) return 0;
    const Vec2 probed = geom::snap(from + out * lib_.models[kind_models[0]].offset);
    const Where probe = side_.at(probed);
    if (!probe.zone) return 0;
    std::vector<int> models;
    double later = 0;  // the spacing of an entry that stands here at another station
    for (int m : kind_models) {
      const Fit fit = fits(lib_.models[m], *probe.zone);
      if (fit == kHere)
        models.push_back(m);
      else if (fit == kNotNow && later == 0)
        later = lib_.models[m].spacing;
    }
    if (models.empty()) return later;
    const Vec2 nominal = geom::snap(from + out * lib_.models[models[0]].offset);
    const std::optional<int> drawn = pick(choices_at(models, lib_, &channels_, nominal), rng_);
    const char* why = nullptr;
    if (!drawn) {
      miss(kind, kChannels);
      return lib_.models[models[0]].spacing;
    }
    const int m = *drawn;
    const Model& model = lib_.models[m];
    const double scale = rng_.uniform(model.min_scale, model.max_scale);
    const int tint = static_cast<int>(rng_.next() % kTints);
    for (double s : shifts) {
      const Vec2 spot = geom::snap(from + out * model.offset + shift * s);
      // The probe's answer where the spot is the probe: a point location less per spot.
      const Where w = spot == probed ? probe : side_.at(spot);
      if (!w.ok() && !(parks_ && w.park)) {
        why = why ? why : w.blocked;
        // Open land or water a metre or two on is open land or water still, mostly: move on
        // without more point locations (each a walk through the map).
        if (w.blocked == kNoGround || w.blocked == kOnWater) break;
        continue;
      }
      Clutter c = made_at(m, spot, front, scale, tint, road);
      c.instance.lot = w.lot;
      if (const char* refused = side_.refuse(c.instance.polygon.outer, w)) {
        why = why ? why : refused;
        continue;
      }
      if (terrain_) std::tie(c.instance.base, c.instance.floor) = terrain_->range_under(c.instance.polygon.outer);
      const Canopy canopy = placed(canopies_[m], c.instance.placed, c.instance.floor);
      if (const char* refused = taken_.refuses(c.instance.polygon.outer, canopy)) {
        why = why ? why : refused;
        continue;
      }
      if (w.zone) c.instance.zone = *w.zone;
      out_.items.push_back(std::move(c));
      taken_.take_last(canopy);
      ++out_.tally.placed[name(kind)];
      return model.spacing;
    }
    miss(kind, why);
    return model.spacing;
  }

 private:
  std::vector<int> of_kind(ModelKind kind) const {
    std::vector<int> out;
    for (std::size_t i = 0; i < lib_.models.size(); ++i)
      if (lib_.models[i].kind == kind) out.push_back(static_cast<int>(i));
    return out;
  }

  void miss(ModelKind kind, const char* why) { ++out_.tally.missed[{name(kind), why}]; }

  // Model m standing at the spot, its front towards `front`: the turn that takes the
  // model's front (-y) there, its origin placed so that its base's centre is on the spot.
  Clutter made_at(int m, Vec2 spot, Vec2 front, double scale, int tint, int road) const {
    const Base& b = bases_[m];
    const double angle = std::atan2(front.x, -front.y), c = std::cos(angle) * scale, s = std::sin(angle) * scale;
    Placement p{m,
                {spot.x - (c * b.centre.x - s * b.centre.y), spot.y - (s * b.centre.x + c * b.centre.y)},
                angle,
                scale,
                tint};
    geom::Ring ring;
    for (Vec2 v : b.ring) {
      const Vec2 w = geom::snap(Vec2{p.position.x + c * v.x - s * v.y, p.position.y + s * v.x + c * v.y});
      if (ring.empty() || !(w == ring.back())) ring.push_back(w);
    }
    while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    Clutter out;
    out.instance = made(lib_.models[m], p, std::move(ring));
    out.spot = spot;
    out.road = road;
    // To a hundredth of a degree in [-180, 180], then into [0, 360) (at most 359.99; + 0.0
    // turns a -0 into 0).
    const double heading = std::round(std::atan2(front.y, front.x) * 18000 / M_PI) / 100;
    out.heading = (heading < 0 ? heading + 360 : heading) + 0.0;
    return out;
  }

  const StandingGround& side_;
  const ModelLibrary& lib_;
  const std::vector<Base>& bases_;
  const std::vector<Canopy>& canopies_;
  const Channels& channels_;
  const Terrain* terrain_;
  Random& rng_;
  Proposals& out_;
  TakenClutter taken_;
  bool parks_ = false;
};

bool stands_in(const Model& m, ZoneType zone) {
  return std::find(m.zones.begin(), m.zones.end(), zone) != m.zones.end();
}

// Along one centre line, each side: lamps, benches and hydrants every `spacing`, trees along
// residential streets; none within a junction's reach of a node where three or more lines
// meet, where traffic lights and signs stand. Each side counts its stations from half a
// spacing in; a model whose `side` is alternate stands on the left at even stations and on
// the right at odd ones, so along the street it stands on each side in turn.
// Where along a centre line (from, to) a spot a street's clutter probes, up to `reach` off
// the line, may lie in one of the boxes: elsewhere no zone is there and no station can
// dress. A highway runs on far past the zones (up to 2e10 m), and walking it a station at a
// time would take as long as it is long. Sorted and disjoint.
std::vector<std::pair<double, double>> stretches_near(const geom::Polyline& line, const std::vector<double>& at,
                                                      const std::vector<geom::Box>& boxes, double reach) {
  std::vector<std::pair<double, double>> near;
  for (std::size_t k = 1; k < line.size(); ++k) {
    const Vec2 a = line[k - 1], d = line[k] - line[k - 1];
    const double len = at[k] - at[k - 1];
    for (const geom::Box& b : boxes) {
      // The segment's part within the box grown by `reach` (Liang and Barsky's clipping).
      double lo = 0, hi = 1;
      auto clip = [&](double p, double q) {  // keep p * s <= q
        if (p == 0) return q >= 0;
        const double s = q / p;
        if (p < 0) lo = std::max(lo, s); else hi = std::min(hi, s);
        return lo <= hi;
      };
      if (clip(-d.x, a.x - (b.min_x - reach)) && clip(d.x, b.max_x + reach - a.x) &&
          clip(-d.y, a.y - (b.min_y - reach)) && clip(d.y, b.max_y + reach - a.y))
        near.push_back({at[k - 1] + lo * len - reach, at[k - 1] + hi * len + reach});
    }
  }
  std::sort(near.begin(), near.end());
  std::vector<std::pair<double, double>> merged;
  for (const auto& iv : near)
    if (!merged.empty() && iv.first <= merged.back().second)
      merged.back().second = std::max(merged.back().second, iv.second);
    else
      merged.push_back(iv);
  return merged;
}

void dress_street(const RoadLine& road, int id, const std::unordered_map<Vec2, double, geom::Vec2Hash>& junction_reach,
                  const std::vector<geom::Box>& zone_boxes, const ModelLibrary& lib, Dresser& dresser) {
  const geom::Polyline& line = road.line;
  std::vector<double> at(line.size(), 0);  // distance along the line to each vertex
  for (std::size_t i = 1; i < line.size(); ++i) at[i] = at[i - 1] + geom::distance(line[i - 1], line[i]);
  std::vector<std::pair<double, double>> kept_clear;  // (from, to) along the line
  for (std::size_t i = 0; i < line.size(); ++i)
    if (auto it = junction_reach.find(line[i]); it != junction_reach.end())
      kept_clear.push_back({at[i] - it->second, at[i] + it->second});
  const double length = at.back();
  double offset = 0;
  for (const Model& m : lib.models) offset = std::max(offset, std::abs(m.offset));
  const std::vector<std::pair<double, double>> near_zones =
      stretches_near(line, at, zone_boxes, road.width / 2 + offset + 1);
  for (ModelKind kind : {ModelKind::Lamp, ModelKind::Bench, ModelKind::Hydrant, ModelKind::Tree}) {
    if (!dresser.has(kind)) continue;
    double first = 0;
    for (const Model& m : lib.models)
      if (m.kind == kind) first = first > 0 ? std::min(first, m.spacing / 2) : m.spacing / 2;
    for (int side : {1, -1}) {
      int station = 0;
      for (double t = first; t < length;) {
        auto clear =
            std::find_if(kept_clear.begin(), kept_clear.end(), [&](auto iv) { return iv.first <= t && t < iv.second; });
        if (clear != kept_clear.end()) {
          t = clear->second;
          continue;
        }
        // Far from every zone: on to the first station by one, or in a stretch kept clear, in
        // the steps the stations between would have taken (each finds no zone: two halves).
        auto zone = std::find_if(near_zones.begin(), near_zones.end(), [&](auto iv) { return t < iv.second; });
        if (zone == near_zones.end()) break;
        if (t < zone->first && first > 0) {
          double to = zone->first;
          for (const auto& iv : kept_clear)
            if (iv.first > t) to = std::min(to, iv.first);
          const double stations = std::ceil((to - t) / (first * 2));
          t += stations * first * 2, station += static_cast<int>(std::fmod(stations, 2));
          continue;
        }
        std::size_t k = 1;
        while (k + 1 < line.size() && at[k] < t) ++k;
        const Vec2 u = geom::unit_along(line[k - 1], line[k]);
        const Vec2 centre =
            geom::lerp(line[k - 1], line[k], at[k] > at[k - 1] ? (t - at[k - 1]) / (at[k] - at[k - 1]) : 0);
        const Vec2 out = Vec2{-u.y, u.x} * side;
        const bool left = side > 0, even = station % 2 == 0;
        const double spacing =
            dresser.dress(kind, centre + out * (road.width / 2), out, u, {0, 1, -1, 2, -2}, out * -1, id,
                          [&](const Model& m, ZoneType z) {
                            if (!stands_in(m, z) || (kind == ModelKind::Tree && z != ZoneType::Residential))
                              return kNotHere;
                            return m.side == StreetSide::Both || even == left ? kHere : kNotNow;
                          });
        // No entry for the zone here: look again a station further on.
        t += spacing > 0 ? spacing : first * 2;
        ++station;
      }
    }
  }
}

// The direction halfway round from a to b, counter-clockwise, and the angle between them.
std::pair<Vec2, double> halfway(Vec2 a, Vec2 b) {
  double turn = std::atan2(geom::cross(a, b), geom::dot(a, b));
  if (turn <= 0) turn += 2 * M_PI;
  const double mid = std::atan2(a.y, a.x) + turn / 2;
  return {{std::cos(mid), std::sin(mid)}, turn};
}

// A junction of major roads gets a traffic light at each corner between neighbouring arms,
// facing the junction; a local road meeting a major one gets a stop sign on its approach, on
// the right of the traffic coming in, facing it.
void dress_junction(const StreetJunction& j, Dresser& dresser) {
  const double reach = j.reach();
  const auto any_zone = [](const Model& m, ZoneType z) { return stands_in(m, z) ? kHere : kNotHere; };
  if (j.of_major_roads()) {
    for (std::size_t i = 0; i < j.arms.size(); ++i) {
      const RoadArm &a = j.arms[i], &b = j.arms[(i + 1) % j.arms.size()];
      const auto [bisector, turn] = halfway(a.toward, b.toward);
      Vec2 corner = j.at + bisector * std::max(a.half_width, b.half_width);
      if (turn > 0.2 && turn < M_PI - 0.2) {
        // A real corner: where the kerbs on its two sides meet, which is where a mitred
        // junction's surface turns (docs/design.md, Exactness rule 3).
        const Vec2 p = j.at + Vec2{-a.toward.y, a.toward.x} * a.half_width;
        const Vec2 q = j.at + Vec2{b.toward.y, -b.toward.x} * b.half_width;
        corner = p + a.toward * (geom::cross(q - p, b.toward) / geom::cross(a.toward, b.toward));
      }
      dresser.dress(ModelKind::TrafficLight, corner, bisector * std::sqrt(2.0), bisector, {0, 0.5, 1, 1.5, 2.5},
                    bisector * -1, a.road, any_zone);
    }
    return;
  }
  if (!j.local_meets_major()) return;
  for (const RoadArm& a : j.arms) {
    if (is_major(a.road_class)) continue;
    const Vec2 right_of_incoming{-a.toward.y, a.toward.x};
    dresser.dress(ModelKind::Sign, j.at + a.toward * (reach + 2) + right_of_incoming * a.half_width, right_of_incoming,
                  a.toward, {0, 1, 2, 3, 4}, a.toward, a.road, any_zone);
  }
}

// The spacing of the trees that stand in parks (the widest, as the squares are laid out);
// 0 when none do.
double park_tree_spacing(const ModelLibrary& lib) {
  double spacing = 0;
  for (const Model& m : lib.models)
    if (m.kind == ModelKind::Tree && stands_in(m, ZoneType::Park)) spacing = std::max(spacing, m.spacing);
  return spacing;
}

// The park's box in squares of `step`, row by row from its lowest corner, as dress_park
// walks them.
struct Squares {
  geom::Box box;
  double count = 0;
};
Squares squares_of(const ZoneArea& park, double step) {
  Squares s{geom::Box::none()};
  for (Vec2 p : park.polygon.outer) s.box.add(p);
  if (!s.box.holds_nothing()) s.count = std::ceil(s.box.width() / step) * std::ceil(s.box.height() / step);
  return s;
}

// Trees over a park's open land: one per square of 1.5 tree spacings, at a random place in
// it (so they stand apart but in no rows), each turned at random; a spot that is not on
// the park's open land (a road, water, a pond's hole) is tried a metre or two away.
void dress_park(const ZoneArea& park, const ModelLibrary& lib, Random& rng, Dresser& dresser) {
  const double spacing = park_tree_spacing(lib);
  if (spacing <= 0) return;
  const double step = 1.5 * spacing;
  const geom::Box box = squares_of(park, step).box;
  const auto in_park = [](const Model& m, ZoneType z) {
    return stands_in(m, ZoneType::Park) && z == ZoneType::Park ? kHere : kNotHere;
  };
  for (double y = box.min_y; y < box.max_y; y += step)
    for (double x = box.min_x; x < box.max_x; x += step) {
      const Vec2 spot{x + rng.uniform(0.15, 0.85) * step, y + rng.uniform(0.15, 0.85) * step};
      const double turn = rng.uniform(0, 2 * M_PI);
      // Doubles choose the spots worth a walk through the map; the map decides (Where).
      if (geom::winding_number(park.polygon.outer, spot) == 0) continue;
      const Vec2 front{std::cos(turn), std::sin(turn)};
      dresser.dress(ModelKind::Tree, spot, {0, 0}, front, {0, 1, -1, 2, -2}, front, -1, in_park);
    }
}

// Parks whose trees would be more than one run plants are refused before any is placed:
// each tree is an instance in every export (a park of 4.5 by 2.5 degrees took 13 GB and
// was still planting), and the squares of the parks' boxes are each walked.
void check_park_trees(const std::vector<const ZoneArea*>& parks, const ModelLibrary& lib, const CitySettings& city,
                      const std::vector<ZoneFeature>& zones) {
  const double spacing = park_tree_spacing(lib);
  if (spacing <= 0 || parks.empty()) return;
  const double step = 1.5 * spacing;
  double trees = 0, squares = 0;
  for (const ZoneArea* park : parks) trees += std::abs(geom::area(park->polygon)) / (step * step), squares += squares_of(*park, step).count;
  if (trees <= kMaxParkTrees && squares <= kMaxParkSquares) return;
  // The drawn park with the largest area, to name.
  const ZoneFeature* largest = nullptr;
  double largest_area = -1;
  for (const ZoneFeature& z : zones) {
    if (z.type != ZoneType::Park) continue;
    double area = 0;
    for (const geom::Polygon& p : z.polygons) area += std::abs(geom::area(p));
    if (area > largest_area) largest_area = area, largest = &z;
  }
  const std::string feature = !largest                    ? std::string("the parks")
                              : !largest->source.empty()    ? largest->source
                              : !largest->grid_cell.empty() ? "grid map cell " + largest->grid_cell
                                                            : "features[" + std::to_string(largest->index) + "]";
  auto count = [](double n) { return std::to_string(static_cast<long long>(std::round(n))); };
  const std::string what = trees > kMaxParkTrees
                               ? "would plant about " + count(trees) + " trees, more than the " + count(kMaxParkTrees) + " one run plants"
                               : "span about " + count(squares) + " squares of a tree in their boxes, more than the " +
                                     count(kMaxParkSquares) + " one run walks";
  // A library of built-in models only has no file (builtin_models.h).
  const std::string fix = lib.file.empty()
                              ? "raise the trees' \"spacing\" in a model library of your own, or leave \"tree\" out of "
                                "\"exacity\".builtin_models"
                              : "raise the \"spacing\" of the trees in " + lib.file.string() +
                                    " that stand in parks, or leave \"park\" out of their \"zones\"";
  throw UserError(city.path.string() + ": " + feature + " (park): the parks " + what + " (a tree to a square of " +
                  format_number(step) + " m, 1.5 times the park trees' spacing); draw smaller parks, " + fix);
}

}  // namespace

StandingMap standing_map(const CityMap& map, const std::vector<Lot>& lots) {
  StandingMap out;
  out.faces = map.map.face_locator(), out.labels = map.labels;
  out.lot_cells.reserve(lots.size());
  for (const Lot& lot : lots) out.lot_cells.push_back(lot.cell);
  return out;
}

StreetClutter place_clutter(const ClutterGround& ground, const ModelLibrary* library, const Channels& channels,
                            const CitySettings& city, const std::vector<ZoneFeature>& zones, const Terrain* terrain) {
  StreetClutter out;
  if (!library ||
      std::none_of(library->models.begin(), library->models.end(), [](const Model& m) { return is_clutter(m.kind); }))
    return out;
  std::vector<Base> bases;
  std::vector<Canopy> canopies;
  for (const Model& m : library->models) bases.push_back(base_of(m)), canopies.push_back(canopy_of(m, bases.back()));
  const StandingGround side(ground, zones);
  const std::vector<RoadLine>& roads = ground.ground.roads;
  const std::vector<StreetJunction> junctions = street_junctions(roads);
  // Streets keep clear of a junction's surface and of the clutter at its corners.
  std::unordered_map<Vec2, double, geom::Vec2Hash> junction_reach;
  for (const StreetJunction& j : junctions) junction_reach[j.at] = j.reach() + 3;

  // What a street's stations probe stands in a drawn zone, or none is there.
  std::vector<geom::Box> zone_boxes;
  for (const ZoneFeature& z : zones)
    for (const geom::Polygon& p : z.polygons) zone_boxes.push_back(RingBuckets::box_of(p.outer));

  std::vector<const ZoneArea*> parks;
  for (const ZoneArea& z : ground.ground.zones)
    if (z.type == ZoneType::Park) parks.push_back(&z);
  check_park_trees(parks, *library, city, zones);

  // Each street, then each junction, then each park proposes its own clutter in parallel,
  // checked against the ground and its own; then in that order each is checked against the
  // clutter kept.
  const std::size_t streets_and_junctions = roads.size() + junctions.size();
  const std::size_t groups = streets_and_junctions + parks.size();
  std::vector<Proposals> proposed(groups);
  const std::uint64_t stage = mix(city.seed, static_cast<std::uint64_t>(Stage::Clutter));
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), groups, [&](std::size_t g) {
    cancel.check();
    Random rng(mix(stage, g));
    Dresser dresser(side, *library, bases, canopies, channels, terrain, rng, proposed[g]);
    if (g < roads.size()) {
      if (!roads[g].bridge) dress_street(roads[g], static_cast<int>(g), junction_reach, zone_boxes, *library, dresser);
    } else if (g < streets_and_junctions) {
      dress_junction(junctions[g - roads.size()], dresser);
    } else {
      dresser.in_parks();
      dress_park(*parks[g - streets_and_junctions], *library, rng, dresser);
    }
  });
  // Each group's proposals freed once its pieces are kept or refused, and the kept ones
  // moved into room made for them all at once: the proposals, the pieces kept and their
  // vector's copies as it grew were all held together, at the top of the 10 km city's
  // memory.
  std::size_t proposed_pieces = 0;
  for (const Proposals& p : proposed) proposed_pieces += p.items.size();
  out.items.reserve(proposed_pieces);
  TakenClutter kept(out.items);
  for (Proposals& p : proposed) {
    for (auto& [kind, n] : p.tally.placed) out.tally.placed[kind] += n;
    for (auto& [why, n] : p.tally.missed) out.tally.missed[why] += n;
    for (Clutter& c : p.items) {
      const geom::Ring& ring = c.instance.polygon.outer;
      const Canopy canopy = placed(canopies[static_cast<std::size_t>(c.instance.placed.model)], c.instance.placed,
                                   c.instance.floor);
      if (const char* refused = kept.refuses(ring, canopy)) {
        const std::string kind(name(c.instance.kind));
        --out.tally.placed[kind];
        ++out.tally.missed[{kind, refused}];
        continue;
      }
      c.instance.id = static_cast<int>(out.items.size());
      out.items.push_back(std::move(c));
      kept.take_last(canopy);
    }
    p = {};
  }
  for (auto it = out.tally.placed.begin(); it != out.tally.placed.end();)
    it = it->second == 0 ? out.tally.placed.erase(it) : std::next(it);
  // Each piece's id in the outputs (stable_ids.h), from what clutter.geojson writes of it.
  std::vector<std::uint64_t> hashes;
  for (const Clutter& c : out.items)
    hashes.push_back(ContentHash(static_cast<std::uint64_t>(c.instance.kind))
                         .add(c.instance.placed.model).add(c.spot).add(c.heading).value());
  const std::vector<int> ids = stable_ids(hashes);
  for (std::size_t i = 0; i < out.items.size(); ++i) out.items[i].instance.stable_id = ids[i];
  return out;
}

}  // namespace exacity
