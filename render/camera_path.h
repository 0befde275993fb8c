// A camera path (render/README.md, Camera paths): cameras keyed at times, in between on
// splines through the keys, sampled into frames at a frame rate. The file:
//   {"fps": 24, "keys": [{"t": 0, "camera": "orbit:..."}, {"t": 4, "camera": "look:..."}]}
// with the camera syntax of --camera (parse_camera_spec). Pedestrian and flyer keys stand on
// the city's ground, so a path is placed on a city (CameraPath::place) before its frames.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "generate/city.h"
#include "render/camera_spec.h"

namespace render {

struct CameraKey {
  double t = 0;  // seconds
  CameraSpec spec;
  Camera camera;  // the spec's camera, placed on the city's ground for pedestrians and flyers
};

struct CameraPath {
  double fps = 24;
  std::vector<CameraKey> keys;          // times strictly increasing, at least one
  const exacity::City* city = nullptr;  // the ground the keys stand on, once placed

  // Places the pedestrian and flyer keys on the city's ground; throws
  // std::invalid_argument naming `file` and the key (a road the city does not have).
  void place(const exacity::City& on, const std::string& file);

  // Frame n is at the first key's time plus n / fps; the last one at or before the last key.
  int frame_count() const;
  Camera frame(int n) const;
  // Between keys i and i + 1, the eye and the target each follow a cubic Hermite segment
  // whose tangents are the keys' neighbours' differences over their time apart
  // (Catmull-Rom for uneven key times; one-sided at the ends): it passes through every key
  // and its velocity is continuous at them. The field of view goes linearly. Between two
  // keys on the ground (pedestrian, flyer) the eye and the target keep their heights over
  // the terrain, each going linearly from one key's to the next's; between two pedestrian
  // keys on the same road the eye walks its centre line, the distance along it, the look
  // ahead and the eye height going linearly.
  Camera at(double t) const;
};

// Parses a path file's text; `file` names it in errors. Throws std::invalid_argument with
// one line naming the file and the key that is wrong.
CameraPath parse_camera_path(const std::string& text, const std::string& file, float fov_y);
CameraPath load_camera_path(const std::filesystem::path& file, float fov_y);

}  // namespace render
