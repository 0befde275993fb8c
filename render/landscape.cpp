#include "render/landscape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "render/noise.h"

namespace render {

namespace {

constexpr float kRow = 170;           // m: a row of fields' depth, on average
constexpr float kVerge = 15;          // m of grass around the city's ground before the fields
constexpr float kFieldsFrom = 45;     // m from the city's ground: all fields
constexpr float kMargin = 3;          // m of grass along a field's edges
constexpr float kHedge = 1.5f;        // m: half a hedgerow's width
constexpr float kWoodsSpacing = 9;    // m between trees in woods
constexpr float kHedgeSpacing = 3.5f; // m between shrubs along a hedgerow
constexpr float kCorridorVerge = 6;   // m of grass either side of a road or river carried on

const Noise& noise() {
  static const Noise n;
  return n;
}

// Ground albedos in linear sRGB, near the broadband albedos measured for each cover
// (grass and pasture 0.2-0.25, ripe cereals 0.25-0.3, moist bare soil 0.1-0.15,
// broadleaf woods 0.12-0.18: e.g. the MODIS albedo tables of Gao et al. 2005).
V3 crop_albedo(Landscape::Crop c) {
  switch (c) {
    case Landscape::Crop::Pasture: return {0.13f, 0.25f, 0.08f};
    case Landscape::Crop::Meadow: return {0.22f, 0.28f, 0.12f};
    case Landscape::Crop::Wheat: return {0.36f, 0.31f, 0.16f};
    case Landscape::Crop::Barley: return {0.38f, 0.36f, 0.22f};
    case Landscape::Crop::Green: return {0.11f, 0.22f, 0.06f};
    case Landscape::Crop::Ploughed: return {0.17f, 0.12f, 0.08f};
    case Landscape::Crop::Rapeseed: return {0.42f, 0.40f, 0.08f};
    case Landscape::Crop::Woods: return {0.05f, 0.09f, 0.03f};  // the floor under the trees
  }
  return {0.2f, 0.3f, 0.1f};
}

constexpr V3 kVergeAlbedo{0.17f, 0.28f, 0.09f}, kHedgeFloor{0.06f, 0.11f, 0.04f};

// Even-odd scanline fill of a polygon's cells (cell centres inside) on the grid.
void fill(const geom::Polygon& p, geom::Vec2 origin, const geom::Box& box, float cell, int nx, int ny,
          std::vector<float>& grid) {
  std::vector<const geom::Ring*> rings{&p.outer};
  for (const geom::Ring& h : p.holes) rings.push_back(&h);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const geom::Vec2& v : p.outer) lo = std::min(lo, v.y - origin.y), hi = std::max(hi, v.y - origin.y);
  const int r0 = std::max(0, static_cast<int>(std::floor((lo - box.min_y) / cell)));
  const int r1 = std::min(ny - 1, static_cast<int>(std::ceil((hi - box.min_y) / cell)));
  std::vector<double> xs;
  for (int r = r0; r <= r1; ++r) {
    const double y = box.min_y + (r + 0.5) * cell;
    xs.clear();
    for (const geom::Ring* ring : rings)
      for (std::size_t i = 0; i < ring->size(); ++i) {
        const geom::Vec2 a = (*ring)[i] - origin, b = (*ring)[(i + 1) % ring->size()] - origin;
        if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
      }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      const int c0 = std::max(0, static_cast<int>(std::ceil((xs[k] - box.min_x) / cell - 0.5)));
      const int c1 = std::min(nx - 1, static_cast<int>(std::floor((xs[k + 1] - box.min_x) / cell - 0.5)));
      for (int c = c0; c <= c1; ++c) grid[static_cast<std::size_t>(r) * nx + c] = 0;
    }
  }
}

