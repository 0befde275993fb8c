#include "generate/placement/buildings.h"

#include <algorithm>
#include <map>
#include <cmath>
#include <tuple>

#include <tbb/parallel_for.h>

#include "generate/cancel.h"
#include "generate/city/stable_ids.h"
#include "generate/errors.h"
#include "generate/placement/building_settings.h"
#include "generate/city/format_number.h"
#include "generate/placement/grid_filling.h"
#include "generate/placement/model_placement.h"
#include "generate/placement/perimeter.h"
#include "generate/placement/placer.h"
#include "geom/grid.h"
#include "geom/measure.h"
#include "geom/polygon_check.h"

namespace exacity {

Vec3 Placement::apply(Vec3 v, double floor) const {
  const double c = std::cos(angle) * scale, s = std::sin(angle) * scale;
  return {position.x + c * v[0] - s * v[1], position.y + s * v[0] + c * v[1], floor + scale * v[2]};
}

double building_height(const BuildingSettings& p, double near_centre, Random& rng) {
  double scale = 0.5 + 0.5 * near_centre;
  double top = p.max_height * scale;
  if (rng.uniform() < 0.1 * near_centre * near_centre) top *= 2;  // a rare tower near the centre
  double h = rng.uniform(p.min_height * scale, std::max(top, p.min_height * scale));
  return std::round(h * 100) / 100;  // centimetres
}

namespace {

// Four corners, each within 10 degrees of square.
bool near_rectangle(const geom::Polygon& p) {
  if (p.outer.size() != 4 || !p.holes.empty()) return false;
  for (int i = 0; i < 4; ++i) {
    geom::Vec2 a = p.outer[(i + 3) % 4], o = p.outer[i], c = p.outer[(i + 1) % 4];
    double ux = a.x - o.x, uy = a.y - o.y, wx = c.x - o.x, wy = c.y - o.y;
    double cosine = (ux * wx + uy * wy) / (std::hypot(ux, uy) * std::hypot(wx, wy));
    if (std::abs(cosine) > std::sin(10 * M_PI / 180)) return false;
  }
  return true;
}

// The piece's rings, rounded, in the frontage's frame: x along it, y across (into the lot).
std::vector<geom::Ring> rings_in_frame(const geom::Cell& piece, const Frontage& f) {
  std::vector<geom::Ring> out;
  for (const geom::KindedRing& r : piece.kinded_rings()) {
    geom::Ring& ring = out.emplace_back();
    for (geom::Vec2 v : r.points) ring.push_back({geom::dot(v - f.a, f.u), geom::dot(v - f.a, f.n)});
  }
  return out;
}

// Whether the frame's rectangle [x0, x1] by [y0, y1] surely does not lie inside the piece
// (`rings`, rings_in_frame): an edge runs through it two grid steps in from its sides, or
// its centre lies outside. In doubles: the margin is beyond what moves the rectangle and the
// piece here (snapping the rectangle's corners to the grid moves them up to 0.7 mm; rounding
// the piece's vertices and the frame, nanometres), so where this says so the exact test says
// so too, and nothing else it says is taken as an answer.
bool surely_not_inside(const std::vector<geom::Ring>& rings, double x0, double x1, double y0, double y1) {
  constexpr double kMargin = 2 * geom::kGridStep;
  const double xs = x0 + kMargin, xe = x1 - kMargin, ys = y0 + kMargin, ye = y1 - kMargin;
  if (!(xs < xe && ys < ye)) return false;
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  bool inside = false;
  for (const geom::Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const geom::Vec2 p = ring[i], q = ring[(i + 1) % ring.size()];
      // The x the edge spans within the strip ys..ye.
      const double lo = std::max(ys, std::min(p.y, q.y)), hi = std::min(ye, std::max(p.y, q.y));
      if (lo <= hi) {
        double xl = std::min(p.x, q.x), xh = std::max(p.x, q.x);
        if (p.y != q.y) {
          const double a = p.x + (q.x - p.x) * (lo - p.y) / (q.y - p.y), b = p.x + (q.x - p.x) * (hi - p.y) / (q.y - p.y);
          xl = std::min(a, b), xh = std::max(a, b);
        }
        if (xl <= xe && xh >= xs) return true;
      }
      if ((p.y > cy) != (q.y > cy) && cx < p.x + (q.x - p.x) * (cy - p.y) / (q.y - p.y)) inside = !inside;
    }
  return !inside;
}

// A footprint's sides before it is placed: as drawn, or in other shapes of its area.
struct Size {
  double w = 0, d = 0;
};

// A footprint's sides drawn from the zone's ranges and, with footprint_areas, its area
// from their distribution (linear between its steps) in the shape drawn; no larger than
// max_footprint_area.
Size draw_size(const BuildingSettings& p, Random& rng) {
  double w = rng.uniform(p.footprint_width.min, p.footprint_width.max);
  double d = rng.uniform(p.footprint_depth.min, p.footprint_depth.max);
  if (!p.footprint_areas.empty()) {
    const double s = std::sqrt(draw_from_steps(p.footprint_areas, rng) / (w * d));
    w *= s, d *= s;
  }
  if (w * d > p.max_footprint_area) {
    const double s = std::sqrt(p.max_footprint_area / (w * d));
    w *= s, d *= s;
  }
  return {w, d};
}

// The mean of draw_from_steps' distribution: each interval between steps is drawn alike,
// uniformly within it.
double mean_of_steps(const std::vector<double>& steps) {
  double sum = 0;
  for (std::size_t i = 0; i + 1 < steps.size(); ++i) sum += (steps[i] + steps[i + 1]) / 2;
  return sum / static_cast<double>(steps.size() - 1);
}

// What filling a lot's rows gave: its footprints, and with footprint_areas the sizes they
// were placed from, in order, and past those the one that fitted nowhere if any.
struct Rows {
  std::vector<geom::Ring> rings;
  std::vector<Size> sizes;
  std::size_t placed = 0;
  bool failed() const { return sizes.size() > placed; }
};

// Rectangles in a row along the lot's street frontage, fronts `setback` behind the street
// (rows facing the road), each `footprint_width` by `footprint_depth` and no
// larger than `max_footprint_area`, `building_gap` apart and half that inside the lot's
// other edges; where one does not fit, a smaller one is tried, down to
// `min_footprint_width`. With `footprint_areas`, a drawn area that does not fit as drawn is
// tried at the same area, wider and shallower or narrower and deeper (a lot's frontage
// or depth, not its land, is what a large footprint misses), and else at the next places
// along the rows, never smaller; one that fits nowhere on the lot ends its footprints.
// `given` (street_footprints) are the sizes to place, all of them and no others; without
// them sizes are drawn, and with `lot_coverage` rows follow behind the first, each
// `building_gap` behind the deepest of the row before (a row with no room a step behind
// it), while the footprints cover less than that share of the lot (the first row too stops
// there) and the lot is deep enough. Each is checked exactly against the lot and the
// footprints taken.
Rows fill_rows(Occupancy& occupancy, const BuildingSettings& p, Random& rng, const std::vector<geom::Ring>& frame,
               const std::vector<Size>* given) {
  Rows out;
  const Frontage& f = occupancy.frontage();
  const double clearance = std::max(p.building_gap / 2, 0.05), setback = std::max(p.setback, 0.1);
  const double wanted = p.lot_coverage * occupancy.piece().area();
  double covered = occupancy.standing_m2();  // mapped footprints on the lot count as covered
  auto rectangle = [&](double front, double t, double w, double d, double grow) {
    const double ahead = std::min(grow, setback / 2);
    geom::Ring r;
    for (auto [along, across] : {std::pair{t - grow, front - ahead}, {t + w + grow, front - ahead},
                                 {t + w + grow, front + d + grow}, {t - grow, front + d + grow}})
      r.push_back(geom::snap(f.at(along, across)));
    return r;
  };
  // With footprint_areas, a drawn size that fits nowhere yet waits for the next place
  // along the rows rather than shrinking: shrunk, the place's large footprints became the
  // narrowest allowed (a spike at min_footprint_width squared, and no tail).
  const bool areas = !p.footprint_areas.empty();
  bool waiting = false;
  auto done = [&](bool first) {
    return given ? out.placed == given->size() : (wanted > 0 || !first) && covered >= wanted;
  };
  // Past a place where nothing fits: a metre on with footprint_areas (the place's sizes,
  // whose gaps would otherwise open wherever one waits), else a quarter of the narrowest
  // (as a row with no room is passed: a metre there costs rows times places).
  const double passed = std::max(p.min_footprint_width / 4, 1.0);  // how far a row with no room is passed
  const double step = areas ? 1.0 : passed;
  // One row, its fronts `front` behind the street; how deep its deepest footprint is (0: none).
  auto row = [&](double front, bool first) {
    double deepest = 0;
    for (double t = f.t0 + clearance; t + p.min_footprint_width <= f.t1;) {
      if (done(first)) break;
      const Size drawn = waiting ? out.sizes.back() : given ? (*given)[out.sizes.size()] : draw_size(p, rng);
      const double w = drawn.w, d = drawn.d;
      if (areas && !waiting) out.sizes.push_back(drawn), waiting = true;
      // The drawn size (with footprint_areas, then its area in other shapes; without, then
      // smaller ones, down to the narrowest allowed).
      const double m = p.min_footprint_width;
      if (areas) {
        const double narrowest = std::max(w / 2, m), shallowest = std::max(d / 2, m);
        if (surely_not_inside(frame, t - clearance, t + narrowest + clearance, front - std::min(clearance, setback / 2),
                              front + shallowest + clearance)) {
          t += step;
          continue;
        }
      }
      std::vector<std::pair<double, double>> shapes{{w, d}};
      if (areas) for (double k : {1.25, 1.6, 2.0}) shapes.insert(shapes.end(), {{w * k, d / k}, {w / k, d * k}});
      else shapes.insert(shapes.end(), {{0.8 * w, 0.8 * d}, {0.64 * w, 0.64 * d}, {0.5 * w, 0.5 * d}, {m, 0.5 * d}, {m, m}});
      bool placed = false;
      for (auto [ws, ds] : shapes) {
        ws = std::max(ws, m), ds = std::max(ds, m);
        // Past the lot's side or its deepest corner (a millimetre's margin): outside it, untried.
        if (t + ws > f.t1 || front + ds + clearance > f.depth + 1e-3 || ws * ds < p.min_footprint_area ||
            ws * ds > p.max_footprint_area)
          continue;
        geom::Ring ring = rectangle(front, t, ws, ds, 0);
        if (!occupancy.inside(rectangle(front, t, ws, ds, clearance))) continue;
        // Mapped buildings standing on the lot are kept building_gap away from, as the row's own are.
        if (occupancy.has_standing() && !occupancy.apart_from_standing(rectangle(front, t, ws, ds, p.building_gap))) continue;
        if (!occupancy.take(ring)) continue;
        out.rings.push_back(std::move(ring));
        t += ws + p.building_gap;
        covered += ws * ds, deepest = std::max(deepest, ds);
        placed = true;
        break;
      }
      if (placed && areas) ++out.placed, waiting = false;
      if (!placed) t += step;
    }
    return deepest;
  };
  double front = setback;
  for (bool first = true;; first = false) {
    // What waited fits nowhere in this row goes on waiting in the rows behind, and where it
    // fits nowhere on the lot it ends the lot's footprints: it is not replaced by a fresh
    // draw. Replaced (the row again without it), every lot drew until an area its room
    // held came, so small lots filtered the place's sizes down to theirs: on Kotka's
    // completion the areas dropped had a median of 138 m² and those placed were drawn at 69 m² (the
    // place's 120 m²), and the generated median came out 27% under the mapped one.
    const double deepest = row(front, first);
    if (done(false)) break;
    // A row with no room (a lot's neck, a corner) may have room behind it: the next row
    // a step further back, until the lot's depth.
    front += deepest > 0 ? deepest + std::max(p.building_gap, 0.1) : passed;
    if (front + p.min_footprint_width > f.depth) break;
  }
  return out;
}

// A lot's footprints (fill_rows). With `footprint_areas` and `lot_coverage`, a lot holds a
// number of footprints drawn at once: its share of coverage (less what mapped buildings
// cover) over the areas' mean, rounded up or down at random in proportion. They are placed
// in the order drawn, else largest first; where neither holds them all, the first that
// fits nowhere in the order drawn is left out (as likely the small one as the large one of
// a pair) and the rest placed again. Drawn one at a time until the lot was covered or one
// fitted nowhere, a lot ended at its first large draw and kept every small one before it:
// on Kotka's industrial land (about three footprints a lot) the areas drawn had a median
// of 230 m² for the place's 364, and the generated median and p90 came out 32% and 43%
// under the mapped ones.
std::vector<geom::Ring> street_footprints(Occupancy& occupancy, const BuildingSettings& p, Random& rng) {
  const Frontage& f = occupancy.frontage();
  if (!f.on_road || !(f.t1 > f.t0)) return {};
  if (p.footprint_areas.empty()) return fill_rows(occupancy, p, rng, {}, nullptr).rings;
  // Places stepped a metre apart are each tried in up to seven shapes; across a large lot
  // of odd shape (open land joined to it) most lie partly outside, tens of thousands a lot.
  // A place where the smallest of the shapes, which each of them holds, surely does not lie
  // inside the lot is passed without the exact test: the same places are taken, far cheaper.
  const std::vector<geom::Ring> frame = rings_in_frame(occupancy.piece(), f);
  if (!(p.lot_coverage > 0)) return fill_rows(occupancy, p, rng, frame, nullptr).rings;
  const double share = std::max(p.lot_coverage * occupancy.piece().area() - occupancy.standing_m2(), 0.0);
  const double expected = share / mean_of_steps(p.footprint_areas);
  std::size_t count = static_cast<std::size_t>(expected);
  if (rng.uniform() < expected - static_cast<double>(count)) ++count;
  std::vector<Size> sizes;
  for (std::size_t i = 0; i < count; ++i) sizes.push_back(draw_size(p, rng));
  auto place = [&](const std::vector<Size>& list) {
    Occupancy trial = occupancy;
    return fill_rows(trial, p, rng, frame, &list);
  };
  for (;;) {
    Rows rows = place(sizes);
    if (rows.failed()) {
      std::vector<Size> largest_first = sizes;
      std::stable_sort(largest_first.begin(), largest_first.end(), [](Size a, Size b) { return a.w * a.d > b.w * b.d; });
      if (Rows again = place(largest_first); !again.failed()) rows = std::move(again);
    }
    if (!rows.failed()) {
      // Free on a copy of this occupancy, so free here.
      for (const geom::Ring& ring : rows.rings) occupancy.take(ring);
      return std::move(rows.rings);
    }
    sizes.erase(sizes.begin() + static_cast<std::ptrdiff_t>(rows.placed));
  }
}

}  // namespace

void choose_roof(Building& b, const BuildingSettings& p) {
  b.roof = "flat";
  b.eaves = b.height;
  b.roof_faces.clear();
  std::string want = p.roof;
  if (want == "auto") want = b.zone != ZoneType::Residential ? "flat" : near_rectangle(b.polygon) ? "gabled" : "hipped";
  if (want == "flat") return;
  const double slope = std::tan(p.roof_pitch * M_PI / 180);
  std::vector<geom::Face3> faces;
  if (want == "gabled") faces = geom::gabled_roof(b.polygon, 0, slope);
  if (faces.empty()) want = "hipped", faces = geom::hipped_roof(b.polygon, 0, slope);
  double rise = geom::roof_top(faces);
  if (faces.empty() || rise <= 0 || rise > b.height / 2) return;
  b.roof = want;
  b.eaves = b.height - rise;
  for (geom::Face3& f : faces)
    for (geom::Vec3& v : f) v[2] += b.eaves;
  b.roof_faces = std::move(faces);
}

namespace {

// Extruded buildings (docs/design.md, Algorithms): rectangles in a row along the street, raised to a height that falls
// with distance from the city's centre (or rises with the zone's height channel), under a
// roof.
class Extrusion : public Placer {
  // The perimeter block's footprints the lot takes: those the exact test lets stand whole,
  // courtyards included, and no smaller than min_footprint_area (with footprint_areas, no
  // larger than max_footprint_area either). The union's rings come
  // rounded to doubles and a courtyard may touch its outer ring at a vertex
  // (geom::PlanarMap::dissolve), which a building may not: both are checked here.
  static std::vector<geom::Polygon> perimeter(Occupancy& occupancy, const BuildingSettings& p) {
    std::vector<geom::Polygon> taken;
    for (geom::Polygon& footprint : perimeter_footprints(occupancy.piece(), LotEdge::kStreet, p.setback, p.perimeter_depth,
                                                         std::max(p.building_gap / 2, 0.05))) {
      const bool courtyards_inside = std::all_of(footprint.holes.begin(), footprint.holes.end(), [&](const geom::Ring& hole) {
        return geom::ring_orientation(hole) == -1 && geom::ring_is_simple(hole) &&
               std::all_of(hole.begin(), hole.end(), [&](geom::Vec2 v) { return geom::point_side(footprint.outer, v) == 1; }) &&
               std::all_of(footprint.outer.begin(), footprint.outer.end(), [&](geom::Vec2 v) { return geom::point_side(hole, v) == -1; });
      });
      // With a place's sizes, none larger: a band runs along every street edge of its lot,
      // and a lot fronting more street than a drawn frontage (joined pieces, a block's
      // corner) held bands larger than the place has; with no other band the lot is built
      // in rows of the place's footprints.
      if (!p.footprint_areas.empty() && geom::area(footprint) > p.max_footprint_area) continue;
      if (courtyards_inside && geom::area(footprint) >= p.min_footprint_area && geom::ring_is_simple(footprint.outer) &&
          occupancy.take(footprint.outer))
        taken.push_back(std::move(footprint));
    }
    return taken;
  }

