#include "render/facade.h"

#include <algorithm>
#include <cmath>

#include "generate/city/random.h"
#include "render/noise.h"

namespace render {
namespace {

const Noise& noise() {
  static const Noise n;
  return n;
}

// A hash of two integers to [0, 1), for a tile's own shade.
float hash01(int a, int b) {
  std::uint64_t h = exacity::mix(static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)),
                                 static_cast<std::uint64_t>(static_cast<std::uint32_t>(b)));
  return static_cast<float>(h >> 40) / static_cast<float>(1 << 24);
}

float fraction(float x) { return x - std::floor(x); }

constexpr float kFrame = 0.06f;  // m: a window frame's width
constexpr float kShopFloor = 4.5f;  // m: a shop floor's height, glass from 0.4 m to 3.4 m
constexpr float kBand = 0.3f;  // m: a storey band's height, from the slab up

// The wall's own material between its windows: plaster noise, brick coursing (0.225 by
// 0.075 m bricks in stretcher bond, each its own shade, in lighter mortar) or ribbed
// cladding (a rib every 0.2 m); a storey band at each floor's slab.
V3 wall_albedo(const FacadeStyle& s, V3 albedo, V3 p, V3 n) {
  const float along = along_wall(p, n), h = p.z - s.floor;
  switch (s.kind) {
    case FacadeKind::Brick: {
      const float course = h / 0.075f;
      const int row = static_cast<int>(std::floor(course));
      const float brick = along / 0.225f + (row % 2 ? 0.5f : 0.0f);
      const bool mortar = fraction(course) < 0.13f || fraction(brick) < 0.045f;
      albedo = albedo * (mortar ? 1.3f : 0.82f + 0.3f * hash01(row, static_cast<int>(std::floor(brick))));
      break;
    }
    case FacadeKind::Cladding:
      albedo = albedo * (0.92f + 0.1f * std::cos(along * (2 * kPi / 0.2f)));
      break;
    default:
      albedo = albedo * (0.93f + 0.14f * noise().fractal(p.x * 0.7f + p.y * 0.7f, p.z * 0.7f, 3));
      break;
  }
  if (s.band != 1 && h > 0 && p.z < s.eaves) {
    const float above = s.shopfront ? h - kShopFloor : h;
    if (above >= 0 && fraction(above / s.storey) * s.storey < kBand) albedo = albedo * s.band;
  }
  return {std::min(albedo.x, 0.9f), std::min(albedo.y, 0.9f), std::min(albedo.z, 0.9f)};
}

}  // namespace

FacadeStyle facade_style(exacity::ZoneType zone, std::uint64_t seed, int id, float floor, float eaves) {
  exacity::Random rng(exacity::mix(exacity::mix(seed, 0xfacade), static_cast<std::uint64_t>(id)));
  FacadeStyle s;
  s.floor = floor, s.eaves = eaves;
  switch (zone) {
    case exacity::ZoneType::Commercial:
      s.storey = static_cast<float>(rng.uniform(3.4, 4.2));
      s.bay = static_cast<float>(rng.uniform(2.2, 3.4));
      s.window = static_cast<float>(rng.uniform(0.55, 0.8));
      s.sill = 0.22f, s.head = static_cast<float>(rng.uniform(0.78, 0.88));
      s.shopfront = true;
      break;
    case exacity::ZoneType::Industrial:
      s.storey = static_cast<float>(rng.uniform(4.5, 6.0));
      s.bay = static_cast<float>(rng.uniform(4.0, 6.0));
      s.window = static_cast<float>(rng.uniform(0.5, 0.75));
      s.sill = 0.55f, s.head = 0.85f;
      break;
    default:
      s.storey = static_cast<float>(rng.uniform(2.8, 3.2));
      s.bay = static_cast<float>(rng.uniform(2.6, 3.6));
      s.window = static_cast<float>(rng.uniform(0.35, 0.5));
      s.sill = static_cast<float>(rng.uniform(0.3, 0.36)), s.head = static_cast<float>(rng.uniform(0.74, 0.8));
      break;
  }
  s.phase = static_cast<float>(rng.uniform(0, s.bay));
  s.dark_frames = rng.uniform(0, 1) < 0.4;
  // Drawn after the rest, so each building keeps the storeys and bays it had.
  const double kind = rng.uniform(0, 1);
  const bool banded = rng.uniform(0, 1) < 0.6;
  const float band = static_cast<float>(rng.uniform(0, 1) < 0.5 ? rng.uniform(0.65, 0.8) : rng.uniform(1.15, 1.3));
  static const V3 kTints[4] = {{0.55f, 0.75f, 1.0f}, {0.6f, 0.9f, 0.8f}, {0.95f, 0.75f, 0.55f}, {0.8f, 0.8f, 0.8f}};
  s.glass_tint = kTints[rng.next() % 4];
  switch (zone) {
    case exacity::ZoneType::Commercial:
      s.kind = kind < 0.35 ? FacadeKind::Punched : kind < 0.65 ? FacadeKind::Ribbon : FacadeKind::CurtainWall;
      break;
    case exacity::ZoneType::Industrial:
      s.kind = kind < 0.5 ? FacadeKind::Punched : FacadeKind::Cladding;
      break;
    default:
      s.kind = kind < 0.6 ? FacadeKind::Punched : FacadeKind::Brick;
      break;
  }
  // Ribbons and curtain walls: panes 1.5 m wide from mullion to mullion all along the wall.
  if (s.kind == FacadeKind::Ribbon) s.bay = 1.5f, s.window = 0.98f, s.sill = 0.32f, s.head = 0.8f;
  if (s.kind == FacadeKind::CurtainWall) s.bay = 1.5f, s.window = 0.98f, s.sill = 0.12f, s.head = 0.97f;
  if (banded && (s.kind == FacadeKind::Punched || s.kind == FacadeKind::Brick)) s.band = band;
  return s;
}