// Chamfer distances (3-4, Borgefors 1986) from the cells at 0, in cells.
void chamfer(std::vector<float>& d, int nx, int ny) {
  auto at = [&](int x, int y) -> float& { return d[static_cast<std::size_t>(y) * nx + x]; };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      float& v = at(x, y);
      if (x > 0) v = std::min(v, at(x - 1, y) + 1);
      if (y > 0) {
        v = std::min(v, at(x, y - 1) + 1);
        if (x > 0) v = std::min(v, at(x - 1, y - 1) + 1.4142f);
        if (x + 1 < nx) v = std::min(v, at(x + 1, y - 1) + 1.4142f);
      }
    }
  for (int y = ny - 1; y >= 0; --y)
    for (int x = nx - 1; x >= 0; --x) {
      float& v = at(x, y);
      if (x + 1 < nx) v = std::min(v, at(x + 1, y) + 1);
      if (y + 1 < ny) {
        v = std::min(v, at(x, y + 1) + 1);
        if (x + 1 < nx) v = std::min(v, at(x + 1, y + 1) + 1.4142f);
        if (x > 0) v = std::min(v, at(x - 1, y + 1) + 1.4142f);
      }
    }
}

float smoothstep(float a, float b, float x) {
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}

}  // namespace

Landscape::Landscape(const exacity::Ground& ground, const geom::Box& city_box, geom::Vec2 origin, std::uint32_t seed,
                     std::vector<Corridor> corridors)
    : seed_(seed), corridors_(std::move(corridors)) {
  const float turn = 6.2831853f * hash(1, 2, 3);
  cos_ = std::cos(turn), sin_ = std::sin(turn);
  // A grid over the city and 100 m around it, of at most about four million cells.
  const double pad = 100;
  grid_box_ = {city_box.min_x - pad, city_box.min_y - pad, city_box.max_x + pad, city_box.max_y + pad};
  cell_ = static_cast<float>(std::max(4.0, std::sqrt(grid_box_.width() * grid_box_.height() / 4e6)));
  nx_ = static_cast<int>(std::ceil(grid_box_.width() / cell_)), ny_ = static_cast<int>(std::ceil(grid_box_.height() / cell_));
  distance_.assign(static_cast<std::size_t>(nx_) * ny_, 1e9f);
  for (const auto& z : ground.zones) fill(z.polygon, origin, grid_box_, cell_, nx_, ny_, distance_);
  for (const auto& w : ground.water) fill(w, origin, grid_box_, cell_, nx_, ny_, distance_);
  for (const auto& a : ground.road_areas) fill(a.polygon, origin, grid_box_, cell_, nx_, ny_, distance_);
  chamfer(distance_, nx_, ny_);
  for (float& d : distance_) d *= cell_;
}

float Landscape::beyond(float x, float y) const {
  const float fx = static_cast<float>((x - grid_box_.min_x) / cell_) - 0.5f;
  const float fy = static_cast<float>((y - grid_box_.min_y) / cell_) - 0.5f;
  if (!(fx >= 0 && fy >= 0 && fx < nx_ - 1 && fy < ny_ - 1)) return 1;
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  const float tx = fx - ix, ty = fy - iy;
  auto d = [&](int i, int j) { return distance_[static_cast<std::size_t>(iy + j) * nx_ + ix + i]; };
  const float dist = (d(0, 0) * (1 - tx) + d(1, 0) * tx) * (1 - ty) + (d(0, 1) * (1 - tx) + d(1, 1) * tx) * ty;
  return smoothstep(kVerge, kFieldsFrom, dist);
}

double Landscape::from_corridors(float x, float y) const {
  double d = INFINITY;
  for (const Corridor& c : corridors_) d = std::min(d, geom::distance_to_segment({x, y}, c.a, c.b) - c.half_width);
  return d;
}

float Landscape::hash(int a, int b, int salt) const {
  std::uint32_t h = seed_ * 0x9e3779b9u ^ static_cast<std::uint32_t>(a) * 0x85ebca6bu ^
                    static_cast<std::uint32_t>(b) * 0xc2b2ae35u ^ static_cast<std::uint32_t>(salt) * 0x27d4eb2fu;
  h ^= h >> 16, h *= 0x7feb352du, h ^= h >> 15, h *= 0x846ca68bu, h ^= h >> 16;
  return static_cast<float>(h >> 8) / 16777216.0f;
}

