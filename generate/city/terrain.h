// The heightmap stretched over its bounds (value 0 marks water; docs/design.md, The city model).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "generate/city/grey_image.h"
#include "generate/city/features.h"
#include "geom/plain.h"

namespace exacity {

class Terrain {
 public:
  // Reads the image (read_grey_image). Throws UserError.
  static Terrain load(const TerrainSpec& spec);
  // For tests: values already normalised to [0, 1], row 0 north.
  Terrain(const TerrainSpec& spec, int width, int height, std::vector<float> values);

  int width() const { return image_.width; }
  int height() const { return image_.height; }
  const geom::Box& bounds() const { return spec_.bounds; }
  bool is_water(int col, int row) const { return water_[static_cast<std::size_t>(row) * width() + col]; }
  // The ground's value at a pixel: the image's, but a water pixel's is the lowest of the
  // land around it (filled in from the shore, ring by ring), so the ground runs on level
  // under water rather than down to the image's 0 in a pixel-wide cliff.
  float value(int col, int row) const { return image_.at(col, row); }

  // The height in metres at a point: bicubic between pixel centres (water pixels filled,
  // value), held within the four pixels around it; past the bounds the map mirrored at its
  // edges, sinking smoothly to lowest() over fade() metres and level there.
  double height_at(geom::Vec2 p) const;
  // The lowest height of the map (water pixels filled).
  double lowest() const { return lowest_; }
  // How far past the bounds the ground sinks to lowest(): half the map's longer side.
  double fade() const;
  // The lowest and highest terrain under a ring: sampled at its corners, along its edges
  // and at the pixel centres inside, so no pixel under it is missed.
  std::pair<double, double> range_under(const geom::Ring& ring) const;
  // The centres of the pixels around the box (a pixel's margin included).
  std::vector<geom::Vec2> pixel_centres(const geom::Box& box) const;
  // The size of a pixel on the ground, the finer of its two sides, in metres.
  double pixel_size() const;

  // The water outline: closed rings on the grid with water on their left, simple and apart,
  // smooth where the pixels step (water_outline, generate/city/water_outline.h).
  std::vector<geom::Ring> water_boundary() const;

 private:
  double inside_height(geom::Vec2 p) const;
  TerrainSpec spec_;
  GreyImage image_;           // water pixels filled (value)
  std::vector<char> water_;  // by pixel, row 0 north
  double lowest_ = 0;
};

}  // namespace exacity
