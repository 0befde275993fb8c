// Procedural facades and roofs (docs/design.md, Rendering: facades and roofs): what a
// building's wall or roof looks like at a hit, from the hit's position and the building's
// zone, floor and id, with no texture file. Walls get windows in rows, one row a storey,
// bays along the wall; commercial buildings a ground floor of shop windows under a fascia;
// each building its own storey height, bay width, window size and a phase along its walls.
// Pitched roofs get rows of tiles down their slope, flat ones gravel (Perlin fBm, as grass
// has).
#pragma once

#include <cstdint>

#include "generate/city/zone_type.h"
#include "render/material.h"

namespace render {

// What a wall is made of: punched windows in plaster or stone, the same in brick coursing,
// ribbon windows (one band of glass a storey, mullions every bay), a curtain wall (glass
// from slab to slab over dark spandrel panels) or ribbed metal cladding.
enum class FacadeKind : std::uint8_t { Punched, Brick, Ribbon, CurtainWall, Cladding };

struct FacadeStyle {
  FacadeKind kind = FacadeKind::Punched;
  float floor = 0;                  // height of the ground floor, scene coordinates
  float eaves = 1e9f;               // walls above this (a gable) get no windows
  float storey = 3.2f;              // m from floor to floor
  float bay = 3.0f;                 // m between window centres along a wall
  float window = 0.5f;              // a window's width, as a share of its bay
  float sill = 0.3f, head = 0.78f;  // a window's bottom and top, as shares of its storey
  float phase = 0;                  // m: where the bays start along a wall
  bool shopfront = false;           // commercial: shop windows on the ground floor
  bool dark_frames = false;         // window frames dark grey, else white
  // A band at each floor's slab (a string course), this much of the wall's albedo; 1: none.
  float band = 1;
  V3 glass_tint{1, 1, 1};  // a curtain wall's glass and spandrels (blue, green, bronze or grey)
  // At night: the share of its windows lit, and their radiance.
  float lit = 0;
  V3 light{0, 0, 0};
};

// Where a wall point lies in the style's windows: inside a window or not, that window's
// storey (-1: the shop floor) and bay, and the metres to the pane's nearest edge and to
// its vertical centre line.
struct WindowPoint {
  bool inside = false;
  int row = 0, column = 0;
  float from_edge = 0, from_centre = 0;
};
WindowPoint window_at(const FacadeStyle& style, float along, float z);

// A building's style: storeys and windows by its zone (residential 2.8-3.2 m storeys,
// commercial 3.4-4.2 m over a 4.5 m shop floor, industrial 4.5-6 m with wide high
// windows) and its kind of wall (residential plaster or brick, commercial stone, ribbon
// windows or a curtain wall, industrial plaster or cladding), varied per building by a
// stream seeded by the city's seed and its id.
FacadeStyle facade_style(exacity::ZoneType zone, std::uint64_t seed, int id, float floor, float eaves);

// What the wall is at a point: in a window glass over its room, or its frame or mullion;
// else the wall's albedo with a little plaster noise; `along` is the distance along the wall's horizontal direction.
Material facade_material(const FacadeStyle& style, const Material& wall, V3 position, V3 normal);

// The light of the style's lit windows spread evenly over its wall, at a wall point: what a
// diffusely scattered ray takes there instead of the window it may hit (render/README.md,
// Night). The same light leaves the wall, from everywhere on it rather than from a few
// windows: a ray bounced off the street opposite finds it every time where it found a lit
// pane now and then, a grain of bright dots on every wall facing lit windows. Zero by day,
// off the wall (roofs, gables) and on the shop floor of a style without shops.
V3 spread_window_light(const FacadeStyle& style, V3 position, V3 normal);

// Whether a wall point lies in a window of the style (the facade test's oracle too).
bool in_window(const FacadeStyle& style, float along, float z);
// The distance along a wall, for a wall whose outward normal is `normal`.
inline float along_wall(V3 position, V3 normal) { return position.x * -normal.y + position.y * normal.x; }

// A roof at a point: tiles in rows down a pitched roof's slope, gravel on a flat one.
Material roof_material(const Material& roof, V3 position, V3 normal);

}  // namespace render
