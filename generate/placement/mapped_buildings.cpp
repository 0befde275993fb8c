#include "generate/placement/mapped_buildings.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include <ogr_geometry.h>

#include "generate/city/memo.h"
#include "generate/city/random.h"
#include "geom/measure.h"
#include "geom/polygon_check.h"
#include "geom/triangulate.h"

namespace exacity {

namespace {

// How many refusals and repairs report.json names one by one; the counts hold them all.
constexpr std::size_t kNamed = 20;

bool simple(const geom::Polygon& p) {
  if (!geom::ring_is_simple(p.outer)) return false;
  return std::all_of(p.holes.begin(), p.holes.end(), [](const geom::Ring& h) { return geom::ring_is_simple(h); });
}

// Outer ring counter-clockwise, holes clockwise, as every layer writes them.
void orient(geom::Polygon& p) {
  if (geom::ring_orientation(p.outer) < 0) std::reverse(p.outer.begin(), p.outer.end());
  for (geom::Ring& h : p.holes)
    if (geom::ring_orientation(h) > 0) std::reverse(h.begin(), h.end());
}

std::unique_ptr<OGRPolygon> ogr_polygon(const geom::Polygon& p) {
  auto out = std::make_unique<OGRPolygon>();
  auto ring = [](const geom::Ring& r) {
    auto o = new OGRLinearRing;
    for (geom::Vec2 v : r) o->addPoint(v.x, v.y);
    o->closeRings();
    return o;
  };
  out->addRingDirectly(ring(p.outer));
  for (const geom::Ring& h : p.holes) out->addRingDirectly(ring(h));
  return out;
}

geom::Ring plain_ring(const OGRLinearRing& r) {
  geom::Ring out;
  for (int i = 0; i + 1 < r.getNumPoints(); ++i) {
    const geom::Vec2 v{r.getX(i), r.getY(i)};
    if (out.empty() || !(out.back() == v)) out.push_back(v);
  }
  return out;
}

// A footprint whose rings are not simple, or that GEOS finds invalid (a hole outside its
// outer ring), made valid by GEOS's MakeValid: the one polygon of area it leaves, or
// nothing where it leaves none or several (a bow tie's two triangles).
std::optional<geom::Polygon> made_valid(const geom::Polygon& p) {
  std::unique_ptr<OGRGeometry> valid(ogr_polygon(p)->MakeValid());
  if (!valid) return std::nullopt;
  std::vector<const OGRPolygon*> parts;
  std::function<void(const OGRGeometry*)> collect = [&](const OGRGeometry* g) {
    if (const auto* polygon = dynamic_cast<const OGRPolygon*>(g)) {
      if (polygon->get_Area() > 0) parts.push_back(polygon);
    } else if (const auto* collection = dynamic_cast<const OGRGeometryCollection*>(g)) {
      for (int i = 0; i < collection->getNumGeometries(); ++i) collect(collection->getGeometryRef(i));
    }
  };
  collect(valid.get());
  if (parts.size() != 1) return std::nullopt;
  geom::Polygon out;
  out.outer = plain_ring(*parts[0]->getExteriorRing());
  for (int i = 0; i < parts[0]->getNumInteriorRings(); ++i) out.holes.push_back(plain_ring(*parts[0]->getInteriorRing(i)));
  if (!simple(out)) return std::nullopt;
  orient(out);
  return out;
}

bool ogr_valid(const geom::Polygon& p) { return ogr_polygon(p)->IsValid(); }

}  // namespace

std::vector<Building> mapped_footprints(const std::vector<MappedBuilding>& drawn, const CityMap& map, MappedTally& tally) {
  std::vector<Building> kept;
  if (drawn.empty()) return kept;
  auto refuse = [&](const MappedBuilding& m, const std::string& why, const std::string& detail = "") {
    ++tally.refused[why];
    if (tally.named.size() < kNamed) tally.named.push_back(m.name + ": refused, " + (detail.empty() ? why : detail));
  };
  // Each footprint simple, or repaired, or refused.
  std::vector<Building> candidates;
  std::vector<char> repaired;
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    const MappedBuilding& m = drawn[i];
    if (!m.problem.empty()) {
      refuse(m, m.problem);
      continue;
    }
    Building b;
    b.mapped = static_cast<int>(i);
    b.osm_id = m.osm_id;
    b.building_tag = m.building;
    b.polygon = m.polygon;
    repaired.push_back(!simple(b.polygon) || !ogr_valid(b.polygon));
    if (repaired.back()) {
      std::optional<geom::Polygon> valid = made_valid(b.polygon);
      if (!valid) {
        refuse(m, "self-intersecting footprint that GEOS's MakeValid does not make one polygon");
        repaired.pop_back();
        continue;
      }
      b.polygon = std::move(*valid);
    }
    orient(b.polygon);
    candidates.push_back(std::move(b));
  }
  // The road surfaces (carriageways, sidewalks, junctions, bridges) as the map has them,
  // then the footprints, in one exact map: which footprint crosses a road, which overlap.
  std::vector<int> group(map.labels.size(), -1);
  for (std::size_t l = 0; l < map.labels.size(); ++l)
    if (map.labels[l].road_surface()) group[l] = 0;
  const std::vector<std::vector<geom::Dissolved>> surfaces = map.map.dissolve(group, 1);
  std::vector<const geom::Polygon*> polygons;
  for (const geom::Dissolved& d : surfaces[0]) polygons.push_back(&d.polygon);
  const int roads = static_cast<int>(polygons.size());
  for (const Building& b : candidates) polygons.push_back(&b.polygon);
  std::vector<char> on_road(candidates.size(), 0);
  std::vector<std::vector<int>> earlier(candidates.size());  // the footprints before each that it overlaps
  for (auto [a, b] : geom::overlapping_pairs(polygons)) {
    if (b < roads) continue;
    if (a < roads) on_road[b - roads] = 1;
    else earlier[b - roads].push_back(a - roads);
  }
  std::vector<int> kept_as(candidates.size(), -1);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const MappedBuilding& m = drawn[candidates[c].mapped];
    if (on_road[c]) {
      refuse(m, "crosses a road surface");
      continue;
    }
    const auto over = std::find_if(earlier[c].begin(), earlier[c].end(), [&](int e) { return kept_as[e] >= 0; });
    if (over != earlier[c].end()) {
      refuse(m, "overlaps a mapped building kept before it",
             "overlaps " + drawn[candidates[*over].mapped].name + ", kept before it");
      continue;
    }
    if (repaired[c]) {
      ++tally.repaired, ++tally.repairs["self-intersecting footprint made valid by GEOS's MakeValid"];
      if (tally.named.size() < kNamed) tally.named.push_back(m.name + ": repaired, its self-intersecting footprint made valid by GEOS's MakeValid");
    } else {
      ++tally.kept;
    }
    kept_as[c] = static_cast<int>(kept.size());
    kept.push_back(candidates[c]);
  }
  return kept;
}