float Landscape::row_edge(int row) const { return row * kRow + (hash(row, 0, 11) - 0.5f) * 0.5f * kRow; }
float Landscape::row_width(int row) const { return 90 + 170 * hash(row, 0, 12); }
float Landscape::column_edge(int column, int row) const {
  const float w = row_width(row);
  return column * w + (hash(column, row, 13) - 0.5f) * 0.5f * w;
}
bool Landscape::hedged_column_edge(int column, int row) const { return hash(column, row, 14) < 0.6f; }
bool Landscape::hedged_row_edge(int row, float u) const {
  return hash(row, static_cast<int>(std::floor(u / 220)), 15) < 0.55f;
}
// Woods group whole fields where a noise of a kilometre's scale is high.
bool Landscape::woods_at(float u, float v) const {
  return noise().fractal(u / 1100 + 17.3f * hash(0, 0, 16), v / 1100 + 5.1f, 3) > 0.12f;
}

Landscape::Field Landscape::field_at(float x, float y) const {
  Field f;
  f.u = x * cos_ + y * sin_, f.v = -x * sin_ + y * cos_;
  int row = static_cast<int>(std::floor(f.v / kRow));
  if (f.v < row_edge(row)) --row;
  else if (f.v >= row_edge(row + 1)) ++row;
  const float w = row_width(row);
  int column = static_cast<int>(std::floor(f.u / w));
  if (f.u < column_edge(column, row)) --column;
  else if (f.u >= column_edge(column + 1, row)) ++column;
  f.row = row, f.column = column;
  f.v0 = row_edge(row), f.v1 = row_edge(row + 1), f.u0 = column_edge(column, row), f.u1 = column_edge(column + 1, row);
  if (woods_at((f.u0 + f.u1) / 2, (f.v0 + f.v1) / 2)) {
    f.crop = Crop::Woods;
  } else {
    // Shares of each cover: meadows and pasture most, cereals, then the rest.
    const float h = hash(column, row, 17);
    static constexpr std::pair<float, Crop> kShares[] = {{0.22f, Crop::Pasture}, {0.36f, Crop::Meadow},
                                                         {0.56f, Crop::Wheat},   {0.68f, Crop::Barley},
                                                         {0.83f, Crop::Green},   {0.97f, Crop::Ploughed},
                                                         {1.01f, Crop::Rapeseed}};
    f.crop = Crop::Pasture;
    for (const auto& [upto, crop] : kShares)
      if (h < upto) {
        f.crop = crop;
        break;
      }
  }
  return f;
}

V3 Landscape::albedo(float x, float y) const {
  if (from_corridors(x, y) < kCorridorVerge) {
    const float patch = noise().fractal(x / 45, y / 45, 3), fine = noise()(x * 0.7f, y * 0.7f);
    return kVergeAlbedo * (0.9f + 0.35f * patch) * (0.92f + 0.16f * fine);
  }
  const Field f = field_at(x, y);
  V3 a = crop_albedo(f.crop);
  // Hedgerows' floor and the grass margins along the edges.
  const float to_column = std::min(f.u - f.u0, f.u1 - f.u), to_row = std::min(f.v - f.v0, f.v1 - f.v);
  const bool hedged_column = f.u - f.u0 < f.u1 - f.u ? hedged_column_edge(f.column, f.row)
                                                      : hedged_column_edge(f.column + 1, f.row);
  const bool hedged_row = f.v - f.v0 < f.v1 - f.v ? hedged_row_edge(f.row, f.u) : hedged_row_edge(f.row + 1, f.u);
  if (f.crop != Crop::Woods) {
    if ((to_column < kHedge && hedged_column) || (to_row < kHedge && hedged_row)) return kHedgeFloor;
    if (std::min(to_column, to_row) < kMargin) return kVergeAlbedo;
  }
  // Drill rows 2.5 m apart in arable fields, along or across the row by the field's hash.
  const bool arable = f.crop == Crop::Wheat || f.crop == Crop::Barley || f.crop == Crop::Green ||
                      f.crop == Crop::Ploughed || f.crop == Crop::Rapeseed;
  if (arable) {
    const float along = hash(f.column, f.row, 18) < 0.5f ? f.u : f.v;
    const float phase = along / 2.5f - std::floor(along / 2.5f);
    a = a * (0.88f + 0.24f * std::abs(2 * phase - 1));
  }
  // Patches: soil and growth vary across a field.
  const float patch = noise().fractal(x / 45, y / 45, 3);
  a = a * (0.9f + 0.35f * patch);
  if (f.crop == Crop::Meadow || f.crop == Crop::Pasture) {
    const float fine = noise()(x * 0.7f, y * 0.7f);
    a = a * (0.92f + 0.16f * fine);
  }
  return a;
}

