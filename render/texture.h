// A model's texture as the renderer samples it (docs/design.md, Textured models): the
// image's sRGB texels decoded to linear once, sampled bilinearly at a hit's texture
// coordinates, repeating outside 0..1 or clamped to the edge (map_Kd -clamp on).
#pragma once

#include <cstdint>
#include <vector>

#include "generate/placement/texture_image.h"
#include "render/vec.h"

namespace render {

// sRGB's transfer function undone: an 8-bit value to linear light in [0, 1].
float srgb_to_linear(std::uint8_t value);

class Texture {
 public:
  explicit Texture(const exacity::TextureImage& image);
  // u to the right, v up (OBJ's vt: v = 0 is the image's bottom row).
  V3 sample(float u, float v, bool clamp) const;

 private:
  V3 texel(int x, int y) const { return texels_[static_cast<std::size_t>(y) * width_ + x]; }
  int width_, height_;
  std::vector<V3> texels_;  // linear RGB, row 0 at the top
};

}  // namespace render
