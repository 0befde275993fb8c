#include "generate/city/terrain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "generate/city/water_outline.h"
#include "generate/errors.h"
#include "geom/measure.h"

namespace exacity {

namespace {

// Each water pixel (value 0) takes the lowest value of its neighbours (across and along)
// filled before it, ring by ring in from the shore: the heightmap marks water with 0, which
// says nothing of the ground's height there (docs/design.md, The city model). A map all
// water keeps its 0s.
void fill_water(std::vector<float>& values, const std::vector<char>& water, int width, int height) {
  std::vector<char> known(water.size());
  std::vector<std::size_t> ring;
  for (std::size_t i = 0; i < water.size(); ++i) known[i] = !water[i];
  auto neighbours = [&](std::size_t i, auto&& visit) {
    const int col = static_cast<int>(i % width), row = static_cast<int>(i / width);
    if (col > 0) visit(i - 1);
    if (col + 1 < width) visit(i + 1);
    if (row > 0) visit(i - width);
    if (row + 1 < height) visit(i + width);
  };
  for (std::size_t i = 0; i < water.size(); ++i)
    if (water[i]) {
      bool shore = false;
      neighbours(i, [&](std::size_t j) { shore |= static_cast<bool>(known[j]); });
      if (shore) ring.push_back(i);
    }
  while (!ring.empty()) {
    for (std::size_t i : ring) {
      float lowest = INFINITY;
      neighbours(i, [&](std::size_t j) {
        if (known[j]) lowest = std::min(lowest, values[j]);
      });
      values[i] = lowest;
    }
    for (std::size_t i : ring) known[i] = 1;
    std::vector<std::size_t> next;
    for (std::size_t i : ring)
      neighbours(i, [&](std::size_t j) {
        if (!known[j] && water[j]) known[j] = 2, next.push_back(j);  // 2: queued, not yet filled
      });
    for (std::size_t j : next) known[j] = 0;
    ring = std::move(next);
  }
}

}  // namespace

Terrain::Terrain(const TerrainSpec& spec, int width, int height, std::vector<float> values)
    : spec_(spec), image_{width, height, std::move(values)} {
  for (float v : image_.values) water_.push_back(v <= 0.0f);
  fill_water(image_.values, water_, width, height);
  lowest_ = spec_.low + *std::min_element(image_.values.begin(), image_.values.end()) * (spec_.high - spec_.low);
}

Terrain Terrain::load(const TerrainSpec& spec) {
  GreyImage image = read_grey_image(spec.heightmap, "heightmap", "\"exacity\".terrain.heightmap");
  return Terrain(spec, image.width, image.height, std::move(image.values));
}

namespace {

// Catmull-Rom weights of the four samples around a point at fraction t past the second.
std::array<double, 4> catmull_rom(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {(-t3 + 2 * t2 - t) / 2, (3 * t3 - 5 * t2 + 2) / 2, (-3 * t3 + 4 * t2 + t) / 2, (t3 - t2) / 2};
}

}  // namespace

// Bicubic (Catmull-Rom) between pixel centres, so slopes run on smoothly across pixels
// where bilinear creases the ground at every row and column of centres (docs/design.md,
// Terrain). The value is held within the four pixels around the point: no ripple below a
// riverbed or above a crest, and the extremes stay at pixel centres, which range_under
// samples.
double Terrain::inside_height(geom::Vec2 p) const {
  const geom::Box& b = spec_.bounds;
  const int w = image_.width, h = image_.height;
  const double u = std::clamp((p.x - b.min_x) / b.width() * w - 0.5, 0.0, w - 1.0);
  const double v = std::clamp((b.max_y - p.y) / b.height() * h - 0.5, 0.0, h - 1.0);
  const int c = std::min(static_cast<int>(u), std::max(w - 2, 0));
  const int r = std::min(static_cast<int>(v), std::max(h - 2, 0));
  const std::array<double, 4> wu = catmull_rom(u - c), wv = catmull_rom(v - r);
  auto at = [&](int col, int row) { return image_.at(std::clamp(col, 0, w - 1), std::clamp(row, 0, h - 1)); };
  double value = 0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) value += wu[i] * wv[j] * at(c - 1 + i, r - 1 + j);
  const std::array<float, 4> around{at(c, r), at(c + 1, r), at(c, r + 1), at(c + 1, r + 1)};
  value = std::clamp(value, static_cast<double>(*std::min_element(around.begin(), around.end())),
                     static_cast<double>(*std::max_element(around.begin(), around.end())));
  return spec_.low + value * (spec_.high - spec_.low);
}

double Terrain::fade() const { return std::max(spec_.bounds.width(), spec_.bounds.height()) / 2; }

// Past the bounds the map is mirrored at its edges, so hills run on as hills rather than
// as its edge pixels drawn out into walls and grooves, and it sinks smoothly to its lowest
// height, which the renderer's plane beyond has (docs/design.md, Terrain).
double Terrain::height_at(geom::Vec2 p) const {
  const geom::Box& b = spec_.bounds;
  const double dx = std::max({b.min_x - p.x, p.x - b.max_x, 0.0}), dy = std::max({b.min_y - p.y, p.y - b.max_y, 0.0});
  if (dx == 0 && dy == 0) return inside_height(p);
  const double s = std::hypot(dx, dy) / fade();
  if (s >= 1) return lowest();
  auto mirror = [](double x, double lo, double hi) {
    const double span = hi - lo;
    double t = std::fmod(x - lo, 2 * span);
    if (t < 0) t += 2 * span;
    return lo + (t > span ? 2 * span - t : t);
  };
  const double h = inside_height({mirror(p.x, b.min_x, b.max_x), mirror(p.y, b.min_y, b.max_y)});
  return h + (lowest() - h) * s * s * (3 - 2 * s);
}

double Terrain::pixel_size() const {
  return std::min(spec_.bounds.width() / image_.width, spec_.bounds.height() / image_.height);
}

std::vector<geom::Vec2> Terrain::pixel_centres(const geom::Box& box) const {
  const geom::Box& b = spec_.bounds;
  const double pw = b.width() / image_.width, ph = b.height() / image_.height;
  int c0 = std::max(0, static_cast<int>(std::floor((box.min_x - b.min_x) / pw))),
      c1 = std::min(image_.width - 1, static_cast<int>(std::ceil((box.max_x - b.min_x) / pw)));
  int r0 = std::max(0, static_cast<int>(std::floor((b.max_y - box.max_y) / ph))),
      r1 = std::min(image_.height - 1, static_cast<int>(std::ceil((b.max_y - box.min_y) / ph)));
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

std::vector<geom::Ring> Terrain::water_boundary() const {
  std::vector<char> water;
  for (int row = 0; row < height(); ++row)
    for (int col = 0; col < width(); ++col) water.push_back(is_water(col, row));
  return water_outline(water, image_.width, image_.height, spec_.bounds);
}

}  // namespace exacity