WindowPoint window_at(const FacadeStyle& s, float along, float z) {
  WindowPoint w;
  const float h = z - s.floor;
  if (h < 0 || z > s.eaves - 0.4f) return w;
  // A shop floor: bays 0.9 of their width, a fascia above.
  if (s.shopfront && h < kShopFloor) {
    const float cell = (along - s.phase) / (2 * s.bay), bay = fraction(cell);
    if (!(h > 0.4f && h < 3.4f && bay > 0.05f && bay < 0.95f)) return w;
    w.inside = true, w.row = -1, w.column = static_cast<int>(std::floor(cell));
    w.from_edge = std::min((0.45f - std::abs(bay - 0.5f)) * 2 * s.bay, std::min(h - 0.4f, 3.4f - h));
    w.from_centre = std::abs(bay - 0.5f) * 2 * s.bay;
    return w;
  }
  const float above = s.shopfront ? h - kShopFloor : h;
  const float storey = fraction(above / s.storey);
  // No window cut by the eaves: the storey's top must be below them.
  if (s.floor + (s.shopfront ? kShopFloor : 0) + (std::floor(above / s.storey) + s.head) * s.storey > s.eaves - 0.4f)
    return w;
  const float cell = (along - s.phase) / s.bay, bay = fraction(cell);
  if (!(storey > s.sill && storey < s.head && std::abs(bay - 0.5f) < s.window / 2)) return w;
  w.inside = true, w.row = static_cast<int>(std::floor(above / s.storey)), w.column = static_cast<int>(std::floor(cell));
  w.from_edge = std::min((s.window / 2 - std::abs(bay - 0.5f)) * s.bay, std::min(storey - s.sill, s.head - storey) * s.storey);
  w.from_centre = std::abs(bay - 0.5f) * s.bay;
  return w;
}

bool in_window(const FacadeStyle& s, float along, float z) { return window_at(s, along, z).inside; }

