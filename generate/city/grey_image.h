// A greyscale image stretched over a box of the city: the heightmap (generate/city/terrain.h)
// and the channels (generate/city/channels.h) read theirs this way.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "geom/plain.h"

namespace exacity {

struct GreyImage {
  int width = 0, height = 0;
  std::vector<float> values;  // in [0, 1], row 0 north

  float at(int col, int row) const { return values[static_cast<std::size_t>(row) * width + col]; }
  // Bilinear between pixel centres, at a point of `bounds` (clamped to them).
  double sample(const geom::Box& bounds, geom::Vec2 p) const;
};

// The most pixels a heightmap or channel image may have (8192 x 4096; a 1-arc-second
// elevation tile has 3601 x 3601): read as floats, the image takes 12 bytes a pixel.
inline constexpr long kMaxGreyImagePixels = 8192L * 4096;

// Reads the image with OpenImageIO: unsigned 8/16/32-bit images scaled by their type's
// maximum, float and signed ones by their largest value; grey saved as RGB is accepted, a
// colour image is not. Throws UserError "FILE: ROLE ...", `role` naming what the image is
// for ("heightmap") and `named_by` where the sketch names it, for a missing file.
GreyImage read_grey_image(const std::filesystem::path& file, const std::string& role, const std::string& named_by);

}  // namespace exacity
