#include "generate/export/svg_map.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <ostream>
#include <vector>

#include "generate/cancel.h"
#include "generate/city/palette.h"
#include "generate/errors.h"
#include "generate/export/geojson.h"

namespace exacity {
namespace {

// y flips so north is up; coordinates stay exact relative to the frame's corner.
std::string point(geom::Vec2 p, const geom::Box& b) {
  return format_number(p.x - b.min_x) + "," + format_number(b.max_y - p.y);
}

// Every feature of the map passes here: the place to stop a cancelled build.
std::string path_data(const geom::Polygon& poly, const geom::Box& b) {
  CancelCheck().check();
  std::string d;
  auto ring = [&](const geom::Ring& r) {
    for (std::size_t i = 0; i < r.size(); ++i) d += i ? 'L' : 'M', d += point(r[i], b);
    d += "Z";
  };
  ring(poly.outer);
  for (const auto& h : poly.holes) ring(h);
  return d;
}

// A key to the colours and a scale bar, sized in screen pixels (px world units each).
void write_legend(std::ostream& out, const Ground& ground, bool structures, bool clutter, double w, double h,
                  double px) {
  std::vector<std::pair<std::string, std::string>> keys;
  const bool green_blocks = std::any_of(ground.blocks.begin(), ground.blocks.end(), [](const BlockArea& b) { return b.green; });
  // Not a structured binding: clang 14 (the fuzz preset's) cannot capture one in a lambda.
  for (const auto& zone_colour : map_zone_colours()) {
    const auto& zone = zone_colour.first;
    if (std::any_of(ground.zones.begin(), ground.zones.end(), [&](const ZoneArea& z) { return name(z.type) == zone; }) ||
        (zone == "park" && green_blocks))
      keys.emplace_back(zone, zone_colour.second);
  }
  if (!ground.water.empty()) keys.emplace_back("water", kMapWater);
  if (!ground.lots.empty()) keys.emplace_back("lot", kMapLot);
  if (structures) keys.emplace_back("building", kMapBuilding);
  if (!ground.road_areas.empty()) keys.emplace_back("road", kMapRoad);
  auto any_area = [&](auto test) { return std::any_of(ground.road_areas.begin(), ground.road_areas.end(), test); };
  if (any_area([](const RoadArea& a) { return a.bridge; })) keys.emplace_back("bridge", kMapBridge);
  if (any_area([](const RoadArea& a) { return a.surface == RoadSurface::Sidewalk; }))
    keys.emplace_back("sidewalk", kMapSidewalk);
  if (clutter) keys.emplace_back("street clutter", kMapClutter);
  auto n = [&](double pixels) { return format_number(pixels * px); };
  double line = 20, x = 10, y = h / px - 10 - line * (keys.size() + 1);
  out << "<g class=\"legend\" font-family=\"sans-serif\" font-size=\"" << n(13) << "\">\n"
      << "<rect x=\"" << n(x - 6) << "\" y=\"" << n(y - 6) << "\" width=\"" << n(150) << "\" height=\""
      << n(line * (keys.size() + 1) + 8) << "\" fill=\"#ffffff\" fill-opacity=\"0.85\"/>\n";
  for (const auto& [label, colour] : keys) {
    out << "<rect x=\"" << n(x) << "\" y=\"" << n(y) << "\" width=\"" << n(14) << "\" height=\"" << n(14)
        << "\" fill=\"" << colour << "\"/><text x=\"" << n(x + 22) << "\" y=\"" << n(y + 12) << "\">" << label
        << "</text>\n";
    y += line;
  }
  // Scale bar: 1, 2 or 5 times a power of ten, about a fifth of the map wide.
  double target = w / 5, step = std::pow(10, std::floor(std::log10(target)));
  double metres = target >= 5 * step ? 5 * step : target >= 2 * step ? 2 * step : step;
  out << "<rect x=\"" << n(x) << "\" y=\"" << n(y + 4) << "\" width=\"" << format_number(std::min(metres, w))
      << "\" height=\"" << n(4) << "\" fill=\"#222222\"/><text x=\"" << n(x) << "\" y=\"" << n(y + 20)
      << "\" font-size=\"" << n(11) << "\">" << format_number(metres) << " m</text>\n</g>\n";
}

}  // namespace

void write_svg_map(const Ground& ground, const std::vector<Building>& buildings,
                   const std::vector<ModelInstance>& models, const std::filesystem::path& file,
                   const std::vector<Clutter>& clutter) {
  geom::Box b = ground.bounds();
  for (const RoadLine& r : ground.roads)
    for (auto p : r.line) b.add(p);
  if (!(b.max_x > b.min_x)) b = {0, 0, 1, 1};
  double w = b.width(), h = std::max(b.height(), 1e-9);
  double px_w = 1200, px_h = std::max(1.0, std::round(px_w * h / w));
  double stroke = w / px_w;  // one pixel at the default size

  std::ofstream out(file, std::ios::binary);
  if (!out) throw UserError(file.string() + ": cannot write this file; check the output folder's permissions");
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << px_w << "\" height=\"" << px_h
      << "\" viewBox=\"0 0 " << format_number(w) << ' ' << format_number(h) << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"" << kMapBackground << "\"/>\n";
  auto polygons = [&](const auto& features, const char* cls, auto polygon_of, auto fill_of) {
    out << "<g class=\"" << cls << "\" stroke-width=\"" << format_number(stroke * 0.5) << "\">\n";
    for (const auto& f : features)
      out << "<path fill-rule=\"evenodd\" fill=\"" << fill_of(f) << "\" stroke=\"" << fill_of(f) << "\" d=\""
          << path_data(polygon_of(f), b) << "\"/>\n";
    out << "</g>\n";
  };
  polygons(
      ground.zones, "zones", [](const ZoneArea& z) -> const geom::Polygon& { return z.polygon; },
      [](const ZoneArea& z) {
        auto it = map_zone_colours().find(std::string(name(z.type)));
        return it == map_zone_colours().end() ? "#dddddd" : it->second;
      });
  // Green space inside zones (a grammar's parks, blocks too small or thin to build on).
  std::vector<const BlockArea*> green;
  for (const BlockArea& block : ground.blocks)
    if (block.green) green.push_back(&block);
  polygons(
      green, "parks", [](const BlockArea* block) -> const geom::Polygon& { return block->polygon; },
      [](const BlockArea*) { return map_zone_colours().at("park"); });
  out << "<g class=\"lots\" fill=\"" << kMapLotFill << "\" fill-opacity=\"0.55\" stroke=\"" << kMapLotEdge << "\" stroke-width=\""
      << format_number(stroke * 0.5) << "\">\n";
  for (const LotArea& lot : ground.lots) out << "<path fill-rule=\"evenodd\" d=\"" << path_data(lot.polygon, b) << "\"/>\n";
  out << "</g>\n";
  out << "<g class=\"buildings\" fill=\"" << kMapBuilding << "\" stroke=\"" << kMapBuildingEdge << "\" stroke-width=\"" << format_number(stroke * 0.5)
      << "\">\n";
  auto footprint = [&](const auto& s) { out << "<path fill-rule=\"evenodd\" d=\"" << path_data(s.polygon, b) << "\"/>\n"; };
  for_each_by_id(buildings, models, footprint, footprint);
  out << "</g>\n";
  polygons(
      ground.water, "water", [](const geom::Polygon& p) -> const geom::Polygon& { return p; },
      [](const geom::Polygon&) { return kMapWater; });
  polygons(
      ground.road_areas, "road_areas", [](const RoadArea& a) -> const geom::Polygon& { return a.polygon; },
      [](const RoadArea& a) {
        if (a.surface == RoadSurface::Sidewalk) return kMapSidewalk;
        return a.bridge ? kMapBridge : kMapRoad;
      });
  out << "<g class=\"roads\" fill=\"none\" stroke=\"" << kMapCentreLine << "\" stroke-width=\"" << format_number(stroke)
      << "\" stroke-dasharray=\"" << format_number(stroke * 6) << ',' << format_number(stroke * 4) << "\">\n";
  for (const RoadLine& r : ground.roads) {
    out << "<polyline points=\"";
    for (std::size_t i = 0; i < r.line.size(); ++i) out << (i ? " " : "") << point(r.line[i], b);
    out << "\"/>\n";
  }
  out << "</g>\n";
  out << "<g class=\"clutter\" fill=\"" << kMapClutter << "\">\n";
  for (const Clutter& c : clutter) {
    const std::string at = point(c.spot, b);
    const std::size_t comma = at.find(',');
    out << "<circle cx=\"" << at.substr(0, comma) << "\" cy=\"" << at.substr(comma + 1) << "\" r=\""
        << format_number(stroke * 1.5) << "\"/>\n";
  }
  out << "</g>\n";
  write_legend(out, ground, !buildings.empty() || !models.empty(), !clutter.empty(), w, h, stroke);
  out << "</svg>\n";
}

}  // namespace exacity
