#include "generate/placement/mapped_buildings.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

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

// A footprint as kept: as drawn where its rings are simple and GEOS finds it valid, else
// made valid (`repaired`), else nothing; oriented.
std::optional<geom::Polygon> kept_polygon(geom::Polygon p, bool& repaired) {
  repaired = !simple(p) || !ogr_valid(p);
  if (repaired) {
    std::optional<geom::Polygon> valid = made_valid(p);
    if (!valid) return std::nullopt;
    p = std::move(*valid);
  }
  orient(p);
  return p;
}

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


}  // namespace

namespace {

// A road's carriageway as mapped, which it keeps whatever stands beside it.
double mapped_carriageway(const RoadFeature& road) {
  if (road.carriageway) return *road.carriageway;
  constexpr double kLane = 3.5;
  bool one_lane = false;
  for (const auto& [key, value] : road.osm_tags)
    one_lane |= (key == "oneway" && (value == "yes" || value == "1" || value == "-1")) || (key == "highway" && value == "service");
  return std::min(road.width, one_lane ? kLane : 2 * kLane);
}

std::string format_metres(double v) {
  std::ostringstream out;
  out << std::round(v * 100) / 100;
  return out.str();
}

}  // namespace

void give_way_to_mapped_buildings(DrawnFeatures& drawn, MappedTally& tally) {
  constexpr double kClear = 0.01;
  struct Footprint {
    std::unique_ptr<OGRPolygon> polygon;
    geom::Box box;
    geom::Vec2 centre;
    const MappedBuilding* mapped;
  };
  std::vector<Footprint> footprints;
  for (const MappedBuilding& m : drawn.buildings) {
    if (!m.problem.empty() || m.polygon.outer.size() < 3) continue;
    Footprint f{ogr_polygon(m.polygon), geom::Box::none(), {0, 0}, &m};
    for (geom::Vec2 v : m.polygon.outer) {
      f.box.add(v);
      f.centre = f.centre + v * (1.0 / static_cast<double>(m.polygon.outer.size()));
    }
    footprints.push_back(std::move(f));
  }
  if (footprints.empty()) return;
  for (RoadFeature& road : drawn.roads) {
    const double floor = mapped_carriageway(road);
    double width = road.width, left = road.sidewalk_left, right = road.sidewalk_right;
    std::string for_building;  // the first building it gave way to
    for (const geom::Polyline& line : road.lines) {
      OGRLineString ogr_line;
      geom::Box box = geom::Box::none();
      for (geom::Vec2 v : line) ogr_line.addPoint(v.x, v.y), box.add(v);
      const double reach = road.width / 2 + road.widest_sidewalk();
      box = {box.min_x - reach, box.min_y - reach, box.max_x + reach, box.max_y + reach};
      for (const Footprint& f : footprints) {
        if (!box.meets(f.box)) continue;
        const double d = ogr_line.Distance(f.polygon.get());
        // Narrowing to the carriageway as mapped would not clear it: it stands on the road.
        if (!(d - kClear >= floor / 2) || d >= width / 2 + std::max(left, right)) continue;
        // Its side of the road: of the segment nearest its centre.
        std::size_t nearest = 0;
        for (std::size_t i = 0; i + 1 < line.size(); ++i)
          if (geom::distance_to_segment(f.centre, line[i], line[i + 1]) <
              geom::distance_to_segment(f.centre, line[nearest], line[nearest + 1]))
            nearest = i;
        double& sidewalk = geom::cross(line[nearest + 1] - line[nearest], f.centre - line[nearest]) > 0 ? left : right;
        if (d >= width / 2 + sidewalk) continue;
        sidewalk = std::max(0.0, std::min(sidewalk, d - kClear - width / 2));
        width = std::min(width, 2 * (d - kClear));
        if (for_building.empty()) for_building = f.mapped->osm_id.empty() ? f.mapped->name : f.mapped->osm_id;
      }
    }
    if (for_building.empty()) continue;
    ++tally.roads_narrowed;
    if (tally.narrowed.size() < kNamed) {
      std::string name = "features[" + std::to_string(road.index) + "]";
      for (const auto& [key, value] : road.osm_tags)
        if (key == "osm_id") name = value;
      tally.narrowed.push_back(name + ": " + format_metres(road.width) + " m wide to " + format_metres(width) +
                               " m, sidewalks " + format_metres(road.sidewalk_left) + " | " +
                               format_metres(road.sidewalk_right) + " m to " + format_metres(left) + " | " +
                               format_metres(right) + " m, for " + for_building);
    }
    road.width = width, road.sidewalk_left = left, road.sidewalk_right = right;
  }
}

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
    b.source_id = m.source_id;
    bool was_repaired = false;
    std::optional<geom::Polygon> polygon = kept_polygon(m.polygon, was_repaired);
    if (!polygon) {
      refuse(m, "self-intersecting footprint that GEOS's MakeValid does not make one polygon");
      continue;
    }
    b.polygon = std::move(*polygon);
    repaired.push_back(was_repaired);
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

