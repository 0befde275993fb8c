#include "generate/placement/mapped_buildings.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include <ogr_geometry.h>

#include "generate/city/memo.h"
#include "generate/city/random.h"
#include "generate/gis/ogr_polygon.h"
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

geom::Ring plain_ring(const OGRLinearRing& r) {
  geom::Ring out;
  for (int i = 0; i + 1 < r.getNumPoints(); ++i) {
    const geom::Vec2 v{r.getX(i), r.getY(i)};
    if (out.empty() || !(out.back() == v)) out.push_back(v);
  }
  return out;
}

// The smallest piece of a footprint kept where a repair splits it, in area and in mean width
// (twice its area over its perimeter): less is not a building (a strip of wall beyond a road).
constexpr double kSmallestPiece = 1, kNarrowestPiece = 1;

// The polygons of a GEOS result that have area (the lines and points where two polygons
// only touch have none), as simple rings oriented as every layer writes them; the others
// (a ring GEOS leaves touching itself, pieces under kSmallestPiece and kNarrowestPiece) are
// not kept.
std::vector<geom::Polygon> simple_polygons(const OGRGeometry* g) {
  std::vector<geom::Polygon> out;
  std::function<void(const OGRGeometry*)> collect = [&](const OGRGeometry* g) {
    if (const auto* polygon = dynamic_cast<const OGRPolygon*>(g)) {
      if (!(polygon->get_Area() >= kSmallestPiece)) return;
      geom::Polygon p;
      p.outer = plain_ring(*polygon->getExteriorRing());
      for (int i = 0; i < polygon->getNumInteriorRings(); ++i) p.holes.push_back(plain_ring(*polygon->getInteriorRing(i)));
      if (!simple(p)) return;
      orient(p);
      if (!(2 * geom::area(p) >= kNarrowestPiece * geom::perimeter(p))) return;
      out.push_back(std::move(p));
    } else if (const auto* collection = dynamic_cast<const OGRGeometryCollection*>(g)) {
      for (int i = 0; i < collection->getNumGeometries(); ++i) collect(collection->getGeometryRef(i));
    }
  };
  if (g) collect(g);
  return out;
}

// A footprint as kept: as drawn where its rings are simple and GEOS finds it valid, else
// made valid by GEOS's MakeValid (`repaired`): the polygons of at least kSmallestPiece m² it
// leaves (a bow tie's two triangles, a courtyard ring touching the outer one), as QGIS's
// "Fix geometries" leaves them; none where it leaves none.
std::vector<geom::Polygon> kept_polygons(geom::Polygon p, bool& repaired) {
  repaired = !simple(p) || !ogr_polygon(p)->IsValid();
  if (repaired) return simple_polygons(std::unique_ptr<OGRGeometry>(ogr_polygon(p)->MakeValid()).get());
  orient(p);
  return {std::move(p)};
}

