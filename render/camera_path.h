// A camera path (render/README.md, Camera paths): cameras keyed at times, in between on
// splines through the keys, sampled into frames at a frame rate. The file:
//   {"fps": 24, "keys": [{"t": 0, "camera": "orbit:..."}, {"t": 4, "camera": "look:..."}]}
// with the camera syntax of --camera (Camera::parse).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/camera.h"

namespace render {

struct CameraKey {
  double t = 0;  // seconds
  Camera camera;
};

struct CameraPath {
  double fps = 24;
  std::vector<CameraKey> keys;  // times strictly increasing, at least one

  // Frame n is at the first key's time plus n / fps; the last one at or before the last key.
  int frame_count() const;
  Camera frame(int n) const;
  // Between keys i and i + 1, the eye and the target each follow a cubic Hermite segment
  // whose tangents are the keys' neighbours' differences over their time apart
  // (Catmull-Rom for uneven key times; one-sided at the ends): it passes through every key
  // and its velocity is continuous at them. The field of view goes linearly.
  Camera at(double t) const;
};

// Parses a path file's text; `file` names it in errors. Throws std::invalid_argument with
// one line naming the file and the key that is wrong.
CameraPath parse_camera_path(const std::string& text, const std::string& file, float fov_y);
CameraPath load_camera_path(const std::filesystem::path& file, float fov_y);

}  // namespace render
