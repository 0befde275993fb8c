#include "generate/sketch/like_place.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <ogr_api.h>

#include "generate/city/format_number.h"
#include "generate/errors.h"
#include "generate/gis/ogr_polygon.h"
#include "generate/input_file.h"
#include "generate/parcels/lots.h"
#include "generate/sketch/sketch_document.h"
#include "geom/measure.h"

namespace exacity {
namespace {

using geom::Vec2;
using nlohmann::ordered_json;

constexpr double kSetbackReach = 25;  // m: a footprint farther from every road fronts none
constexpr double kGapReach = 20;      // m: a footprint farther from every other stands alone
constexpr double kTouchingGap = 1;    // m: a place whose median gap is under this builds perimeter blocks
constexpr double kMinWidthQuantile = 0.4;  // of the short sides: min_footprint_width (settings_from_figures)

// The value at quantile q (0 to 1) of sorted values, the lower one between two.
double quantile(const std::vector<double>& sorted, double q) {
  const std::size_t n = sorted.size();
  const std::size_t i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
  return sorted[std::clamp<std::size_t>(i, 1, n) - 1];
}

std::vector<double> sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v;
}

double tenth(double x) { return std::round(x * 10) / 10; }

// The convex hull, counter-clockwise (Andrew's monotone chain).
std::vector<Vec2> hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }), p.end());
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && geom::cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && geom::cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// The sides of the smallest-area rectangle around the ring: one of its sides lies along an
// edge of the convex hull (Freeman and Shapira). {long, short}.
std::pair<double, double> rectangle_sides(const geom::Ring& ring) {
  const std::vector<Vec2> h = hull(ring);
  double best = INFINITY, along = 0, across = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const Vec2 a = h[i], b = h[(i + 1) % h.size()];
    const double len = geom::distance(a, b);
    if (len == 0) continue;
    const Vec2 u = (b - a) * (1 / len);
    double lo = INFINITY, hi = -INFINITY, height = 0;
    for (Vec2 q : h) {
      const double s = geom::dot(q - a, u);
      lo = std::min(lo, s), hi = std::max(hi, s);
      height = std::max(height, std::abs(geom::cross(u, q - a)));
    }
    if ((hi - lo) * height < best) best = (hi - lo) * height, along = hi - lo, across = height;
  }
  if (!std::isfinite(best)) return {0, 0};
  return {std::max(along, across), std::min(along, across)};
}

// The ring's centre of area (its first corner when it has none).
Vec2 centre(const geom::Ring& r) {
  double a = 0, x = 0, y = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 p = r[i], q = r[(i + 1) % r.size()];
    const double c = geom::cross(p - r[0], q - r[0]);
    a += c, x += c * (p.x + q.x - 2 * r[0].x), y += c * (p.y + q.y - 2 * r[0].y);
  }
  if (a == 0) return r[0];
  return {r[0].x + x / (3 * a), r[0].y + y / (3 * a)};
}

geom::Box box_of(const geom::Ring& r) {
  geom::Box b = geom::Box::none();
  for (Vec2 p : r) b.add(p);
  return b;
}

bool within(const geom::Box& a, const geom::Box& b, double reach) {
  return a.min_x - reach <= b.max_x && b.min_x - reach <= a.max_x && a.min_y - reach <= b.max_y && b.min_y - reach <= a.max_y;
}

// The least distance between two rings, corner to edge either way (0 where they touch or cross).
double ring_distance(const geom::Ring& a, const geom::Ring& b) {
  double d = INFINITY;
  for (const auto& [from, to] : {std::pair{&a, &b}, std::pair{&b, &a}})
    for (Vec2 p : *from)
      for (std::size_t i = 0; i < to->size(); ++i)
        d = std::min(d, geom::distance_to_segment(p, (*to)[i], (*to)[(i + 1) % to->size()]));
  return d;
}

constexpr ZoneType kBuiltUp[] = {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial};

