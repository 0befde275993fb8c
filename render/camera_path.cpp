#include "render/camera_path.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "generate/input_file.h"

namespace render {
namespace {

V3 eye(const CameraKey& k) { return k.camera.from; }
V3 target(const CameraKey& k) { return k.camera.to; }

// The velocity at key i of a point the keys carry: its neighbours' difference over their
// time apart (one-sided at the ends).
V3 velocity(const std::vector<CameraKey>& keys, std::size_t i, V3 (*point)(const CameraKey&)) {
  const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, keys.size() - 1);
  return (point(keys[b]) - point(keys[a])) / static_cast<float>(keys[b].t - keys[a].t);
}

// The point at time t between keys i and i + 1.
V3 hermite(const std::vector<CameraKey>& keys, std::size_t i, double t, V3 (*point)(const CameraKey&)) {
  const double h = keys[i + 1].t - keys[i].t, s = (t - keys[i].t) / h, s2 = s * s, s3 = s2 * s;
  const float h00 = static_cast<float>(2 * s3 - 3 * s2 + 1), h10 = static_cast<float>(s3 - 2 * s2 + s),
              h01 = static_cast<float>(-2 * s3 + 3 * s2), h11 = static_cast<float>(s3 - s2);
  const float hf = static_cast<float>(h);
  return point(keys[i]) * h00 + velocity(keys, i, point) * (h10 * hf) + point(keys[i + 1]) * h01 +
         velocity(keys, i + 1, point) * (h11 * hf);
}

// The view's direction at s between two keys' directions: the heading the shorter way round,
// the pitch linearly. For where the eye's and the target's curves meet (two keys looking at
// each other's eyes cross half-way), which leaves the view no direction.
V3 turned_between(V3 a, V3 b, double s) {
  const double heading_a = std::atan2(a.y, a.x), pitch_a = std::asin(std::clamp(a.z, -1.0f, 1.0f));
  double turn = std::atan2(b.y, b.x) - heading_a;
  turn -= 2 * M_PI * std::round(turn / (2 * M_PI));
  const double heading = heading_a + turn * s,
               pitch = pitch_a + (std::asin(std::clamp(b.z, -1.0f, 1.0f)) - pitch_a) * s;
  return {static_cast<float>(std::cos(pitch) * std::cos(heading)), static_cast<float>(std::cos(pitch) * std::sin(heading)),
          static_cast<float>(std::sin(pitch))};
}

[[noreturn]] void fail(const std::string& file, const std::string& where, const std::string& what) {
  throw std::invalid_argument(file + ": " + where + (where.empty() ? "" : ": ") + what +
                              "; expected {\"fps\": 24, \"keys\": [{\"t\": 0, \"camera\": \"orbit:...\"}, ...]}");
}

}  // namespace

int CameraPath::frame_count() const {
  const double span = keys.back().t - keys.front().t;
  return static_cast<int>(std::floor(span * fps + 1e-9)) + 1;
}

Camera CameraPath::frame(int n) const { return at(keys.front().t + n / fps); }

void CameraPath::place(const exacity::City& on, const std::string& file) {
  for (std::size_t i = 0; i < keys.size(); ++i) try {
      keys[i].camera = place_camera(keys[i].spec, on);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(file + ": keys[" + std::to_string(i) + "]: camera \"" + keys[i].spec.text +
                                  "\": " + e.what());
    }
  city = &on;
}

