#include "render/render_path.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

namespace render {

std::pair<int, int> frame_share(int first, int last, int part, int parts) {
  const int count = last - first + 1, base = count / parts, longer = count % parts;
  const int begin = first + part * base + std::min(part, longer);
  return {begin, begin + base + (part < longer ? 1 : 0) - 1};
}

std::string frame_file_name(int n) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", n);
  return name;
}

nlohmann::ordered_json render_path_frames(const exacity::City& city, const CameraPath& path, int first, int last,
                                          const RenderRequest& request, const std::filesystem::path& dir,
                                          const RenderProgress& progress) {
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  CameraPath placed = path;
  if (placed.city != &city) placed.place(city, "the camera path");
  for (int n = first; n <= last; ++n) {
    RenderRequest r = request;
    r.started = std::chrono::steady_clock::now();  // a frame's budget is its own
    r.camera = placed.frame(n);
    r.camera.depth_of_field = request.camera.depth_of_field;
    r.overview = r.minimap = false;
    r.still = dir / frame_file_name(n);
    nlohmann::ordered_json report = render_city(city, r, [&](const std::string& stage, double f) {
      if (progress) progress(stage, (n - first + f) / (last - first + 1));
    });
    report["frame"] = n;
    report["t"] = path.keys.front().t + n / path.fps;
    std::filesystem::path json = r.still;
    std::ofstream(json.replace_extension(".json"), std::ios::binary) << report.dump(2) << "\n";
    frames.push_back(report);
  }
  return frames;
}

}  // namespace render
