#include "render/camera_spec.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace render {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180;
constexpr double kFlyerLook = 100;  // m from a flyer's eye to its target, where it focuses

// The point `s` metres along the line from its first point; before the start and past the
// end it carries on along the first or last segment, so a look ahead past the end still
// looks the way the road went.
geom::Vec2 point_along(const geom::Polyline& line, double s) {
  std::size_t last = 0;
  double walked = 0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const double len = std::hypot(line[i + 1].x - line[i].x, line[i + 1].y - line[i].y);
    if (len == 0) continue;
    const bool first_segment = walked == 0;
    if ((s < 0 && first_segment) || s <= walked + len) {
      const double f = (s - walked) / len;
      return {line[i].x + (line[i + 1].x - line[i].x) * f, line[i].y + (line[i + 1].y - line[i].y) * f};
    }
    walked += len, last = i;
  }
  const geom::Vec2 a = line[last], b = line[last + 1];
  const double len = std::hypot(b.x - a.x, b.y - a.y), f = (s - walked + len) / len;
  return {a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f};
}

double line_length(const geom::Polyline& line) {
  double len = 0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    len += std::hypot(line[i + 1].x - line[i].x, line[i + 1].y - line[i].y);
  return len;
}

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

void check_range(const char* key, double value, double low, double high) {
  // The spec's numbers are floats: the bounds are too, or "pitch=89.9" would be outside 89.9.
  if (!(value >= static_cast<float>(low) && value <= static_cast<float>(high)))
    throw std::invalid_argument(std::string(key) + "=" + number(value) + " is outside " + number(low) + " to " +
                                number(high));
}

// Eye height over the terrain, as a pedestrian's.
double eye_height(const CameraSpecText& t) {
  const double eye = t.get_or("eye", 1.7f);
  check_range("eye", eye, 0.1, 100);
  return eye;
}

}  // namespace

CameraSpec parse_camera_spec(const std::string& text, float fov_y) {
  CameraSpec spec;
  spec.text = text, spec.fov_y = fov_y;
  const CameraSpecText t = CameraSpecText::split(text);
  if (t.kind == "orbit" || t.kind == "look") {
    spec.fixed = Camera::parse(text, fov_y);
    return spec;
  }
  if (t.kind == "pedestrian" && t.has("road")) {
    t.only({"road", "along", "ahead", "eye"});
    spec.kind = CameraSpec::Kind::Pedestrian;
    const float road = t.get("road", 1)[0];
    if (road < 0 || road != std::floor(road) || road > 1e8f)
      throw std::invalid_argument("road=" + number(road) + " is not a road id (0, 1, 2, ...)");
    spec.road = static_cast<int>(road);
    spec.along = t.get("along", 1)[0];
    check_range("along", spec.along, 0, 1e8);
    spec.ahead = t.get_or("ahead", 20);
    if (std::abs(spec.ahead) < 0.1 || std::abs(spec.ahead) > 1e4)
      throw std::invalid_argument("ahead= must be 0.1 to 10000 m either way (negative looks back)");
    spec.height = eye_height(t);
    return spec;
  }
  if (t.kind == "pedestrian" || t.kind == "flyer") {
    const bool flyer = t.kind == "flyer";
    if (flyer)
      t.only({"at", "height", "heading", "pitch"});
    else
      t.only({"at", "heading", "pitch", "eye", "road"});
    spec.kind = flyer ? CameraSpec::Kind::Flyer : CameraSpec::Kind::Pedestrian;
    const auto at = t.get("at", 2);
    spec.x = at[0], spec.y = at[1];
    spec.heading = t.get("heading", 1)[0];
    spec.pitch = t.get_or("pitch", 0);
    check_range("pitch", spec.pitch, -89.9, 89.9);
    if (flyer) {
      spec.height = t.get("height", 1)[0];
      check_range("height", spec.height, 0.1, 1e5);
    } else {
      spec.height = eye_height(t);
    }
    return spec;
  }
  throw std::invalid_argument("unknown camera \"" + t.kind + "\"; use orbit, look, pedestrian or flyer");
}

double ground_height(const exacity::City& city, double x, double y) {
  return city.heightmap() ? city.heightmap()->height_at({x, y}) : 0.0;
}

namespace {

std::string point_text(double x, double y, double z) { return "(" + number(x) + ", " + number(y) + ", " + number(z) + ")"; }

// A camera on the ground stands where the city is, which may be farther out than a spec's
// numbers may say: the renderer's rays are floats, and Embree aborts on a ray from past
// about 1e18 or with no direction (an eye and a target that round to one float point).
Camera within_reach(double x, double y, double z, V3 to, float fov_y) {
  if (!(std::abs(x) <= kLargestCameraNumber && std::abs(y) <= kLargestCameraNumber &&
        std::abs(z) <= kLargestCameraNumber))
    throw std::invalid_argument("the eye at " + point_text(x, y, z) +
                                " lies outside -1e9 to 1e9, where the renderer can place a camera; generate the city "
                                "nearer the origin");
  const V3 from{static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
  if (!(length(to - from) >= kNearestTarget))
    throw std::invalid_argument("the eye at " + point_text(x, y, z) +
                                " and the point it looks at are one point in the renderer's floats (the city is too "
                                "far from the origin for them); generate the city nearer the origin");
  return Camera::look(from, to, fov_y);
}

}  // namespace

Camera place_camera(const CameraSpec& spec, const exacity::City& city) {
  if (spec.kind == CameraSpec::Kind::Fixed) return spec.fixed;
  auto height_at = [&](geom::Vec2 p) { return ground_height(city, p.x, p.y) + spec.height; };
  auto eye_at = [&](geom::Vec2 p) {
    return V3{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(height_at(p))};
  };
  if (spec.road >= 0) {
    const auto& roads = city.ground.roads;
    if (roads.empty())
      throw std::invalid_argument("the city has no roads to stand on; use pedestrian:at=X,Y,heading=DEG instead");
    if (spec.road >= static_cast<int>(roads.size()))
      throw std::invalid_argument("the city has no road " + std::to_string(spec.road) + " (its roads are 0 to " +
                                  std::to_string(static_cast<int>(roads.size()) - 1) +
                                  ", the ids of vector/roads.geojson)");
    const geom::Polyline& line = roads[static_cast<std::size_t>(spec.road)].line;
    const double length = line_length(line);
    if (!(length > 0)) throw std::invalid_argument("road " + std::to_string(spec.road) + " has no length to walk");
    const double along = std::min(spec.along, length);
    // Ahead: as far on along the road (or past its end, the way it went), at eye height there.
    const geom::Vec2 eye = point_along(line, along);
    return within_reach(eye.x, eye.y, height_at(eye), eye_at(point_along(line, along + spec.ahead)), spec.fov_y);
  }
  const V3 eye = eye_at({spec.x, spec.y});
  const double h = spec.heading * kDegree, p = spec.pitch * kDegree;
  const V3 direction{static_cast<float>(std::cos(p) * std::cos(h)), static_cast<float>(std::cos(p) * std::sin(h)),
                     static_cast<float>(std::sin(p))};
  const double look = spec.kind == CameraSpec::Kind::Flyer ? kFlyerLook : 20;
  return within_reach(spec.x, spec.y, height_at({spec.x, spec.y}), eye + direction * static_cast<float>(look),
                      spec.fov_y);
}

}  // namespace render