void attach_building_parts(std::vector<Building>& footprints, const std::vector<MappedBuilding>& drawn, MappedTally& tally) {
  std::vector<geom::Box> boxes;
  for (const Building& b : footprints) {
    geom::Box box = geom::Box::none();
    for (geom::Vec2 v : b.polygon.outer) box.add(v);
    boxes.push_back(box);
  }
  auto refuse = [&](const MappedBuilding& m, const std::string& why) {
    ++tally.parts_refused[why];
    if (tally.named.size() < kNamed) tally.named.push_back(m.name + ": refused, " + why);
  };
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    const MappedBuilding& m = drawn[i];
    if (!m.problem.empty()) {
      refuse(m, "building:part: " + m.problem);
      continue;
    }
    BuildingPart part;
    part.mapped = static_cast<int>(i);
    part.osm_id = m.osm_id;
    part.tag = m.building;
    bool repaired = false;
    std::optional<geom::Polygon> polygon = kept_polygon(m.polygon, repaired);
    if (!polygon) {
      refuse(m, "building:part whose self-intersecting ring GEOS's MakeValid does not make one polygon");
      continue;
    }
    part.polygon = std::move(*polygon);
    const std::optional<geom::Vec2> inside = point_inside(part.polygon);
    std::size_t k = 0;
    for (; inside && k < footprints.size(); ++k)
      if (boxes[k].meets({inside->x, inside->y, inside->x, inside->y}) && geom::point_side(footprints[k].polygon, *inside) > 0) break;
    if (!inside || k == footprints.size()) {
      refuse(m, "building:part in no kept building");
      continue;
    }
    footprints[k].parts.push_back(std::move(part));
  }
}

namespace {

// The area of a GEOS result's polygons (the lines and points where two polygons only touch
// have none).
double surface_area(const OGRGeometry* g) {
  if (const auto* surface = dynamic_cast<const OGRSurface*>(g)) return surface->get_Area();
  double sum = 0;
  if (const auto* collection = dynamic_cast<const OGRGeometryCollection*>(g))
    for (int i = 0; i < collection->getNumGeometries(); ++i) sum += surface_area(collection->getGeometryRef(i));
  return sum;
}

}  // namespace

HeldLots lots_holding(const std::vector<Lot>& lots, const std::vector<Building>& footprints) {
  HeldLots out{std::vector<char>(lots.size(), 0), std::vector<int>(footprints.size(), -1),
               std::vector<std::vector<geom::Ring>>(lots.size()), std::vector<double>(lots.size(), 0)};
  if (footprints.empty()) return out;
  std::vector<const geom::Polygon*> polygons;
  for (const Lot& lot : lots) polygons.push_back(&lot.polygon);
  for (const Building& b : footprints) polygons.push_back(&b.polygon);
  const int n = static_cast<int>(lots.size());
  // Pairs come in order, so each footprint's lot is the first it stands on.
  for (auto [lot, footprint] : geom::overlapping_pairs(polygons)) {
    if (lot >= n || footprint < n) continue;
    const geom::Polygon& f = footprints[footprint - n].polygon;
    out.held[lot] = 1;
    if (out.lot_of[footprint - n] < 0) out.lot_of[footprint - n] = lot;
    out.standing[lot].push_back(f.outer);
    const std::unique_ptr<OGRGeometry> on_lot(ogr_polygon(lots[lot].polygon)->Intersection(ogr_polygon(f).get()));
    out.standing_m2[lot] += surface_area(on_lot.get());
  }
  return out;
}

