// Images out through OpenImageIO: a multi-layer EXR (half RGB beauty; float depth,
// normals and albedo, a 32-bit integer id; zip compression, lossless) and tone-mapped
// 8-bit sRGB PNGs. Files are written under a temporary name and renamed into place.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "render/path_tracer.h"

namespace render {

struct Rgb8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // RGB, row 0 at the top
  void set(int x, int y, V3 c);
};

void write_exr(const Image& image, const std::filesystem::path& file);
// ACES filmic curve (Narkowicz's fit) after `exposure` and the white balance's per-channel
// `gains`, then the sRGB transfer function.
Rgb8 tone_map(const Image& image, float exposure, V3 gains = {1, 1, 1});
// A camera's meter: the stops to add to the default exposure so that the image's
// log-average luminance (Reinhard et al. 2002's key) reaches that of a sunlit town seen
// from above, where the default exposure was set; never fewer than none, at most
// kMostMeteredStops. A street in its buildings' shade is exposed for, as a photographer
// would; a view of sunlit roofs stays as it was.
constexpr float kMostMeteredStops = 1.5f;
float metered_stops(const Image& image);
void write_png(const Rgb8& image, const std::filesystem::path& file);

}  // namespace render