Material facade_material(const FacadeStyle& s, const Material& wall, V3 p, V3 n) {
  if (std::abs(n.z) < 0.3f) {
    const WindowPoint w = window_at(s, along_wall(p, n), p.z);
    // A frame 6 cm wide round the pane, and a mullion down the middle of a pane wider than
    // 1.2 m, in white or dark grey by building.
    const float width = w.row < 0 ? 0.9f * 2 * s.bay : s.window * s.bay;
    if (w.inside && (w.from_edge < kFrame || (width > 1.2f && w.from_centre < kFrame / 2)))
      return {Material::Diffuse, s.dark_frames ? V3{0.12f, 0.12f, 0.13f} : V3{0.75f, 0.75f, 0.73f}};
    if (w.inside) {
      // Glass: a smooth coat that mirrors the sky and the street (Fresnel), over the room
      // behind it, each window its own (curtains, blinds, a lit wall or a dark room); a
      // curtain wall's glass is tinted.
      const float room = 0.03f + 0.1f * hash01(w.row * 7919 + static_cast<int>(s.phase * 1000), w.column);
      const float warm = hash01(w.column, w.row * 31 + 3);
      V3 behind{room * (0.9f + 0.2f * warm), room, room * (1.1f - 0.2f * warm)};
      if (s.kind == FacadeKind::CurtainWall && w.row >= 0) behind = behind * s.glass_tint;
      Material glass{Material::Glossy, behind, 0.05f, 1.52f};
      // At night a share of the rooms are lit, each window its own, warm to cool white.
      if (s.lit > 0 && hash01(w.row * 104729 + static_cast<int>(s.phase * 1000) + 17, w.column * 3 + 1) < s.lit)
        glass.emission = s.light * (0.6f + 0.8f * hash01(w.column + 5, w.row)) * V3{1, 0.85f - 0.1f * warm, 0.6f - 0.2f * warm};
      return glass;
    }
    // A curtain wall's spandrels, from one storey's glass to the next: opaque glass, dark.
    const bool above_shops = !s.shopfront || p.z - s.floor > kShopFloor;
    if (s.kind == FacadeKind::CurtainWall && above_shops && p.z - s.floor > 0 && p.z < s.eaves - 0.4f)
      return {Material::Glossy, s.glass_tint * 0.14f, 0.05f, 1.52f};
  }
  Material m = wall;
  m.albedo = wall_albedo(s, m.albedo, p, n);
  return m;
}

V3 spread_window_light(const FacadeStyle& s, V3 p, V3 n) {
  if (!(s.lit > 0) || std::abs(n.z) >= 0.3f) return {0, 0, 0};
  const float h = p.z - s.floor;
  if (h < 0 || p.z > s.eaves - 0.4f) return {0, 0, 0};
  // The share of the wall in glass, inside the frames (and a mullion down a pane wider
  // than 1.2 m): a shop floor's, its panes 0.9 of each double bay from 0.4 m to 3.4 m; a
  // storey's, its window's width by its height.
  const bool shop = s.shopfront && h < kShopFloor;
  const float width = shop ? 0.9f * 2 * s.bay : s.window * s.bay, height = shop ? 3.0f : (s.head - s.sill) * s.storey;
  const float pane = (width - 2 * kFrame - (width > 1.2f ? kFrame : 0)) * (height - 2 * kFrame);
  const float glass = std::max(0.0f, pane) / (shop ? 2 * s.bay * kShopFloor : s.bay * s.storey);
  // facade_material's lit pane on average: its brightness 0.6 to 1.4 (mean 1), its
  // colour (1, 0.85 - 0.1 w, 0.6 - 0.2 w) for w even in 0 to 1.
  return s.light * V3{1, 0.8f, 0.5f} * (s.lit * glass);
}

Material roof_material(const Material& roof, V3 p, V3 n) {
  Material m = roof;
  if (std::abs(n.z) > 0.98f) {
    // Gravel: fine grains over broad stains.
    const float grain = noise()(p.x * 9.0f, p.y * 9.0f), stain = noise().fractal(p.x * 0.15f, p.y * 0.15f, 3);
    m.albedo = m.albedo * std::clamp(0.9f + 0.25f * grain + 0.3f * stain, 0.5f, 1.3f);
    return m;
  }
  // Tiles: rows 0.3 m apart down the slope, 0.25 m wide, each row shifted half a tile; the
  // lower edge of each row in the shadow of the row above.
  const float len = std::hypot(n.x, n.y);
  const float dx = n.x / len, dy = n.y / len;
  const float down = (p.x * dx + p.y * dy) / 0.3f, across = (p.x * -dy + p.y * dx) / 0.25f;
  const int row = static_cast<int>(std::floor(down));
  const float shifted = across + (row % 2 ? 0.5f : 0.0f);
  const int column = static_cast<int>(std::floor(shifted));
  const float in_row = fraction(down), in_tile = fraction(shifted);
  float shade = 0.88f + 0.24f * hash01(row, column);
  if (in_row > 0.8f) shade *= 0.6f;     // the row above's shadow
  if (in_tile < 0.06f) shade *= 0.75f;  // the joint between two tiles
  m.albedo = m.albedo * shade;
  return m;
}

}  // namespace render
