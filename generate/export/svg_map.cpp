#include "generate/export/svg_map.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <ostream>
#include <vector>

#include "generate/errors.h"

namespace exacity {
namespace {

const std::map<std::string, const char*> kZoneColours = {
    {"residential", "#f2c9a0"}, {"commercial", "#a9c8ec"}, {"industrial", "#cdb89a"}, {"park", "#a8d38d"}};

// y flips so north is up; coordinates stay exact relative to the frame's corner.
std::string point(geom::Vec2 p, const geom::Box& b) {
  return format_number(p.x - b.min_x) + "," + format_number(b.max_y - p.y);
}

std::string path_data(const geom::Polygon& poly, const geom::Box& b) {
  std::string d;
  auto ring = [&](const geom::Ring& r) {
    for (std::size_t i = 0; i < r.size(); ++i) d += (i ? "L" : "M") + point(r[i], b);
    d += "Z";
  };
  ring(poly.outer);
  for (const auto& h : poly.holes) ring(h);
  return d;
}

// A key to the colours and a scale bar, sized in screen pixels (px world units each).
void write_legend(std::ostream& out, const CityLayers& layers, double w, double h, double px) {
  std::vector<std::pair<std::string, std::string>> keys;
  for (const auto& [zone, colour] : kZoneColours)
    for (const auto& f : layers.zones.features)
      if (f.properties.value("zone", "") == zone) {
        keys.emplace_back(zone, colour);
        break;
      }
  if (!layers.water.features.empty()) keys.emplace_back("water", "#5b9bd5");
  if (!layers.lots.features.empty()) keys.emplace_back("lot", "#f7ecdc");
  if (!layers.buildings.features.empty()) keys.emplace_back("building", "#9a8672");
  if (!layers.road_areas.features.empty()) keys.emplace_back("road", "#6b6b6b");
  for (const auto& f : layers.road_areas.features)
    if (f.properties.value("bridge", false)) {
      keys.emplace_back("bridge", "#3a3a3a");
      break;
    }
  for (const auto& f : layers.road_areas.features)
    if (f.properties.value("surface", "") == "sidewalk") {
      keys.emplace_back("sidewalk", "#c9c3b8");
      break;
    }
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

void write_svg_map(const CityLayers& layers, const std::filesystem::path& file) {
  geom::Box b = layers.ground_bounds();
  for (const auto& f : layers.roads.features)
    for (auto p : f.line) b.add(p);
  if (!(b.max_x > b.min_x)) b = {0, 0, 1, 1};
  double w = b.width(), h = std::max(b.height(), 1e-9);
  double px_w = 1200, px_h = std::max(1.0, std::round(px_w * h / w));
  double stroke = w / px_w;  // one pixel at the default size

  std::ofstream out(file, std::ios::binary);
  if (!out) throw UserError(file.string() + ": cannot write this file; check the output folder's permissions");
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << px_w << "\" height=\"" << px_h
      << "\" viewBox=\"0 0 " << format_number(w) << ' ' << format_number(h) << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#f4f4f0\"/>\n";
  auto polygons = [&](const Layer& layer, const char* cls, auto fill_of) {
    out << "<g class=\"" << cls << "\" stroke-width=\"" << format_number(stroke * 0.5) << "\">\n";
    for (const auto& f : layer.features)
      out << "<path fill-rule=\"evenodd\" fill=\"" << fill_of(f) << "\" stroke=\"" << fill_of(f) << "\" d=\""
          << path_data(f.polygon, b) << "\"/>\n";
    out << "</g>\n";
  };
  polygons(layers.zones, "zones", [](const VectorFeature& f) {
    auto it = kZoneColours.find(f.properties.value("zone", ""));
    return it == kZoneColours.end() ? "#dddddd" : it->second;
  });
  out << "<g class=\"lots\" fill=\"#fbf3e6\" fill-opacity=\"0.55\" stroke=\"#8a6d4b\" stroke-width=\""
      << format_number(stroke * 0.5) << "\">\n";
  for (const auto& f : layers.lots.features) out << "<path fill-rule=\"evenodd\" d=\"" << path_data(f.polygon, b) << "\"/>\n";
  out << "</g>\n";
  out << "<g class=\"buildings\" fill=\"#9a8672\" stroke=\"#5e4f40\" stroke-width=\"" << format_number(stroke * 0.5)
      << "\">\n";
  for (const auto& f : layers.buildings.features) out << "<path fill-rule=\"evenodd\" d=\"" << path_data(f.polygon, b) << "\"/>\n";
  out << "</g>\n";
  polygons(layers.water, "water", [](const VectorFeature&) { return "#5b9bd5"; });
  polygons(layers.road_areas, "road_areas", [](const VectorFeature& f) {
    if (f.properties.value("surface", "") == "sidewalk") return "#c9c3b8";
    return f.properties.value("bridge", false) ? "#3a3a3a" : "#6b6b6b";
  });
  out << "<g class=\"roads\" fill=\"none\" stroke=\"#ffffff\" stroke-width=\"" << format_number(stroke)
      << "\" stroke-dasharray=\"" << format_number(stroke * 6) << ',' << format_number(stroke * 4) << "\">\n";
  for (const auto& f : layers.roads.features) {
    out << "<polyline points=\"";
    for (std::size_t i = 0; i < f.line.size(); ++i) out << (i ? " " : "") << point(f.line[i], b);
    out << "\"/>\n";
  }
  out << "</g>\n";
  write_legend(out, layers, w, h, stroke);
  out << "</svg>\n";
}

}  // namespace exacity
