#include "generate/buildings.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <tbb/parallel_for.h>

#include "generate/model_placement.h"
#include "geom/measure.h"

namespace exacity {

double building_height(const ZoneParams& p, double distance, double radius, Random& rng) {
  double near_centre = radius > 0 ? 1 - std::min(distance / radius, 1.0) : 1;
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

// The largest part of the piece inset by the setback, when it is big enough.
std::optional<Building> extruded_building(const geom::Cell& piece, const ZoneParams& p) {
  std::optional<Building> best;
  double best_area = p.min_footprint_area;
  for (geom::Cell& part : geom::inset_cell(piece, p.setback)) {
    geom::Polygon polygon = part.to_plain();
    double a = geom::area(polygon);
    if (polygon.outer.empty() || a < best_area) continue;
    best_area = a;
    best = Building{};
    best->footprint = std::move(part);
    best->polygon = std::move(polygon);
  }
  return best;
}

}  // namespace

void choose_roof(Building& b, const ZoneParams& p) {
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

std::vector<Building> place_buildings(const ZoneMap& zm, const std::vector<Lot>& lots, const Sketch& sketch,
                                      const ModelLibrary* library, const Terrain* terrain) {
  // Lots as they ended up in the map (cut back at roads), one cell per piece; edges
  // along a road surface have kind 1.
  constexpr int kRoad = 1;
  std::vector<int> group(zm.labels.size(), -1), kind(zm.labels.size(), 0), lot_of;
  for (std::size_t l = 0; l < zm.labels.size(); ++l) {
    group[l] = zm.labels[l].lot;
    if (zm.labels[l].cover == Cover::Road || zm.labels[l].bridge) kind[l] = kRoad;
  }
  std::vector<geom::Cell> pieces = zm.map.cells(group, kind, &lot_of);

  geom::Box city = geom::Box::none();
  for (const geom::Cell& c : pieces) city.add(c.bounds());
  const geom::Vec2 centre{(city.min_x + city.max_x) / 2, (city.min_y + city.max_y) / 2};
  const double radius = std::hypot(city.width(), city.height()) / 2;
  const std::uint64_t stage = mix(sketch.seed, static_cast<std::uint64_t>(Stage::Buildings));

  std::vector<std::vector<Building>> placed(pieces.size());
  tbb::parallel_for(std::size_t(0), pieces.size(), [&](std::size_t i) {
    const Lot& lot = lots[lot_of[i]];
    const ZoneParams& p = sketch.zone_params.at(lot.zone);
    // The lots layer drops the same small pieces.
    if (geom::area(pieces[i].to_plain()) < p.min_lot_area) return;
    Random rng(mix(stage, i));
    std::vector<Building>& here = placed[i];
    std::vector<geom::Ring> taken;
    auto models = [&](ModelKind k) {
      if (!library) return;
      for (Building& b : place_models(pieces[i], kRoad, taken, library->choices(lot.zone, k), k, *library, p, rng))
        here.push_back(std::move(b));
    };
    if (library && !library->choices(lot.zone, ModelKind::Building).empty()) {
      models(ModelKind::Building);
    } else if (std::optional<Building> b = extruded_building(pieces[i], p)) {
      geom::Vec2 c = b->footprint.centroid();
      b->height = building_height(p, std::hypot(c.x - centre.x, c.y - centre.y), radius, rng);
      b->zone = lot.zone;
      choose_roof(*b, p);
      taken.push_back(b->polygon.outer);
      here.push_back(std::move(*b));
    }
    models(ModelKind::Street);
    models(ModelKind::Tree);
    for (Building& b : here) {
      b.lot = lot_of[i];
      b.zone = lot.zone;
      if (terrain) std::tie(b.base, b.floor) = terrain->range_under(b.polygon.outer);
    }
  });
  std::vector<Building> buildings;
  for (auto& here : placed)
    for (Building& b : here) buildings.push_back(std::move(b));
  return buildings;
}

}  // namespace exacity