// The zone type whose drawn zone holds p, the last drawn winning; none outside them all.
std::optional<ZoneType> zone_at(const std::vector<ZoneFeature>& zones, Vec2 p) {
  for (auto z = zones.rbegin(); z != zones.rend(); ++z)
    for (const geom::Polygon& polygon : z->polygons)
      if (geom::odd_crossings(polygon, p)) return z->type;
  return std::nullopt;
}


// The spread s of a footprint's sides about their centre (each drawn from [c(1-s), c(1+s)])
// whose area's 90th percentile over its median is `ratio`, with that median over the
// centres' product: the area of two independent uniform draws, on a fine grid of both.
struct Spread {
  double s = 0, median = 1;
};

Spread spread_for(double ratio) {
  auto figures = [](double s) {
    constexpr int kSteps = 200;
    std::vector<double> products;
    products.reserve((kSteps + 1) * (kSteps + 1));
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; j <= kSteps; ++j)
        products.push_back((1 + s * (2.0 * i / kSteps - 1)) * (1 + s * (2.0 * j / kSteps - 1)));
    std::sort(products.begin(), products.end());
    return std::pair{quantile(products, 0.5), quantile(products, 0.9)};
  };
  double lo = 0, hi = 0.9;
  auto [m_hi, p_hi] = figures(hi);
  if (p_hi / m_hi <= ratio) return {hi, m_hi};
  for (int k = 0; k < 30; ++k) {
    const double mid = (lo + hi) / 2;
    auto [m, p] = figures(mid);
    (p / m < ratio ? lo : hi) = mid;
  }
  return {lo, figures(lo).first};
}

// The area of a polygon as drawn (its rings winding either way): the outer ring's less its holes'.
double drawn_area(const geom::Polygon& p) {
  double a = std::abs(geom::signed_area(p.outer));
  for (const geom::Ring& h : p.holes) a -= std::abs(geom::signed_area(h));
  return a;
}

ordered_json summary(const std::vector<double>& values) {
  if (values.empty()) return {{"count", 0}};
  const std::vector<double> v = sorted(values);
  return {{"count", v.size()}, {"p10", tenth(quantile(v, 0.1))}, {"median", tenth(quantile(v, 0.5))},
          {"p90", tenth(quantile(v, 0.9))}};
}

}  // namespace

std::map<ZoneType, double> land_by_zone(const std::vector<ZoneFeature>& zones) {
  struct Land {
    ZoneType type;
    std::unique_ptr<OGRGeometry> geometry;
    OGREnvelope box;
  };
  std::vector<Land> drawn;
  for (const ZoneFeature& z : zones)
    for (const geom::Polygon& p : z.polygons) {
      Land land{z.type, std::unique_ptr<OGRGeometry>(ogr_polygon(p)->MakeValid()), {}};
      if (!land.geometry) continue;
      land.geometry->getEnvelope(&land.box);
      drawn.push_back(std::move(land));
    }
  // Each less the ones drawn after it that it meets: a land use's thousands of polygons
  // overlap only their neighbours.
  std::map<ZoneType, double> out;
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    std::unique_ptr<OGRGeometry> seen(drawn[i].geometry->clone());
    for (std::size_t j = i + 1; j < drawn.size() && seen; ++j)
      if (drawn[j].box.Intersects(drawn[i].box)) seen.reset(seen->Difference(drawn[j].geometry.get()));
    if (seen) out[drawn[i].type] += OGR_G_Area(OGRGeometry::ToHandle(seen.get()));
  }
  return out;
}

std::optional<ZoneType> built_up_zone_at(const std::vector<ZoneFeature>& zones, const geom::Ring& ring) {
  if (ring.size() < 3) return std::nullopt;
  const std::optional<ZoneType> t = zone_at(zones, centre(ring));
  if (t && std::find(std::begin(kBuiltUp), std::end(kBuiltUp), *t) != std::end(kBuiltUp)) return t;
  return std::nullopt;
}