 public:
  Extrusion(geom::Vec2 centre, double radius, const Channels& channels)
      : centre_(centre), radius_(radius), channels_(channels) {}
  void place(const Lot& lot, const BuildingSettings& p, Occupancy& occupancy, Random& rng, Structures& out) const override {
    std::vector<geom::Polygon> footprints;
    if (p.perimeter_depth > 0) footprints = perimeter(occupancy, p);
    if (footprints.empty())
      for (geom::Ring& ring : street_footprints(occupancy, p, rng)) footprints.push_back({std::move(ring), {}});
    const int height_channel = p.height_channel.empty() ? -1 : channels_.index(p.height_channel);
    for (geom::Polygon& footprint : footprints) {
      Building b;
      b.polygon = std::move(footprint);
      geom::Vec2 c{0, 0};
      for (geom::Vec2 v : b.polygon.outer) c = c + v * (1.0 / static_cast<double>(b.polygon.outer.size()));
      const double near_centre = height_channel >= 0 ? channels_.value(height_channel, c)
                                 : radius_ > 0 ? 1 - std::min(std::hypot(c.x - centre_.x, c.y - centre_.y) / radius_, 1.0)
                                               : 1;
      b.height = building_height(p, near_centre, rng);
      b.zone = lot.zone;
      choose_roof(b, p);
      out.buildings.push_back(std::move(b));
    }
  }

