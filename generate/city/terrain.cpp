#include "generate/city/terrain.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "generate/errors.h"
#include "geom/grid.h"
#include "geom/measure.h"

namespace exacity {

Terrain::Terrain(const TerrainSpec& spec, int width, int height, std::vector<float> values)
    : spec_(spec), width_(width), height_(height), values_(std::move(values)) {}

Terrain Terrain::load(const TerrainSpec& spec) {
  const std::string file = spec.heightmap.string();
  auto fail = [&](const std::string& what) -> Terrain {
    throw UserError(file + ": heightmap " + what);
  };
  if (!std::filesystem::exists(spec.heightmap))
    fail("not found; fix \"exacity\".terrain.heightmap (it is read relative to the sketch's folder)");
  auto in = OIIO::ImageInput::open(file);
  if (!in) fail("is unreadable (" + OIIO::geterror() + "); save it as an 8/16-bit PNG, TIFF or EXR");
  const OIIO::ImageSpec& is = in->spec();
  int w = is.width, h = is.height, channels = is.nchannels;
  if (w < 1 || h < 1) fail("has no pixels");
  std::vector<float> pixels(static_cast<std::size_t>(w) * h * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    fail("is unreadable (" + in->geterror() + ")");
  in->close();

  bool scaled_by_type = is.format == OIIO::TypeDesc::UINT8 || is.format == OIIO::TypeDesc::UINT16 ||
                        is.format == OIIO::TypeDesc::UINT32;
  float full_scale = 1.0f;
  if (!scaled_by_type) {
    full_scale = 0.0f;
    for (float v : pixels) full_scale = std::max(full_scale, v);
  }
  // Grey saved as RGB often carries dithering of a level or so between channels
  // (measured: 1/255 in a real 8-bit heightmap); a real colour image differs far more.
  const float tolerance = 2.0f / 255.0f * std::max(full_scale, 1e-30f);
  std::vector<float> values(static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float* p = &pixels[i * channels];
    float v = p[0];
    if (std::isnan(v)) fail("has a NaN value at pixel " + std::to_string(i % w) + "," + std::to_string(i / w));
    if (channels >= 3) {
      float lo = std::min({p[0], p[1], p[2]}), hi = std::max({p[0], p[1], p[2]});
      if (hi - lo > tolerance)
        fail("is a colour image (pixel " + std::to_string(i % w) + "," + std::to_string(i / w) +
             " has R, G, B = " + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) +
             "); save it as greyscale");
      v = (p[0] + p[1] + p[2]) / 3;  // 0 only where every channel is 0
    }
    values[i] = full_scale > 0 ? std::max(v, 0.0f) / full_scale : 0.0f;
  }
  return Terrain(spec, w, h, std::move(values));
}

double Terrain::height_at(geom::Vec2 p) const {
  const geom::Box& b = spec_.bounds;
  // Pixel centres carry the values.
  double u = std::clamp((p.x - b.min_x) / b.width() * width_ - 0.5, 0.0, width_ - 1.0);
  double v = std::clamp((b.max_y - p.y) / b.height() * height_ - 0.5, 0.0, height_ - 1.0);
  int c = std::min(static_cast<int>(u), width_ - 2 < 0 ? 0 : width_ - 2);
  int r = std::min(static_cast<int>(v), height_ - 2 < 0 ? 0 : height_ - 2);
  int c1 = std::min(c + 1, width_ - 1), r1 = std::min(r + 1, height_ - 1);
  double fu = u - c, fv = v - r;
  double t = (value(c, r) * (1 - fu) + value(c1, r) * fu) * (1 - fv) +
             (value(c, r1) * (1 - fu) + value(c1, r1) * fu) * fv;
  return spec_.low + t * (spec_.high - spec_.low);
}

double Terrain::pixel_size() const {
  return std::min(spec_.bounds.width() / width_, spec_.bounds.height() / height_);
}

std::vector<geom::Vec2> Terrain::pixel_centres(const geom::Box& box) const {
  const geom::Box& b = spec_.bounds;
  const double pw = b.width() / width_, ph = b.height() / height_;
  int c0 = std::max(0, static_cast<int>(std::floor((box.min_x - b.min_x) / pw))),
      c1 = std::min(width_ - 1, static_cast<int>(std::ceil((box.max_x - b.min_x) / pw)));
  int r0 = std::max(0, static_cast<int>(std::floor((b.max_y - box.max_y) / ph))),
      r1 = std::min(height_ - 1, static_cast<int>(std::ceil((b.max_y - box.min_y) / ph)));
  std::vector<geom::Vec2> centres;
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) centres.push_back({b.min_x + (c + 0.5) * pw, b.max_y - (r + 0.5) * ph});
  return centres;
}

std::pair<double, double> Terrain::range_under(const geom::Ring& ring) const {
  double low = INFINITY, high = -INFINITY;
  auto sample = [&](geom::Vec2 p) {
    double h = height_at(p);
    low = std::min(low, h), high = std::max(high, h);
  };
  geom::Box box = geom::Box::none();
  for (geom::Vec2 p : ring) box.add(p);
  for (geom::Vec2 p : geom::densified(ring, pixel_size() / 2)) sample(p);
  for (geom::Vec2 p : pixel_centres(box))
    if (geom::odd_crossings(ring, p)) sample(p);
  return {low, high};
}

geom::Vec2 Terrain::corner(int col, int row) const {
  const geom::Box& b = spec_.bounds;
  // The outer corners are the bounds themselves, so the water outline meets them exactly.
  double x = col == width_ ? b.max_x : b.min_x + b.width() * col / width_;
  double y = row == height_ ? b.min_y : b.max_y - b.height() * row / height_;
  return geom::snap(geom::Vec2{x, y});
}

std::vector<std::pair<geom::Vec2, geom::Vec2>> Terrain::water_boundary() const {
  auto water = [&](int c, int r) { return c >= 0 && r >= 0 && c < width_ && r < height_ && is_water(c, r); };
  std::vector<std::pair<geom::Vec2, geom::Vec2>> segments;
  // dir: +1 where the edge runs with the axis, -1 against it, 0 where it is no boundary.
  auto runs = [&](int count, auto dir, auto from, auto to) {
    int start = 0, current = 0;
    for (int i = 0; i <= count; ++i) {
      int d = i < count ? dir(i) : 0;
      if (d == current) continue;
      if (current > 0) segments.push_back({from(start), to(i)});
      if (current < 0) segments.push_back({to(i), from(start)});
      start = i, current = d;
    }
  };
  // Vertical lines x = corner(col): water west of an upward (northward) edge.
  for (int col = 0; col <= width_; ++col) {
    runs(height_, [&](int row) { return water(col - 1, row) == water(col, row) ? 0 : water(col - 1, row) ? -1 : 1; },
         [&](int row) { return corner(col, row); }, [&](int row) { return corner(col, row); });
  }
  // Horizontal lines y = corner(row): water north of an eastward edge.
  for (int row = 0; row <= height_; ++row) {
    runs(width_, [&](int col) { return water(col, row - 1) == water(col, row) ? 0 : water(col, row - 1) ? 1 : -1; },
         [&](int col) { return corner(col, row); }, [&](int col) { return corner(col, row); });
  }
  return segments;
}

}  // namespace exacity
