// A camera path on any bytes: a path whose every frame is a camera, or one line (the
// renderer's std::invalid_argument, which the program turns into its UserError).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "render/camera_path.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const render::CameraPath path = render::parse_camera_path(text, "fuzz.json", 45);
    // Frames at the ends and between: pedestrian and flyer keys need a city, so only
    // paths of fixed cameras are sampled.
    bool fixed = true;
    for (const render::CameraKey& k : path.keys) fixed = fixed && !k.spec.on_ground();
    const int n = path.frame_count();
    if (fixed && n > 0)
      for (int f : {0, n / 2, n - 1}) path.frame(f);
  } catch (const std::invalid_argument&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "not a user error: %s\n", e.what());
    std::abort();
  }
  return 0;
}