Camera CameraPath::at(double t) const {
  if (keys.size() == 1 || t <= keys.front().t) return keys.front().camera;
  if (t >= keys.back().t) return keys.back().camera;
  std::size_t i = 0;
  while (keys[i + 1].t < t) ++i;
  const CameraKey &a = keys[i], &b = keys[i + 1];
  const double s = (t - a.t) / (b.t - a.t);
  auto mix = [s](double from, double to) { return from + (to - from) * s; };
  const float fov = static_cast<float>(mix(a.camera.fov_y, b.camera.fov_y));
  if (city && a.spec.road >= 0 && a.spec.road == b.spec.road) {
    CameraSpec walk = a.spec;
    walk.along = mix(a.spec.along, b.spec.along), walk.ahead = mix(a.spec.ahead, b.spec.ahead);
    walk.height = mix(a.spec.height, b.spec.height), walk.fov_y = fov;
    Camera c = place_camera(walk, *city);
    c.depth_of_field = a.camera.depth_of_field;
    return c;
  }
  Camera c = a.camera;
  c.from = hermite(keys, i, t, eye), c.to = hermite(keys, i, t, target);
  c.fov_y = fov;
  // Next to a key on the ground the eye keeps over the terrain: its height over it goes from
  // one key's to the other's, where a curve through the two eyes could run into a hill.
  // Between the air and the ground it eases in and out, so the walk starts at a standstill.
  if (city && (a.spec.on_ground() || b.spec.on_ground())) {
    const double w = a.spec.on_ground() && b.spec.on_ground() ? s : s * s * (3 - 2 * s);
    auto over_ground = [&](V3 p) { return p.z - ground_height(*city, p.x, p.y); };
    auto onto_ground = [&](V3& p, double from, double to) {
      p.z = static_cast<float>(ground_height(*city, p.x, p.y) + from + (to - from) * w);
    };
    onto_ground(c.from, over_ground(a.camera.from), over_ground(b.camera.from));
    onto_ground(c.to, over_ground(a.camera.to), over_ground(b.camera.to));
  }
  if (!(length(c.to - c.from) >= kNearestTarget)) c.to = c.from + turned_between(a.camera.forward(), b.camera.forward(), s);
  return c;
}

CameraPath parse_camera_path(const std::string& text, const std::string& file, float fov_y) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) fail(file, "", "not a JSON object");
  CameraPath path;
  if (!j.contains("fps") || !j["fps"].is_number() || !(j["fps"].get<double>() > 0) || j["fps"].get<double>() > 1000)
    fail(file, "\"fps\"", "missing or not a number in (0, 1000]");
  path.fps = j["fps"].get<double>();
  if (!j.contains("keys") || !j["keys"].is_array() || j["keys"].empty())
    fail(file, "\"keys\"", "missing or not a non-empty array");
  const nlohmann::json& keys = j["keys"];
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string where = "keys[" + std::to_string(i) + "]";
    const nlohmann::json& k = keys[i];
    if (!k.is_object() || !k.contains("t") || !k["t"].is_number() || !std::isfinite(k["t"].get<double>()))
      fail(file, where, "no \"t\" number (seconds)");
    if (!k.contains("camera") || !k["camera"].is_string()) fail(file, where, "no \"camera\" string");
    CameraKey key;
    key.t = k["t"].get<double>();
    if (!path.keys.empty() && key.t <= path.keys.back().t)
      fail(file, where, "t " + k["t"].dump() + " is not after the key before's");
    try {
      key.spec = parse_camera_spec(k["camera"].get<std::string>(), fov_y);
      key.camera = key.spec.fixed;
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(file + ": " + where + ": camera \"" + k["camera"].get<std::string>() +
                                  "\": " + e.what());
    }
    path.keys.push_back(key);
  }
  // In doubles: a span of 1e300 s would overflow frame_count's int.
  if ((path.keys.back().t - path.keys.front().t) * path.fps >= 1000000)
    fail(file, "", "more than a million frames (the keys' span in seconds times \"fps\")");
  return path;
}

CameraPath load_camera_path(const std::filesystem::path& file, float fov_y) {
  std::string text, why;
  if (!exacity::read_input(file, exacity::kMaxSettingsFileBytes, text, why))
    throw std::invalid_argument(file.string() + ": cannot read the camera path (" + why + "); give a camera path's JSON file to --path");
  return parse_camera_path(text, file.string(), fov_y);
}

}  // namespace render