namespace {

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


// The roof a mapped building's (or part's) tags ask for over `polygon`, its faces rising
// from 0, or flat (no faces) where geom/roof.h does not make that shape, counted.
std::pair<std::string, std::vector<geom::Face3>> tagged_roof(const MappedBuilding& m, const geom::Polygon& polygon,
                                                             double pitch, MappedTally& tally) {
  const std::string shape = m.roof_shape.empty() ? "flat" : m.roof_shape;
  if (shape == "flat") return {shape, {}};
  std::vector<geom::Face3> roof = pitched_roof(shape, polygon, m.roof_height.value_or(0), pitch);
  if (!roof.empty()) return {shape, std::move(roof)};
  const bool known = shape == "gabled" || shape == "hipped" || shape == "pyramidal";
  ++tally.made_flat[shape + (known ? ": the footprint's shape does not take it" : ": not a shape Exacity builds")];
  return {"flat", {}};
}

// The roof put on walls from `bottom` up to `height`: a roof as tall as the walls leaves
// them none, and is made flat (counted); the faces stand on the eaves. The eaves' height.
double put_roof(std::string& shape, std::vector<geom::Face3>& roof, double bottom, double height, MappedTally& tally) {
  if (!roof.empty() && !(geom::roof_top(roof) < height - bottom)) {
    ++tally.made_flat[shape + ": its roof as tall as the building"];
    roof.clear(), shape = "flat";
  }
  const double eaves = height - geom::roof_top(roof);
  for (geom::Face3& f : roof)
    for (geom::Vec3& v : f) v[2] += eaves;
  return eaves;
}

}  // namespace

void raise_mapped_buildings(std::vector<Building>& footprints, const std::vector<MappedBuilding>& drawn,
                            const std::vector<MappedBuilding>& drawn_parts,
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
    auto [shape, roof] = tagged_roof(m, b.polygon, p.roof_pitch, tally);
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
    b.eaves = put_roof(shape, roof, 0, b.height, tally);
    b.roof = shape;
    b.roof_faces = std::move(roof);
    ++tally.roofs[b.roof];
    if (terrain) std::tie(b.base, b.floor) = terrain->range_under(b.polygon.outer);
    // Its parts: each from its bottom to its own height, the building's where it tags none.
    std::vector<BuildingPart> parts;
    for (BuildingPart& part : b.parts) {
      const MappedBuilding& t = drawn_parts[part.mapped];
      auto [part_shape, part_roof] = tagged_roof(t, part.polygon, p.roof_pitch, tally);
      part.bottom = t.min_height ? *t.min_height : t.min_level ? *t.min_level * p.storey_height : 0;
      part.height = t.height ? *t.height : t.levels ? *t.levels * p.storey_height + geom::roof_top(part_roof) : b.height;
      if (!(part.height > part.bottom)) {
        ++tally.parts_refused["building:part whose height is not above its min_height"];
        if (tally.named.size() < kNamed) tally.named.push_back(t.name + ": refused, its height is not above its min_height");
        continue;
      }
      part.eaves = put_roof(part_shape, part_roof, part.bottom, part.height, tally);
      part.roof = part_shape;
      part.roof_faces = std::move(part_roof);
      ++tally.parts, ++tally.part_roofs[part.roof];
      parts.push_back(std::move(part));
    }
    b.parts = std::move(parts);
    if (!b.parts.empty()) b.height = 0;
    for (const BuildingPart& part : b.parts) b.height = std::max(b.height, part.height);
  }
}

}  // namespace exacity