// What is left of `footprint` clear of `obstacles` (road surfaces, footprints kept before
// it): its pieces of at least kSmallestPiece m² (GEOS's difference, each obstacle grown by
// kClear so that the result's rounding to doubles does not bring an edge back onto it).
constexpr double kClear = 0.01;
std::vector<geom::Polygon> cut_back(const geom::Polygon& footprint, const std::vector<const geom::Polygon*>& obstacles) {
  std::unique_ptr<OGRGeometry> rest = ogr_polygon(footprint);
  OGREnvelope near;
  rest->getEnvelope(&near);
  const OGRPolygon reach = box_around(near, 1);  // a road network's surface is one polygon
  for (const geom::Polygon* o : obstacles) {
    std::unique_ptr<OGRGeometry> there(ogr_polygon(*o)->Intersection(&reach));
    if (!there) return {};
    std::unique_ptr<OGRGeometry> grown(there->Buffer(kClear, 2));
    if (!grown) return {};
    rest.reset(rest->Difference(grown.get()));
    if (!rest) return {};
  }
  return simple_polygons(rest.get());
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
  // Each footprint simple, or made valid (in one piece or several), or refused.
  struct Candidate {
    Building building;                // its first piece
    std::vector<geom::Polygon> pieces;
    std::vector<std::string> repairs;
    std::vector<int> kept;            // its pieces' indices in `kept`
  };
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    const MappedBuilding& m = drawn[i];
    if (!m.problem.empty()) {
      refuse(m, m.problem);
      continue;
    }
    Candidate c;
    c.building.mapped = static_cast<int>(i);
    c.building.osm_id = m.osm_id;
    c.building.building_tag = m.building;
    c.building.source_id = m.source_id;
    bool repaired = false;
    c.pieces = kept_polygons(m.polygon, repaired);
    if (c.pieces.empty()) {
      refuse(m, "self-intersecting footprint that GEOS's MakeValid leaves no polygon of");
      continue;
    }
    if (repaired)
      c.repairs.push_back(c.pieces.size() == 1 ? "self-intersecting footprint made valid by GEOS's MakeValid"
                                               : "self-intersecting footprint made valid by GEOS's MakeValid, in pieces");
    candidates.push_back(std::move(c));
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
  std::vector<int> candidate_of;  // each piece's candidate
  for (std::size_t c = 0; c < candidates.size(); ++c)
    for (const geom::Polygon& piece : candidates[c].pieces) polygons.push_back(&piece), candidate_of.push_back(static_cast<int>(c));
  std::vector<std::vector<int>> roads_under(candidates.size()), earlier(candidates.size()), later(candidates.size());
  for (auto [a, b] : geom::overlapping_pairs(polygons)) {
    if (b < roads) continue;
    const int c = candidate_of[b - roads];
    if (a < roads) roads_under[c].push_back(a);
    else if (const int e = candidate_of[a - roads]; e != c) earlier[c].push_back(e), later[e].push_back(c);
  }
  // In the sketch's order: a footprint over a road surface or a footprint kept before it is
  // cut back from them where at least half of it stands clear (a road through a building's
  // passage, a sidewalk guessed wider than the street has room for, two footprints mapped
  // over each other's wall), else refused.
  std::vector<char> cut(candidates.size(), 0);
  std::vector<geom::Box> boxes;
  for (const Candidate& candidate : candidates) {
    boxes.push_back(geom::Box::none());
    for (const geom::Polygon& piece : candidate.pieces)
      for (geom::Vec2 v : piece.outer) boxes.back().add(v);
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    Candidate& candidate = candidates[c];
    const MappedBuilding& m = drawn[candidate.building.mapped];
    std::vector<const geom::Polygon*> obstacles;
    for (int r : roads_under[c]) obstacles.push_back(polygons[r]);
    std::sort(earlier[c].begin(), earlier[c].end());
    earlier[c].erase(std::unique(earlier[c].begin(), earlier[c].end()), earlier[c].end());
    const bool over_kept = std::any_of(earlier[c].begin(), earlier[c].end(), [&](int e) { return !candidates[e].kept.empty(); });
    if (!obstacles.empty() || over_kept) {
      double before = 0, after = 0;
      std::vector<geom::Polygon> pieces;
      // Besides what it overlaps, the footprints beside it: a piece's new corner on a wall it
      // shares with one, rounded to doubles, may stand a hair inside it.
      for (std::size_t e = 0; e < candidates.size(); ++e) {
        // (Not one after it that it overlaps: that one is cut back from this one.)
        if (e == c || !boxes[e].meets(boxes[c]) || std::count(later[c].begin(), later[c].end(), static_cast<int>(e))) continue;
        if (e < c)
          for (int k : candidates[e].kept) obstacles.push_back(&kept[k].polygon);
        else
          for (const geom::Polygon& piece : candidates[e].pieces) obstacles.push_back(&piece);
      }
      for (const geom::Polygon& piece : candidate.pieces) {
        before += geom::area(piece);
        for (geom::Polygon& p : cut_back(piece, obstacles)) after += geom::area(p), pieces.push_back(std::move(p));
      }
      const std::string why = roads_under[c].empty() ? "overlaps a mapped building kept before it" : "crosses a road surface";
      if (!(after >= before / 2)) {
        std::ostringstream detail;
        detail << why << ": " << std::round(after * 10) / 10 << " of its " << std::round(before * 10) / 10 << " m2 stand clear, under half";
        refuse(m, why, detail.str());
        continue;
      }
      candidate.pieces = std::move(pieces);
      candidate.repairs.push_back(roads_under[c].empty() ? "cut back from a mapped building kept before it"
                                                         : "cut back from a road surface");
      cut[c] = 1;
    }
    for (geom::Polygon& piece : candidate.pieces) {
      candidate.kept.push_back(static_cast<int>(kept.size()));
      kept.push_back(candidate.building);
      kept.back().polygon = std::move(piece);
    }
  }
  // The cut pieces checked exactly, as the footprints were: GEOS's difference is in doubles.
  std::vector<char> refused(candidates.size(), 0);
  if (std::find(cut.begin(), cut.end(), 1) != cut.end()) {
    polygons.resize(roads);
    candidate_of.clear();
    for (std::size_t c = 0; c < candidates.size(); ++c)
      for (int k : candidates[c].kept) polygons.push_back(&kept[k].polygon), candidate_of.push_back(static_cast<int>(c));
    for (auto [a, b] : geom::overlapping_pairs(polygons)) {
      if (b < roads) continue;
      const int c = candidate_of[b - roads], other = a < roads ? -1 : candidate_of[a - roads];
      if (other == c) continue;
      const int to_refuse = cut[c] ? c : other;  // only a cut piece can overlap anything now
      if (to_refuse < 0 || refused[to_refuse]) continue;
      refused[to_refuse] = 1;
      refuse(drawn[candidates[to_refuse].building.mapped],
             a < roads ? "crosses a road surface" : "overlaps a mapped building kept before it");
    }
  }
  std::vector<Building> out;
  for (const Candidate& c : candidates) {
    if (c.kept.empty() || refused[&c - candidates.data()]) continue;
    const MappedBuilding& m = drawn[c.building.mapped];
    if (c.repairs.empty()) ++tally.kept;
    else ++tally.repaired;
    for (const std::string& repair : c.repairs) {
      ++tally.repairs[repair];
      if (tally.named.size() < kNamed) tally.named.push_back(m.name + ": repaired, " + repair);
    }
    for (int k : c.kept) out.push_back(std::move(kept[k]));
  }
  return out;
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
    bool repaired = false;
    std::vector<geom::Polygon> pieces = kept_polygons(m.polygon, repaired);
    if (pieces.empty()) {
      refuse(m, "building:part whose self-intersecting ring GEOS's MakeValid leaves no polygon of");
      continue;
    }
    for (geom::Polygon& piece : pieces) {
      const std::optional<geom::Vec2> inside = point_inside(piece);
      std::size_t k = 0;
      for (; inside && k < footprints.size(); ++k)
        if (boxes[k].meets({inside->x, inside->y, inside->x, inside->y}) && geom::point_side(footprints[k].polygon, *inside) > 0) break;
      if (!inside || k == footprints.size()) {
        refuse(m, "building:part in no kept building");
        continue;
      }
      BuildingPart part;
      part.mapped = static_cast<int>(i);
      part.osm_id = m.osm_id;
      part.tag = m.building;
      part.polygon = std::move(piece);
      footprints[k].parts.push_back(std::move(part));
    }
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
  double walls = 0;  // the height drawn for the building's first piece, which its other pieces take
  for (std::size_t k = 0; k < footprints.size(); ++k) {
    Building& b = footprints[k];
    const MappedBuilding& m = drawn[b.mapped];
    // A footprint repaired into pieces is one building: counted once, all its pieces as high.
    const bool first_piece = k == 0 || footprints[k - 1].mapped != b.mapped;
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
    const char* height_from = m.height ? "height" : m.levels ? "building:levels" : "zone";
    if (first_piece) ++tally.heights[height_from];
    if (m.height) {
      b.height = *m.height;
    } else if (m.levels) {
      b.height = *m.levels * p.storey_height + rise;
    } else if (!first_piece) {
      b.height = walls + rise;
    } else {
      std::string key = "mapped ";
      append_key(key, b.polygon);
      Random rng(mix(stage, content_id(key)));
      const int channel = p.height_channel.empty() ? -1 : channels.index(p.height_channel);
      const geom::Vec2 c = inside.value_or(b.polygon.outer[0]);
      const double near_centre = channel >= 0 ? channels.value(channel, c)
                                 : radius > 0 ? 1 - std::min(std::hypot(c.x - centre.x, c.y - centre.y) / radius, 1.0)
                                              : 1;
      walls = building_height(p, near_centre, rng);
      b.height = walls + rise;
    }
    b.eaves = put_roof(shape, roof, 0, b.height, tally);
    b.roof = shape;
    b.roof_faces = std::move(roof);
    if (first_piece) ++tally.roofs[b.roof];
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