std::vector<LandscapeTree> Landscape::tree_spots(const geom::Box& region) const {
  std::vector<LandscapeTree> out;
  auto place = [&](float x, float y, float width, float height, bool conifer, int tint, float angle) {
    if (x < region.min_x || x > region.max_x || y < region.min_y || y > region.max_y) return;
    if (beyond(x, y) < 0.999f || from_corridors(x, y) < kCorridorVerge - 2) return;
    out.push_back({{x, y, 0}, width, height, angle, conifer, tint});
  };
  // Woods: a jittered grid, broadleaf or conifer by the wood's own noise.
  const float s = kWoodsSpacing;
  for (int j = static_cast<int>(std::floor(region.min_y / s)); j * s <= region.max_y; ++j)
    for (int i = static_cast<int>(std::floor(region.min_x / s)); i * s <= region.max_x; ++i) {
      const float x = (i + 0.15f + 0.7f * hash(i, j, 21)) * s, y = (j + 0.15f + 0.7f * hash(i, j, 22)) * s;
      const Field f = field_at(x, y);
      if (f.crop != Crop::Woods) continue;
      // Not right on the wood's edge, so its crowns stay inside it.
      if (std::min({f.u - f.u0, f.u1 - f.u, f.v - f.v0, f.v1 - f.v}) < 2) continue;
      const bool conifer = noise()(x / 300 + 40.5f, y / 300) + 0.4f * (hash(i, j, 23) - 0.5f) > 0.1f;
      const float size = 0.8f + 0.45f * hash(i, j, 24);
      place(x, y, (conifer ? 1.6f : 2.3f) * size, (conifer ? 1.9f : 2.5f) * size, conifer,
            static_cast<int>(hash(i, j, 25) * 4), 6.2831853f * hash(i, j, 26));
    }
  // Hedgerows: shrubs along the hedged edges, now and then a standard tree. Edges in the
  // fields' frame, walked over the region's corners' extent in that frame.
  float u_lo = INFINITY, u_hi = -INFINITY, v_lo = INFINITY, v_hi = -INFINITY;
  for (double x : {region.min_x, region.max_x})
    for (double y : {region.min_y, region.max_y}) {
      const float u = static_cast<float>(x) * cos_ + static_cast<float>(y) * sin_;
      const float v = -static_cast<float>(x) * sin_ + static_cast<float>(y) * cos_;
      u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u), v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
    }
  auto at = [&](float u, float v) { return geom::Vec2{u * cos_ - v * sin_, u * sin_ + v * cos_}; };
  int n = 0;
  auto hedge = [&](float u, float v) {
    ++n;
    if (hash(n, static_cast<int>(u), 31) < 0.12f) return;  // gaps
    const geom::Vec2 p = at(u, v);
    const float x = static_cast<float>(p.x), y = static_cast<float>(p.y);
    if (field_at(x + 6, y).crop == Crop::Woods && field_at(x - 6, y).crop == Crop::Woods) return;
    const bool standard = hash(n, static_cast<int>(v), 32) < 0.08f;
    const float size = 0.8f + 0.4f * hash(n, 0, 33);
    place(x, y, (standard ? 2.0f : 0.9f) * size, (standard ? 2.2f : 0.55f) * size, false,
          static_cast<int>(hash(n, 0, 34) * 4), 6.2831853f * hash(n, 0, 35));
  };
  for (int row = static_cast<int>(std::floor(v_lo / kRow)) - 1; row_edge(row) <= v_hi + kRow; ++row) {
    const float v0 = row_edge(row), v1 = row_edge(row + 1);
    for (float u = std::floor(u_lo / kHedgeSpacing) * kHedgeSpacing; u <= u_hi; u += kHedgeSpacing)
      if (hedged_row_edge(row, u)) hedge(u, v0);
    const float w = row_width(row);
    for (int column = static_cast<int>(std::floor(u_lo / w)) - 1; column_edge(column, row) <= u_hi + w; ++column)
      if (hedged_column_edge(column, row))
        for (float v = v0 + kHedgeSpacing; v < v1; v += kHedgeSpacing) hedge(column_edge(column, row), v);
  }
  return out;
}

}  // namespace render