HeldLots lots_holding(const std::vector<Lot>& lots, const std::vector<Building>& footprints) {
  HeldLots out{std::vector<char>(lots.size(), 0), std::vector<int>(footprints.size(), -1)};
  if (footprints.empty()) return out;
  std::vector<const geom::Polygon*> polygons;
  for (const Lot& lot : lots) polygons.push_back(&lot.polygon);
  for (const Building& b : footprints) polygons.push_back(&b.polygon);
  const int n = static_cast<int>(lots.size());
  // Pairs come in order, so each footprint's lot is the first it stands on.
  for (auto [lot, footprint] : geom::overlapping_pairs(polygons)) {
    if (lot >= n || footprint < n) continue;
    out.held[lot] = 1;
    if (out.lot_of[footprint - n] < 0) out.lot_of[footprint - n] = lot;
  }
  return out;
}

namespace {

// A point strictly inside the polygon: the centre of its largest triangle.
std::optional<geom::Vec2> point_inside(const geom::Polygon& p) {
  std::vector<geom::Vec2> points(p.outer);
  for (const geom::Ring& h : p.holes) points.insert(points.end(), h.begin(), h.end());
  double best = 0;
  std::optional<geom::Vec2> out;
  for (const auto& t : geom::triangulate(p)) {
    const geom::Vec2 a = points[t[0]], b = points[t[1]], c = points[t[2]];
    const double area = std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
    if (area > best) best = area, out = geom::Vec2{(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3};
  }
  return out;
}

// The roof `shape` over the footprint rising `rise` (or at the zone's pitch where it is 0)
// above its eaves at 0, or nothing where geom/roof.h does not make that shape.
std::vector<geom::Face3> pitched_roof(const std::string& shape, const geom::Polygon& footprint, double rise,
                                      double pitch) {
  const double slope = std::tan(pitch * M_PI / 180);
  std::vector<geom::Face3> faces;
  if (shape == "gabled") faces = geom::gabled_roof(footprint, 0, slope);
  // The straight skeleton's roof: hipped, and over a square or regular footprint a pyramid.
  if (shape == "hipped" || shape == "pyramidal") faces = geom::hipped_roof(footprint, 0, slope);
  const double top = geom::roof_top(faces);
  if (faces.empty() || !(top > 0)) return {};
  if (rise > 0)
    for (geom::Face3& f : faces)
      for (geom::Vec3& v : f) v[2] *= rise / top;
  return faces;
}

}  // namespace

void raise_mapped_buildings(std::vector<Building>& footprints, const std::vector<MappedBuilding>& drawn,
                            const HeldLots& held, const std::vector<Lot>& lots, const CityMap& map, const std::vector<ZoneFeature>& zones,
                            const CitySettings& city, const Channels& channels, const Terrain* terrain, int first_id,
                            MappedTally& tally) {
  if (footprints.empty()) return;
  geom::Box box = geom::Box::none();
  for (const Lot& lot : lots) box.add(lot.cell.bounds());
  const geom::Vec2 centre{(box.min_x + box.max_x) / 2, (box.min_y + box.max_y) / 2};
  const double radius = box.holds_nothing() ? 0 : std::hypot(box.width(), box.height()) / 2;
  const std::uint64_t stage = mix(city.seed, static_cast<std::uint64_t>(Stage::Buildings));
  int id = first_id;
  for (std::size_t k = 0; k < footprints.size(); ++k) {
    Building& b = footprints[k];
    const MappedBuilding& m = drawn[b.mapped];
    b.id = id++;
    b.lot = held.lot_of[k];
    const std::optional<geom::Vec2> inside = point_inside(b.polygon);
    if (b.lot >= 0) {
      b.zone = lots[b.lot].zone;
    } else if (inside) {
      const int label = map.map.label_at(*inside);
      if (label >= 0 && map.labels[label].zone >= 0) b.zone = zones[map.labels[label].zone].type;
    }
    const auto settings = city.zone_settings.find(b.zone);
    const BuildingSettings p = settings != city.zone_settings.end() ? settings->second.buildings : BuildingSettings{};
    // The roof first: a height from levels stands its roof on its walls.
    std::string shape = m.roof_shape.empty() ? "flat" : m.roof_shape;
    std::vector<geom::Face3> roof;
    if (shape != "flat") {
      roof = pitched_roof(shape, b.polygon, m.roof_height.value_or(0), p.roof_pitch);
      if (roof.empty()) {
        const bool known = shape == "gabled" || shape == "hipped" || shape == "pyramidal";
        ++tally.made_flat[shape + (known ? ": the footprint's shape does not take it" : ": not a shape Exacity builds")];
        shape = "flat";
      }
    }
    const double rise = geom::roof_top(roof);
    if (m.height) {
      b.height = *m.height, ++tally.heights["height"];
    } else if (m.levels) {
      b.height = *m.levels * p.storey_height + rise, ++tally.heights["building:levels"];
    } else {
      std::string key = "mapped ";
      append_key(key, b.polygon);
      Random rng(mix(stage, content_id(key)));
      const int channel = p.height_channel.empty() ? -1 : channels.index(p.height_channel);
      const geom::Vec2 c = inside.value_or(b.polygon.outer[0]);
      const double near_centre = channel >= 0 ? channels.value(channel, c)
                                 : radius > 0 ? 1 - std::min(std::hypot(c.x - centre.x, c.y - centre.y) / radius, 1.0)
                                              : 1;
      b.height = building_height(p, near_centre, rng) + rise, ++tally.heights["zone"];
    }
    // A roof as tall as the building leaves it no walls.
    if (!roof.empty() && !(rise < b.height)) {
      ++tally.made_flat[shape + ": its roof as tall as the building"];
      roof.clear(), shape = "flat";
    }
    b.roof = shape;
    b.eaves = b.height - geom::roof_top(roof);
    for (geom::Face3& f : roof)
      for (geom::Vec3& v : f) v[2] += b.eaves;
    b.roof_faces = std::move(roof);
    ++tally.roofs[b.roof];
    if (terrain) std::tie(b.base, b.floor) = terrain->range_under(b.polygon.outer);
  }
}

}  // namespace exacity