std::map<ZoneType, PlaceFigures> measure_place(const std::vector<RealFootprint>& footprints,
                                               const std::vector<ZoneFeature>& zones,
                                               const std::vector<RoadFeature>& roads,
                                               const std::map<ZoneType, ZoneSettings>& settings) {
  std::map<ZoneType, PlaceFigures> out;
  std::vector<geom::Box> boxes;
  for (const RealFootprint& f : footprints) boxes.push_back(box_of(f.polygon.outer));
  // Road pieces with their half widths, for the setbacks.
  struct Piece {
    Vec2 a, b;
    double half;
    geom::Box box;
  };
  std::vector<Piece> pieces;
  for (const RoadFeature& r : roads)
    for (const geom::Polyline& l : r.lines)
      for (std::size_t i = 0; i + 1 < l.size(); ++i) {
        geom::Box b = geom::Box::none();
        b.add(l[i]), b.add(l[i + 1]);
        pieces.push_back({l[i], l[i + 1], r.width / 2, b});
      }
  // Footprints in cells of a grid, for their neighbours.
  constexpr double kCell = 100;
  std::map<std::pair<long, long>, std::vector<std::size_t>> grid;
  auto cell = [&](double x, double y) { return std::pair{std::lround(std::floor(x / kCell)), std::lround(std::floor(y / kCell))}; };
  for (std::size_t i = 0; i < footprints.size(); ++i) grid[cell(boxes[i].min_x, boxes[i].min_y)].push_back(i);

  for (std::size_t i = 0; i < footprints.size(); ++i) {
    const geom::Polygon& p = footprints[i].polygon;
    const double area = drawn_area(p);
    if (p.outer.size() < 3 || !(area > 0)) continue;
    std::vector<ZoneType> types;
    if (zones.empty()) {
      types.assign(std::begin(kBuiltUp), std::end(kBuiltUp));
    } else if (std::optional<ZoneType> t = built_up_zone_at(zones, p.outer)) {
      types.push_back(*t);
    }
    if (types.empty()) continue;
    const auto [long_side, short_side] = rectangle_sides(p.outer);
    double setback = INFINITY;
    for (const Piece& piece : pieces)
      if (within(piece.box, boxes[i], kSetbackReach + piece.half))
        for (Vec2 v : p.outer) setback = std::min(setback, geom::distance_to_segment(v, piece.a, piece.b) - piece.half);
    double gap = INFINITY;
    const auto [cx, cy] = cell(boxes[i].min_x, boxes[i].min_y);
    for (long gx = cx - 1; gx <= cx + 1; ++gx)
      for (long gy = cy - 1; gy <= cy + 1; ++gy) {
        const auto it = grid.find({gx, gy});
        if (it == grid.end()) continue;
        for (std::size_t j : it->second)
          if (j != i && within(boxes[i], boxes[j], kGapReach))
            gap = std::min(gap, ring_distance(p.outer, footprints[j].polygon.outer));
      }
    for (ZoneType t : types) {
      PlaceFigures& f = out[t];
      ++f.buildings;
      f.areas.push_back(area);
      f.long_sides.push_back(long_side), f.short_sides.push_back(short_side);
      f.wing_depths.push_back(2 * area / geom::perimeter(p));
      if (footprints[i].height) f.heights.push_back(*footprints[i].height);
      else if (footprints[i].levels) f.heights.push_back(*footprints[i].levels * settings.at(t).buildings.storey_height);
      if (setback <= kSetbackReach) f.setbacks.push_back(std::max(setback, 0.0));
      if (gap <= kGapReach) f.gaps.push_back(gap);
    }
  }
  const std::map<ZoneType, double> land = land_by_zone(zones);
  for (auto& [type, f] : out)
    if (land.count(type)) f.land_m2 = land.at(type);
  // Each side of each street fronts the land use a metre past its edge, and lies in the
  // land use where the middle of its half does.
  if (!zones.empty())
    for (const Piece& piece : pieces) {
      const Vec2 middle = geom::lerp(piece.a, piece.b, 0.5), n = geom::left_normal(piece.a, piece.b);
      const double length = geom::distance(piece.a, piece.b);
      for (double side : {-1.0, 1.0}) {
        if (const std::optional<ZoneType> t = zone_at(zones, middle + n * (side * (piece.half + 1))); t && out.count(*t))
          out[*t].frontage_m += length;
        if (const std::optional<ZoneType> t = zone_at(zones, middle + n * (side * piece.half / 2)); t && out.count(*t))
          out[*t].street_m2 += length * piece.half;
      }
    }
  return out;
}

