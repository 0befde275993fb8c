// How far one image is from another as a person sees them: the root mean square
// difference of their tone-mapped 8-bit sRGB values, over 255 (0: the same bytes). The
// denoiser's test and benchmark measure against a many-sample reference with it
// (render/README.md, Denoising).
#pragma once

#include <cmath>

#include "render/image_io.h"

namespace render {

inline double display_rmse(const Image& a, const Image& b, float exposure = 0.25f) {
  const Rgb8 x = tone_map(a, exposure), y = tone_map(b, exposure);
  double sum = 0;
  for (std::size_t i = 0; i < x.pixels.size(); ++i) {
    const double d = (static_cast<double>(x.pixels[i]) - y.pixels[i]) / 255;
    sum += d * d;
  }
  return x.pixels.empty() ? 0 : std::sqrt(sum / static_cast<double>(x.pixels.size()));
}

}  // namespace render
