#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace render {
namespace {

constexpr float kDegree = kPi / 180;

}  // namespace

Camera Camera::orbit(V3 target, float azimuth_deg, float elevation_deg, float distance, float fov_y) {
  const float az = azimuth_deg * kDegree, el = std::clamp(elevation_deg, 1.0f, 90.0f) * kDegree;
  V3 offset{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  return {target + offset * distance, target, fov_y};
}

Camera Camera::look(V3 from, V3 to, float fov_y) { return {from, to, fov_y}; }

CameraSpecText CameraSpecText::split(const std::string& spec) {
  auto colon = spec.find(':');
  if (colon == std::string::npos) throw std::invalid_argument("expected KIND:KEY=VALUE,...");
  CameraSpecText text;
  text.kind = spec.substr(0, colon);
  std::stringstream rest(spec.substr(colon + 1));
  std::string item;
  while (std::getline(rest, item, ',')) {
    auto eq = item.find('=');
    std::string value = item;
    if (eq != std::string::npos) text.keys.push_back({item.substr(0, eq), {}}), value = item.substr(eq + 1);
    if (text.keys.empty()) throw std::invalid_argument("\"" + item + "\" has no key");
    try {
      std::size_t used = 0;
      const float number = std::stof(value, &used);
      if (used != value.size() || !std::isfinite(number)) throw std::invalid_argument("");
      text.keys.back().second.push_back(number);
    } catch (const std::exception&) {
      throw std::invalid_argument("\"" + value + "\" is not a number");
    }
    if (std::abs(text.keys.back().second.back()) > kLargestCameraNumber)
      throw std::invalid_argument(text.keys.back().first + "=" + value + " is outside -1e9 to 1e9");
  }
  return text;
}

bool CameraSpecText::has(const std::string& key) const {
  for (const auto& [k, v] : keys)
    if (k == key) return true;
  return false;
}

std::vector<float> CameraSpecText::get(const std::string& key, std::size_t n) const {
  for (const auto& [k, v] : keys)
    if (k == key) {
      if (v.size() != n)
        throw std::invalid_argument(key + " needs " + std::to_string(n) + " number" + (n > 1 ? "s" : ""));
      return v;
    }
  throw std::invalid_argument("missing " + key + "=");
}

float CameraSpecText::get_or(const std::string& key, float otherwise) const {
  return has(key) ? get(key, 1)[0] : otherwise;
}

void CameraSpecText::only(const std::vector<std::string>& known) const {
  for (const auto& [k, v] : keys)
    if (std::find(known.begin(), known.end(), k) == known.end()) {
      std::string list;
      for (const std::string& key : known) list += (list.empty() ? "" : ", ") + key + "=";
      throw std::invalid_argument("unknown key " + k + "= for " + kind + " (it takes " + list + ")");
    }
}

Camera Camera::parse(const std::string& spec, float fov_y) {
  const CameraSpecText text = CameraSpecText::split(spec);
  if (text.kind == "orbit") {
    auto t = text.get("target", 3);
    if (!(text.get("distance", 1)[0] >= kNearestTarget))
      throw std::invalid_argument("distance= must be at least 0.01 (m)");
    return orbit({t[0], t[1], t[2]}, text.get("azimuth", 1)[0], text.get("elevation", 1)[0], text.get("distance", 1)[0],
                 fov_y);
  }
  if (text.kind == "look") {
    auto f = text.get("from", 3), t = text.get("to", 3);
    const V3 from{f[0], f[1], f[2]}, to{t[0], t[1], t[2]};
    if (!(length(to - from) >= kNearestTarget))
      throw std::invalid_argument("from and to are the same point, or under 0.01 m apart");
    return look(from, to, fov_y);
  }
  throw std::invalid_argument("unknown camera \"" + text.kind + "\"; use orbit or look");
}

V3 Camera::right() const {
  V3 f = forward(), r = cross(f, V3{0, 0, 1});
  if (length(r) < 1e-6f) r = cross(f, V3{0, 1, 0});  // straight down: north is up in the image
  return normalize(r);
}

void Camera::ray(float px, float py, int width, int height, V3& origin, V3& direction) const {
  Lens(*this, width, height).ray(px, py, origin, direction);
}

Lens::Lens(const Camera& c, int width, int height)
    : from_(c.from),
      forward_(c.forward()),
      right_(c.right()),
      width_(static_cast<float>(width)),
      height_(static_cast<float>(height)),
      orthographic_(c.orthographic) {
  up_ = cross(right_, forward_);
  const float aspect = width_ / height_;
  // Half the image's extent: in metres (orthographic) or as the tangent of half the view.
  half_y_ = orthographic_ ? c.ortho_height / 2 : std::tan(c.fov_y * kDegree / 2);
  half_x_ = half_y_ * aspect;
  const DepthOfField& dof = c.depth_of_field;
  if (dof.aperture > 0 && !orthographic_) {
    radius_ = dof.aperture / 2;
    const float distance = dof.focus_distance > 0 ? dof.focus_distance : length(c.to - c.from);
    const float tilt = dof.focus_tilt * kDegree;
    // The plane through the point `distance` ahead, its normal turned from the view
    // towards the image's bottom by the tilt.
    focus_normal_ = normalize(forward_ * std::cos(tilt) - up_ * std::sin(tilt));
    focus_offset_ = distance * std::cos(tilt);
  }
}

void Lens::ray(float px, float py, V3& origin, V3& direction) const {
  const float sx = 2 * px / width_ - 1, sy = 1 - 2 * py / height_;
  if (orthographic_) {
    origin = from_ + right_ * (sx * half_x_) + up_ * (sy * half_y_);
    direction = forward_;
    return;
  }
  origin = from_;
  direction = normalize(forward_ + right_ * (sx * half_x_) + up_ * (sy * half_y_));
}

void Lens::ray(float px, float py, float u, float v, V3& origin, V3& direction) const {
  ray(px, py, origin, direction);
  if (radius_ <= 0 || orthographic_) return;
  // Shirley and Chiu's concentric map of the square onto the disk keeps strata apart.
  const float a = 2 * u - 1, b = 2 * v - 1;
  float r = 0, phi = 0;
  if (a != 0 || b != 0) {
    if (std::abs(a) > std::abs(b))
      r = a, phi = kPi / 4 * (b / a);
    else
      r = b, phi = kPi / 2 - kPi / 4 * (a / b);
  }
  const V3 on_lens = right_ * (radius_ * r * std::cos(phi)) + up_ * (radius_ * r * std::sin(phi));
  // Every ray of the pixel passes through the point where the centre's ray meets the plane
  // in focus; a ray parallel to the plane, or meeting it behind, is focused at infinity.
  const float along = dot(focus_normal_, direction);
  origin = from_ + on_lens;
  if (along > 1e-6f * focus_offset_) direction = normalize(direction * (focus_offset_ / along) - on_lens);
}

float overview_height(const geom::Box& city, float fov_y, float aspect) {
  const double map_height = std::max(city.height(), city.width() / aspect);
  return static_cast<float>(map_height / (2 * std::tan(fov_y * kDegree / 2)));
}

Camera overview_camera(const geom::Box& city, float top, float fov_y, float aspect, bool orthographic) {
  const V3 centre{static_cast<float>((city.min_x + city.max_x) / 2), static_cast<float>((city.min_y + city.max_y) / 2),
                  top};
  Camera c{centre + V3{0, 0, overview_height(city, fov_y, aspect)}, centre, fov_y};
  c.orthographic = orthographic;
  c.ortho_height = static_cast<float>(std::max(city.height(), city.width() / aspect));
  return c;
}

std::vector<geom::Vec2> ground_footprint(const Camera& camera, int width, int height, float ground,
                                         const geom::Box& bounds) {
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  const float corners[4][2] = {{0, h}, {w, h}, {w, 0}, {0, 0}};  // bottom-left, bottom-right, top-right, top-left
  V3 o[4], d[4];
  for (int i = 0; i < 4; ++i) camera.ray(corners[i][0], corners[i][1], width, height, o[i], d[i]);
  auto on_ground = [&](int i) {
    float t = (ground - o[i].z) / d[i].z;
    V3 p = o[i] + d[i] * t;
    return geom::Vec2{p.x, p.y};
  };
  std::vector<geom::Vec2> quad(4);
  for (int i = 0; i < 2; ++i) quad[i] = on_ground(i);  // the lower rays point down
  for (int i = 2; i < 4; ++i) {
    if (d[i].z < 0) {
      quad[i] = on_ground(i);
      continue;
    }
    // Follow the lower ray on this side (top-right: bottom-right) along the ground to the
    // bounds' far edge: the slab test's exit parameter.
    const int lower = i == 2 ? 1 : 0;
    const geom::Vec2 start = quad[lower];
    const double dx = d[lower].x, dy = d[lower].y;
    double exit = INFINITY;
    if (dx > 0) exit = std::min(exit, (bounds.max_x - start.x) / dx);
    if (dx < 0) exit = std::min(exit, (bounds.min_x - start.x) / dx);
    if (dy > 0) exit = std::min(exit, (bounds.max_y - start.y) / dy);
    if (dy < 0) exit = std::min(exit, (bounds.min_y - start.y) / dy);
    if (!std::isfinite(exit) || exit < 0) exit = 0;
    quad[i] = {start.x + dx * exit, start.y + dy * exit};
  }
  return quad;
}

}  // namespace render