namespace {

// The land the place's blocks hold: its land use less its streets, or its land use where
// the streets would leave none (a land use drawn as a street's surface).
double block_land_m2(const PlaceFigures& f) { return f.land_m2 > f.street_m2 ? f.land_m2 - f.street_m2 : f.land_m2; }

// The footprints' area, all of them.
double footprint_m2(const PlaceFigures& f) {
  double sum = 0;
  for (double a : f.areas) sum += a;
  return sum;
}

}  // namespace

ordered_json settings_from_figures(const PlaceFigures& f, const ZoneSettings& defaults) {
  ordered_json set = ordered_json::object();
  if (f.buildings < kMinBuildingsToMeasure) return set;
  const std::vector<double> areas = sorted(f.areas);
  const double median = quantile(areas, 0.5), p90 = quantile(areas, 0.9);
  // Generated footprints are rectangles whose sides are drawn independently, each from its
  // range: the ranges' spread gives the areas' p90 over their median as measured, their
  // centres (in the measured ratio of long to short side) the median.
  std::vector<double> ratios;
  for (std::size_t i = 0; i < f.long_sides.size(); ++i)
    if (f.short_sides[i] > 0) ratios.push_back(f.long_sides[i] / f.short_sides[i]);
  const double ratio = ratios.empty() ? 1 : quantile(sorted(ratios), 0.5);
  const Spread spread = spread_for(p90 / median);
  const double product = median / spread.median;
  const double width = std::sqrt(product * ratio), depth = std::sqrt(product / ratio);
  const Range widths{tenth(width * (1 - spread.s)), tenth(width * (1 + spread.s))};
  const Range depths{tenth(depth * (1 - spread.s)), tenth(depth * (1 + spread.s))};
  const BuildingSettings& b = defaults.buildings;
  const double setback = f.setbacks.empty() ? b.setback : tenth(quantile(sorted(f.setbacks), 0.5));
  const double gap = f.gaps.empty() ? b.building_gap : tenth(quantile(sorted(f.gaps), 0.5));
  set["footprint_width"] = {std::max(widths.min, 1.0), std::max(widths.max, 1.0)};
  set["footprint_depth"] = {std::max(depths.min, 1.0), std::max(depths.max, 1.0)};
  // The areas themselves, long tail and all (the sides' ranges alone give none: their
  // product's mean is near its median), at every twentieth of their distribution.
  ordered_json steps = ordered_json::array();
  for (int k = 0; k <= 20; ++k) steps.push_back(std::max(tenth(quantile(areas, k / 20.0)), 1.0));
  set["footprint_areas"] = steps;
  set["max_footprint_area"] = std::ceil(std::max(areas.back(), widths.max * depths.max));
  // With footprint_areas no footprint shrinks, so these only bound the drawn ones: an area
  // under min_footprint_area fits nowhere and ends its lot's footprints (the place's
  // smallest one is the bound), and each side is raised to min_footprint_width. That was
  // 0.8 of the middle width (9 m on Kotka, raising the 40% of its residential draws under
  // 81 m² to 81 m²); it is now a quantile of the measured short sides, the 40th: lower
  // ones (the tenth: 3 m) let the lots' room filter the sizes down (a lot holds the draws
  // before the first it cannot hold), the residential median 32% and the industrial 46%
  // under the mapped ones (docs/gis.md).
  set["min_footprint_area"] = std::max(1.0, std::floor(areas.front()));
  set["min_footprint_width"] = std::max(1.0, std::floor(quantile(sorted(f.short_sides), kMinWidthQuantile)));
  set["setback"] = setback;
  set["building_gap"] = gap;
  // Rows behind the first fill each lot to the place's coverage of its blocks (its land use
  // less its streets): its lots fill its blocks, and so do the lots of a zone with
  // lot_coverage, so their coverage is that.
  if (const double blocks = block_land_m2(f); blocks > 0) {
    set["lot_coverage"] = std::min(std::round(footprint_m2(f) / blocks * 1000) / 1000, 1.0);
  }
  // Lots from the upper part of the distribution: each wide enough for two footprints of
  // the place's 90th percentile long side with their gaps (up to half as wide again), and
  // deep enough for its 90th percentile short side (or the deepest drawn) behind the
  // setback, and for the width (lots are no wider than twice as deep). Lots sized for the
  // middle held one footprint and lost the next draw they could not hold, nearly always a
  // large one: Kotka's industrial p90 33% and its coverage 29% under the mapped ones.
  const double pair = 2 * (quantile(sorted(f.long_sides), 0.9) + gap);
  const double deep = setback + std::max(depths.max, quantile(sorted(f.short_sides), 0.9)) + gap / 2;
  set["lot_depth"] = std::ceil(std::max(deep, 0.75 * pair));
  set["lot_width"] = {std::ceil(pair), std::ceil(1.5 * pair)};
  if (static_cast<int>(f.heights.size()) >= kMinBuildingsToMeasure) {
    const std::vector<double> h = sorted(f.heights);
    set["heights"] = {tenth(std::max(quantile(h, 0.1), 0.5)), tenth(std::max(quantile(h, 0.9), quantile(h, 0.1)))};
  }
  return set;
}

