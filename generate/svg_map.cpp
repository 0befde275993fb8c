#include "generate/svg_map.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include "generate/errors.h"

namespace exacity {
namespace {

const std::map<std::string, const char*> kZoneColours = {
    {"residential", "#f2c9a0"}, {"commercial", "#a9c8ec"}, {"industrial", "#cdb89a"}, {"park", "#a8d38d"}};

struct Frame {
  geom::Box box{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  void add(geom::Vec2 p) {
    box.min_x = std::min(box.min_x, p.x), box.min_y = std::min(box.min_y, p.y);
    box.max_x = std::max(box.max_x, p.x), box.max_y = std::max(box.max_y, p.y);
  }
};

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

}  // namespace

void write_svg_map(const CityLayers& layers, const std::filesystem::path& file) {
  Frame frame;
  for (const Layer* l : {&layers.zones, &layers.water, &layers.road_areas})
    for (const auto& f : l->features)
      for (auto p : f.polygon.outer) frame.add(p);
  for (const auto& f : layers.roads.features)
    for (auto p : f.line) frame.add(p);
  geom::Box b = frame.box;
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
  polygons(layers.water, "water", [](const VectorFeature&) { return "#5b9bd5"; });
  polygons(layers.road_areas, "road_areas",
           [](const VectorFeature& f) { return f.properties.value("bridge", false) ? "#3a3a3a" : "#6b6b6b"; });
  out << "<g class=\"roads\" fill=\"none\" stroke=\"#ffffff\" stroke-width=\"" << format_number(stroke)
      << "\" stroke-dasharray=\"" << format_number(stroke * 6) << ',' << format_number(stroke * 4) << "\">\n";
  for (const auto& f : layers.roads.features) {
    out << "<polyline points=\"";
    for (std::size_t i = 0; i < f.line.size(); ++i) out << (i ? " " : "") << point(f.line[i], b);
    out << "\"/>\n";
  }
  out << "</g>\n</svg>\n";
}

}  // namespace exacity
