#include "generate/city/grey_image.h"

#include <algorithm>
#include <cmath>

#include <OpenImageIO/imageio.h>

#include "generate/errors.h"
#include "generate/input_file.h"
#include "generate/png_check.h"

namespace exacity {

double GreyImage::sample(const geom::Box& b, geom::Vec2 p) const {
  const double u = std::clamp((p.x - b.min_x) / b.width() * width - 0.5, 0.0, width - 1.0);
  const double v = std::clamp((b.max_y - p.y) / b.height() * height - 0.5, 0.0, height - 1.0);
  const int c = std::min(static_cast<int>(u), std::max(width - 2, 0));
  const int r = std::min(static_cast<int>(v), std::max(height - 2, 0));
  const int c1 = std::min(c + 1, width - 1), r1 = std::min(r + 1, height - 1);
  const double fu = u - c, fv = v - r;
  return (at(c, r) * (1 - fu) + at(c1, r) * fu) * (1 - fv) + (at(c, r1) * (1 - fu) + at(c1, r1) * fu) * fv;
}

GreyImage read_grey_image(const std::filesystem::path& path, const std::string& role, const std::string& named_by) {
  const std::string file = path.string();
  auto fail = [&](const std::string& what) -> GreyImage { throw UserError(file + ": " + role + " " + what); };
  if (!std::filesystem::exists(path))
    fail("not found; fix " + named_by + " (it is read relative to the sketch's folder)");
  if (std::filesystem::is_directory(path)) fail("is a folder; name an image file");
  std::string bytes, why;
  if (!read_input(path, kMaxDataFileBytes, bytes, why)) fail("cannot be read (" + why + "); name an image file in " + named_by);
  if (is_png(bytes))
    if (const std::string problem = png_problem(bytes, kMaxGreyImagePixels); !problem.empty())
      fail("is unreadable (" + problem + "); save it as an 8/16-bit PNG, TIFF or EXR");
  auto in = OIIO::ImageInput::open(file);
  if (!in) fail("is unreadable (" + OIIO::geterror() + "); save it as an 8/16-bit PNG, TIFF or EXR");
  const OIIO::ImageSpec& is = in->spec();
  // Grey, or grey saved as RGB: the first three channels say all (alpha is not read).
  const int w = is.width, h = is.height, channels = std::min(is.nchannels, 3);
  if (w < 1 || h < 1 || channels < 1) fail("has no pixels");
  if (static_cast<double>(w) * h > kMaxGreyImagePixels)
    fail("is " + std::to_string(w) + " x " + std::to_string(h) + " pixels, more than the " +
         std::to_string(kMaxGreyImagePixels) + " an image may have; scale it down");
  std::vector<float> pixels(static_cast<std::size_t>(w) * h * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    fail("is unreadable (" + in->geterror() + ")");
  in->close();

  const bool scaled_by_type = is.format == OIIO::TypeDesc::UINT8 || is.format == OIIO::TypeDesc::UINT16 ||
                              is.format == OIIO::TypeDesc::UINT32;
  float full_scale = 1.0f;
  if (!scaled_by_type) {
    full_scale = 0.0f;
    for (float v : pixels) full_scale = std::max(full_scale, v);
  }
  // Grey saved as RGB often carries dithering of a level or so between channels
  // (measured: 1/255 in a real 8-bit heightmap); a real colour image differs far more.
  const float tolerance = 2.0f / 255.0f * std::max(full_scale, 1e-30f);
  GreyImage image{w, h, std::vector<float>(static_cast<std::size_t>(w) * h)};
  for (std::size_t i = 0; i < image.values.size(); ++i) {
    const float* p = &pixels[i * channels];
    float v = p[0];
    if (std::isnan(v)) fail("has a NaN value at pixel " + std::to_string(i % w) + "," + std::to_string(i / w));
    if (channels >= 3) {
      const float lo = std::min({p[0], p[1], p[2]}), hi = std::max({p[0], p[1], p[2]});
      if (hi - lo > tolerance)
        fail("is a colour image (pixel " + std::to_string(i % w) + "," + std::to_string(i / w) + " has R, G, B = " +
             std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + "); save it as greyscale");
      v = (p[0] + p[1] + p[2]) / 3;  // 0 only where every channel is 0
    }
    image.values[i] = full_scale > 0 ? std::min(std::max(v, 0.0f) / full_scale, 1.0f) : 0.0f;
  }
  return image;
}

}  // namespace exacity