namespace {

// The frontage rule (docs/gis.md, Looking like the place): each footprint fronts a street
// with its lot. The place's street frontage, less a gap beside each footprint, is shared by
// its footprints; each one's depth back from the street is then their area over that, and
// its lot's frontage its area over that depth and its gap, so that perimeter blocks of that
// depth on lots of those frontages have the place's areas, as many to the metre of street
// as it has. The settings it gives (lot frontages from the tenth percentile up: smaller
// footprints are below min_footprint_area, and their lots would stand empty; lots deep
// enough for their footprints and for the widest frontage to make a lot, kLotShape); none
// without frontage to share.
ordered_json frontage_rule(const PlaceFigures& f, double setback, double gap, double largest_rectangle) {
  double total_area = 0;
  for (double a : f.areas) total_area += a;
  const double net_frontage = f.frontage_m - static_cast<double>(f.buildings) * gap;
  const double depth = net_frontage > 0 ? tenth(total_area / net_frontage) : 0;
  if (depth < 1) return nullptr;
  const std::vector<double> areas = sorted(f.areas);
  ordered_json frontages = ordered_json::array();
  for (int k = 0; k <= 20; ++k) frontages.push_back(std::max(tenth(quantile(areas, 0.1 + 0.9 * k / 20) / depth + gap), 1.0));
  const double lot_depth = std::ceil(std::max(setback + depth + gap / 2, frontages.back().get<double>() * kLotShape.min));
  // Perimeter footprints from the place's tenth to its 95th percentile area. A band runs
  // along every street edge of its lot, and lots joined at a block's corners, or from
  // pieces too small to stand alone, front more street than any frontage drawn: their
  // bands held Helsinki's commercial p90 25% over the mapped one, while pieces left where
  // runs of lots meet held footprints of a few square metres (its residential median 26%
  // under). A lot whose band is larger is built in rows of the place's footprints instead
  // (which may be as large as the rectangles their sides' ranges make); a piece whose band
  // is smaller stands empty and joins the lot beside it.
  return {{"perimeter_depth", depth},
          {"lot_frontages", frontages},
          {"lot_depth", lot_depth},
          {"min_footprint_area", std::max(1.0, std::floor(quantile(areas, 0.1)))},
          {"max_footprint_area", std::ceil(std::max(quantile(areas, 0.95), largest_rectangle))}};
}

// The footprints a file maps, and the zones and roads it draws.
struct RealPlace {
  std::vector<RealFootprint> footprints;
  DrawnFeatures drawn;
  nlohmann::ordered_json crs;
};

RealPlace read_place(const std::filesystem::path& like) {
  std::error_code error;
  if (!std::filesystem::exists(like, error))
    throw UserError(like.string() + ": no such file, so no place to look like; give an OSM extract or a file of "
                    "building footprints");
  ordered_json doc = sketch_document(like);
  // A file of footprints and nothing else (a cadastre's) has them untagged: each polygon
  // that is no zone or road is one.
  for (ordered_json& f : doc["features"]) {
    if (!f.is_object() || !f.contains("geometry") || !f["geometry"].is_object()) continue;
    const std::string type = f["geometry"].value("type", "");
    if (type != "Polygon" && type != "MultiPolygon") continue;
    if (!f.contains("properties") || !f["properties"].is_object()) f["properties"] = ordered_json::object();
    ordered_json& p = f["properties"];
    if (!p.contains("zone") && !p.contains("road") && !p.contains("building")) p["building"] = "yes";
  }
  RealPlace place;
  place.crs = doc.contains("crs") ? doc["crs"] : ordered_json();
  place.drawn = read_drawn_features(doc, like);
  for (const MappedBuilding& b : place.drawn.buildings)
    if (b.problem.empty()) place.footprints.push_back({b.polygon, b.height, b.levels});
  return place;
}

}  // namespace