 private:
  geom::Vec2 centre_;
  double radius_;
  const Channels& channels_;
};

// Each zone type's placers, in the order they fill a lot: its buildings (the library's,
// where it has some for the zone, else extruded), then street furniture, then trees.
std::map<ZoneType, std::vector<std::unique_ptr<Placer>>> zone_placers(const CitySettings& city_settings, const ModelLibrary* library,
                                                                      const Channels& channels,
                                                                      const geom::Box& city) {
  const geom::Vec2 centre{(city.min_x + city.max_x) / 2, (city.min_y + city.max_y) / 2};
  const double radius = std::hypot(city.width(), city.height()) / 2;
  std::map<ZoneType, std::vector<std::unique_ptr<Placer>>> placers;
  for (const auto& [zone, settings] : city_settings.zone_settings) {
    auto& list = placers[zone];
    std::unique_ptr<Placer> models;
    if (library && settings.lots.layout->models_own_lots()) models = make_own_lot_placer(*library);
    else if (library) models = settings.buildings.placement->make(*library, zone, channels);
    list.push_back(models ? std::move(models) : std::make_unique<Extrusion>(centre, radius, channels));
    if (!library) continue;
    for (ModelKind kind : {ModelKind::Street, ModelKind::Tree})
      if (std::unique_ptr<Placer> p = make_model_placer(*library, zone, kind, channels)) list.push_back(std::move(p));
  }
  return placers;
}

}  // namespace

Structures place_buildings(const std::vector<Lot>& lots, const CitySettings& city, const ModelLibrary* library,
                           const Channels& channels, const Terrain* terrain, Memo<Structures>* memo,
                           const HeldLots* held) {
  geom::Box box = geom::Box::none();
  for (const Lot& lot : lots) box.add(lot.cell.bounds());
  const auto placers = zone_placers(city, library, channels, box);
  const std::uint64_t stage = mix(city.seed, static_cast<std::uint64_t>(Stage::Buildings));
  std::vector<Structures> placed(lots.size());
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), lots.size(), [&](std::size_t i) {
    cancel.check();
    const Lot& lot = lots[i];
    BuildingSettings p = city.zone_settings.at(lot.zone).buildings;
    if (!lot.density.empty()) p.density = lot.density;
    // Without lot_coverage nothing says how much more a lot a mapped building holds takes.
    const bool standing = held && held->held[i];
    if (standing && !(p.lot_coverage > 0)) return;
    // By the lot's shape, not its index, so merging lots around it, or an edit elsewhere,
    // leaves it as it was.
    const std::string cell_text = geom::exact_text(lot.cell);
    auto place = [&] {
      Random rng(mix(stage, content_id(cell_text)));
      Occupancy occupancy(lot.cell, LotEdge::kStreet, terrain);
      if (standing) occupancy.stand(held->standing[i], held->standing_m2[i]);
      Structures here;
      for (const auto& placer : placers.at(lot.zone)) placer->place(lot, p, occupancy, rng, here);
      return here;
    };
    Structures& here = placed[i];
    if (memo) {
      // Everything placing reads of the lot, and the city's box (extruded heights fall from its centre).
      std::string key = "lot zone " +
                        std::to_string(static_cast<int>(lot.zone)) + " density " + lot.density + " model " +
                        (lot.model ? std::to_string(*lot.model) : std::string("none")) + " city ";
      for (double v : {box.min_x, box.min_y, box.max_x, box.max_y}) append_key(key, v);
      key += cell_text;
      if (standing) {
        key += " standing ";
        append_key(key, held->standing_m2[i]);
        for (const geom::Ring& ring : held->standing[i]) append_key(key, ring);
      }
      here = memo->get(key, place);
    } else {
      here = place();
    }
    auto stand = [&](auto& s) {
      s.lot = static_cast<int>(i);
      s.zone = lot.zone;
      if (terrain) std::tie(s.base, s.floor) = terrain->range_under(s.polygon.outer);
    };
    for (Building& b : here.buildings) stand(b);
    for (ModelInstance& m : here.models) stand(m);
  });
  Structures all;
  int id = 0;
  for (Structures& here : placed) {
    for (Building& b : here.buildings) b.id = id++, all.buildings.push_back(std::move(b));
    for (ModelInstance& m : here.models) m.id = id++, all.models.push_back(std::move(m));
  }
  return all;
}

