// Small sketches on a heightmap of 20 x 20 pixels over 200 m x 200 m, heights 0 to 50 m,
// shared by the tests of the ground and its bridges as the renderer draws them
// (ground_render_test.cpp) and as the 3D exports hold them (bridge_export_test.cpp).
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace river_sketch {

// Writes the heightmap dir/h.png, value(col, row) in [0, 1], row 0 north, and returns the
// text of a sketch of `features` (GeoJSON features, comma-separated) on it.
inline std::string write(const std::filesystem::path& dir, double (*value)(int, int), const std::string& features) {
  std::vector<std::uint16_t> pixels;
  for (int row = 0; row < 20; ++row)
    for (int col = 0; col < 20; ++col)
      pixels.push_back(static_cast<std::uint16_t>(std::lround(value(col, row) * 65535)));
  auto out = OIIO::ImageOutput::create((dir / "h.png").string());
  EXPECT_TRUE(out->open((dir / "h.png").string(), OIIO::ImageSpec(20, 20, 1, OIIO::TypeDesc::UINT16)));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, pixels.data()));
  out->close();
  return R"({"type": "FeatureCollection", "exacity": {"seed": 5, "builtin_models": [],
    "terrain": {"heightmap": "h.png", "bounds": [0, 0, 200, 200], "height": [0, 50]}},
    "features": [)" +
         features + "]}";
}

// A park over the whole map.
inline const std::string kPark = R"({"type": "Feature", "properties": {"zone": "park"},
  "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [200, 0], [200, 200], [0, 200], [0, 0]]]}})";

// A straight river, pixel columns 8 to 11 (x 80 to 120 m), banks 20 m up.
inline double straight_river(int col, int) { return col >= 8 && col <= 11 ? 0.0 : 0.4 + 0.01 * std::abs(col - 9.5); }

// A highway `width` metres wide along the points, "[x, y], [x, y], ...".
inline std::string highway(const std::string& points, double width = 12) {
  return R"({"type": "Feature", "properties": {"road": "highway", "width": )" + std::to_string(width) +
         R"(}, "geometry": {"type": "LineString", "coordinates": [)" + points + "]}}";
}

}  // namespace river_sketch
