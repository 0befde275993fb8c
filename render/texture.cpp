#include "render/texture.h"

#include <array>
#include <cmath>

namespace render {

float srgb_to_linear(std::uint8_t value) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[i] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table[value];
}

Texture::Texture(const exacity::TextureImage& image) : width_(image.width), height_(image.height) {
  texels_.resize(static_cast<std::size_t>(width_) * height_);
  for (std::size_t i = 0; i < texels_.size(); ++i)
    texels_[i] = {srgb_to_linear(image.rgb[3 * i]), srgb_to_linear(image.rgb[3 * i + 1]),
                  srgb_to_linear(image.rgb[3 * i + 2])};
}

V3 Texture::sample(float u, float v, bool clamp) const {
  if (!std::isfinite(u) || !std::isfinite(v)) u = v = 0;
  if (clamp)
    u = std::clamp(u, 0.0f, 1.0f), v = std::clamp(v, 0.0f, 1.0f);
  else
    u -= std::floor(u), v -= std::floor(v);  // the image repeats every unit
  // Texel centres sit at half steps; v runs up the image, rows down it.
  const float x = u * static_cast<float>(width_) - 0.5f, y = (1 - v) * static_cast<float>(height_) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float ax = x - fx, ay = y - fy;
  // A texel index: wrapped round the image when it repeats, else held at its edge.
  auto index = [clamp](float i, int size) {
    const long n = static_cast<long>(i);
    if (clamp) return static_cast<int>(std::clamp(n, 0L, static_cast<long>(size - 1)));
    const long m = n % size;
    return static_cast<int>(m < 0 ? m + size : m);
  };
  const int x0 = index(fx, width_), x1 = index(fx + 1, width_), y0 = index(fy, height_), y1 = index(fy + 1, height_);
  return (texel(x0, y0) * (1 - ax) + texel(x1, y0) * ax) * (1 - ay) +
         (texel(x0, y1) * (1 - ax) + texel(x1, y1) * ax) * ay;
}

}  // namespace render