ordered_json like_place(Sketch& sketch, const std::filesystem::path& like) {
  const RealPlace place = read_place(like);
  if (static_cast<int>(place.footprints.size()) < kMinBuildingsToMeasure)
    throw UserError(like.string() + ": maps " + std::to_string(place.footprints.size()) +
                    " building footprints, too few to measure a place by (at least " +
                    std::to_string(kMinBuildingsToMeasure) +
                    "); give an extract or a file with more of its buildings, or leave out --like");
  // Its own land use, else the sketch's where the two lie in one frame, else none: then
  // every footprint stands for every built-up zone type.
  const bool own_zones = std::any_of(place.drawn.zones.begin(), place.drawn.zones.end(), [](const ZoneFeature& z) {
    return std::find(std::begin(kBuiltUp), std::end(kBuiltUp), z.type) != std::end(kBuiltUp);
  });
  const bool same_frame = !own_zones && place.crs == sketch.crs;
  const std::vector<ZoneFeature>& zones = own_zones ? place.drawn.zones : same_frame ? sketch.zones : std::vector<ZoneFeature>{};
  const std::vector<RoadFeature>& roads = own_zones ? place.drawn.roads : same_frame ? sketch.roads : std::vector<RoadFeature>{};
  const std::map<ZoneType, PlaceFigures> figures = measure_place(place.footprints, zones, roads, sketch.zone_settings);

  ordered_json doc = ordered_json::parse(
      sketch.geojson.empty() ? read_input(sketch.path, kMaxDataFileBytes, "the sketch", "give the sketch again") : sketch.geojson);
  if (!doc.contains("exacity") || !doc["exacity"].is_object()) doc["exacity"] = ordered_json::object();
  ordered_json& ex = doc["exacity"];
  ex.erase("like");  // measured once: the copy holds what it gave
  if (!ex.contains("zones")) ex["zones"] = ordered_json::object();
  ordered_json report{{"file", like.string()},
                      {"footprints", place.footprints.size()},
                      {"zones_from", own_zones ? "the file's land use" : same_frame ? "the sketch's land use"
                                                                                    : "none: every footprint for every built-up zone type"},
                      {"zones", ordered_json::object()}};
  for (ZoneType t : kBuiltUp) {
    const std::string type(name(t));
    const auto it = figures.find(t);
    const PlaceFigures f = it == figures.end() ? PlaceFigures{} : it->second;
    ordered_json z{{"buildings", f.buildings}};
    if (f.buildings < kMinBuildingsToMeasure) {
      z["kept_defaults"] = "fewer than " + std::to_string(kMinBuildingsToMeasure) + " mapped buildings in " + type + " land";
      report["zones"][type] = z;
      continue;
    }
    const double footprint_area = footprint_m2(f);
    z["measured"] = {{"area_m2", summary(f.areas)},
                     {"long_side_m", summary(f.long_sides)},
                     {"short_side_m", summary(f.short_sides)},
                     {"wing_depth_m", summary(f.wing_depths)},
                     {"height_m", summary(f.heights)},
                     {"setback_m", summary(f.setbacks)},
                     {"gap_m", summary(f.gaps)}};
    if (f.land_m2 > 0) {
      z["measured"]["coverage_of_land_use"] = std::round(footprint_area / f.land_m2 * 1e4) / 1e4;
      z["measured"]["street_surface_m2"] = std::round(f.street_m2);
      z["measured"]["coverage_of_blocks"] = std::round(footprint_area / block_land_m2(f) * 1e4) / 1e4;
    }
    if (f.frontage_m > 0) z["measured"]["street_frontage_m"] = std::round(f.frontage_m);
    if (!ex["zones"].contains(type) || !ex["zones"][type].is_object()) ex["zones"][type] = ordered_json::object();
    ordered_json& zone = ex["zones"][type];
    ordered_json set = ordered_json::object(), kept = ordered_json::array();
    const ordered_json derived = settings_from_figures(f, sketch.zone_settings.at(t));
    for (const auto& [key, value] : derived.items()) {
      if (zone.contains(key)) {
        kept.push_back(key);
        continue;
      }
      zone[key] = value;
      set[key] = value;
    }
    // Where the place's buildings touch (its median gap under kTouchingGap) they stand in
    // perimeter blocks, which rows of rectangles on lots do not cover as densely (Helsinki's
    // commercial land 29% under its coverage): the frontage rule's perimeter blocks and lots
    // are set too, where the sketch does not set them. Elsewhere it is only reported.
    if (derived.contains("setback"))
      if (ordered_json rule = frontage_rule(f, derived["setback"].get<double>(), derived["building_gap"].get<double>(),
                                                derived["footprint_width"][1].get<double>() * derived["footprint_depth"][1].get<double>());
          !rule.is_null()) {
        z["frontage_rule"] = rule;
        if (derived["building_gap"].get<double>() < kTouchingGap)
          for (const auto& [key, value] : rule.items()) {
            if (zone.contains(key) && !set.contains(key)) {
              if (std::find(kept.begin(), kept.end(), key) == kept.end()) kept.push_back(key);
              continue;
            }
            zone[key] = value;
            set[key] = value;
          }
      }
    z["set"] = set;
    if (!kept.empty()) z["kept_as_the_sketch_sets"] = kept;
    report["zones"][type] = z;
  }
  const std::string text = document_text(doc);
  Sketch measured = parse_sketch(text, sketch.path);
  measured.geojson = text;
  sketch = std::move(measured);
  return report;
}

std::vector<std::string> like_notes(const ordered_json& report) {
  std::vector<std::string> lines;
  const std::string file = report["file"].get<std::string>();
  for (const auto& [type, z] : report["zones"].items()) {
    if (z.contains("kept_defaults")) {
      lines.push_back(file + ": " + type + ": " + std::to_string(z["buildings"].get<int>()) +
                      " mapped buildings, too few to measure; its defaults were kept");
      continue;
    }
    const ordered_json& a = z["measured"]["area_m2"];
    std::string set;
    for (const auto& [key, value] : z["set"].items()) set += (set.empty() ? "" : ", ") + key + " " + value.dump();
    lines.push_back(file + ": " + type + ": " + std::to_string(z["buildings"].get<int>()) +
                    " mapped buildings, footprint median " + format_number(a["median"].get<double>()) + " m2, p90 " +
                    format_number(a["p90"].get<double>()) + " m2; set " + (set.empty() ? "nothing" : set));
  }
  return lines;
}

}  // namespace exacity
