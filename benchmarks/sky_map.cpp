// Exacity's sky as another renderer's environment: Sky::radiance (the sun disk left out)
// over the whole sphere as a float EXR in Cycles' equirectangular layout (the centre column
// looks along +x, east; the left quarter along +y, north; the top row at the zenith), and
// the sun a renderer adds as a distant light, as JSON on standard output: its direction,
// its irradiance on a surface facing it (linear sRGB, W/m² as Cycles' sun strength is)
// and its angular diameter. The Cycles comparison (benchmarks/cycles/) gives Cycles
// these. Measures nothing.
//
//   build/release/benchmarks/exacity_sky_map OUT.exr [--sun-azimuth 200] [--sun-elevation 40] [--turbidity 3]
//                                            [--night 0] [--width 1024]
// --night (0 to 1, still.json's night) dims the sky as a sun under the horizon does
// (Sky::at); the sun's irradiance is then 0 once it has set.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "render/sky.h"

using namespace render;

int main(int argc, char** argv) {
  std::string out;
  float azimuth = 200, elevation = 40, turbidity = 3, night = 0;  // exacity render's defaults (render/render.h)
  int width = 1024;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sun-azimuth") && i + 1 < argc)
      azimuth = std::stof(argv[++i]);
    else if (!std::strcmp(argv[i], "--sun-elevation") && i + 1 < argc)
      elevation = std::stof(argv[++i]);
    else if (!std::strcmp(argv[i], "--turbidity") && i + 1 < argc)
      turbidity = std::stof(argv[++i]);
    else if (!std::strcmp(argv[i], "--night") && i + 1 < argc)
      night = std::stof(argv[++i]);
    else if (!std::strcmp(argv[i], "--width") && i + 1 < argc)
      width = std::stoi(argv[++i]);
    else
      out = argv[i];
  }
  if (out.empty() || width < 4) {
    std::fprintf(
        stderr,
        "usage: exacity_sky_map OUT.exr [--sun-azimuth DEG] [--sun-elevation DEG] [--turbidity T] [--night N] [--width N]\n");
    return 2;
  }
  const Sky sky = Sky::at(azimuth, elevation, turbidity, night);
  const int height = width / 2;
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * 3);
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      // Cycles' equirectangular lookup inverted: u = 0.5 - atan2(y, x) / 2π, v = 0.5 + elevation / π,
      // v counted from the bottom row.
      const float u = (static_cast<float>(col) + 0.5f) / static_cast<float>(width);
      const float v = 1 - (static_cast<float>(row) + 0.5f) / static_cast<float>(height);
      const float phi = (0.5f - u) * 2 * kPi, theta = (v - 0.5f) * kPi;
      const V3 dir{std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), std::sin(theta)};
      // Below the horizon the ground hides the sky in both renderers; the horizon's radiance
      // is carried down so that the map has no seam there.
      const V3 c = sky.radiance(dir.z >= 0 ? dir : normalize(V3{dir.x, dir.y, 0}));
      float* p = &pixels[(static_cast<std::size_t>(row) * width + col) * 3];
      p[0] = c.x, p[1] = c.y, p[2] = c.z;
    }
  auto file = OIIO::ImageOutput::create(out);
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  if (!file || !file->open(out, spec) || !file->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !file->close()) {
    std::fprintf(stderr, "%s: cannot write the sky map\n", out.c_str());
    return 2;
  }
  const V3 d = sky.sun_direction(), e = sky.sun_up() ? sky.sun_irradiance() : V3{0, 0, 0};
  const double diameter = 2 * std::acos(static_cast<double>(sky.sun_cos_max())) * 180 / kPi;
  std::printf(
      "{\"sun_direction\": [%.6f, %.6f, %.6f], \"sun_irradiance\": [%.6f, %.6f, %.6f], \"sun_diameter_deg\": %.6f}\n",
      d.x, d.y, d.z, e.x, e.y, e.z, diameter);
  return 0;
}