void give_stable_ids(std::vector<Building>& buildings, std::vector<ModelInstance>& models) {
  enum Kind : std::uint64_t { kBuilding = 1, kModel };
  std::vector<std::uint64_t> hashes;
  hashes.reserve(buildings.size() + models.size());
  for (const Building& b : buildings) {
    ContentHash h(kBuilding);
    h.add(static_cast<int>(b.zone)).add(b.polygon).add(b.height).add(std::string_view(b.roof)).add(b.mapped);
    hashes.push_back(h.value());
  }
  for (const ModelInstance& m : models) {
    ContentHash h(kModel);
    h.add(static_cast<int>(m.zone)).add(static_cast<int>(m.kind)).add(m.placed.model).add(m.placed.position);
    h.add(m.placed.angle).add(m.placed.scale).add(m.polygon).add(m.height).add(m.floor);
    hashes.push_back(h.value());
  }
  const std::vector<int> ids = stable_ids(hashes);
  for (std::size_t i = 0; i < buildings.size(); ++i) buildings[i].stable_id = ids[i];
  for (std::size_t i = 0; i < models.size(); ++i) models[i].stable_id = ids[buildings.size() + i];
}

void check_export_size(const std::vector<ModelInstance>& models, const ModelLibrary* library) {
  if (!library) return;
  std::vector<double> placed(library->models.size(), 0);
  for (const ModelInstance& m : models) ++placed[m.placed.model];
  double total = 0, heaviest = 0;
  int worst = -1;
  for (std::size_t m = 0; m < placed.size(); ++m) {
    const double triangles = placed[m] * static_cast<double>(library->models[m].mesh.triangles.size());
    total += triangles;
    if (triangles > heaviest) heaviest = triangles, worst = static_cast<int>(m);
  }
  if (total <= kMaxExportTriangles) return;
  const Model& m = library->models[worst];
  auto millions = [](double n) { return format_number(std::round(n / 1e5) / 10) + " million"; };
  // A library of built-in models only has no file (builtin_models.h).
  const std::string where = library->file.empty() ? "\"exacity\".builtin_models" : library->file.string();
  throw UserError(where + ": model \"" + m.name + "\" (" + std::to_string(m.mesh.triangles.size()) +
                  " triangles) is placed " + std::to_string(static_cast<long>(placed[worst])) +
                  " times, and the 3D exports would hold " + millions(total) + " triangles, over the " +
                  millions(kMaxExportTriangles) + " one run writes; use a lighter model or list it for fewer zones");
}

}  // namespace exacity
