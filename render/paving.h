// Paving where people walk (docs/design.md, Rendering: facades and roofs): sidewalks and
// paved lots laid in 0.6 m square slabs, each a shade of its own, with darker joints, from
// the hit's position; no texture file.
#pragma once

#include <cmath>
#include <cstdint>

#include "generate/city/random.h"
#include "render/material.h"

namespace render {

inline Material paving_material(const Material& paving, V3 p) {
  constexpr float kSlab = 0.6f, kJoint = 0.04f;
  const float u = p.x / kSlab, v = p.y / kSlab;
  const auto column = static_cast<std::int64_t>(std::floor(u)), row = static_cast<std::int64_t>(std::floor(v));
  const float in_u = (u - std::floor(u)) * kSlab, in_v = (v - std::floor(v)) * kSlab;
  Material m = paving;
  const std::uint64_t h = exacity::mix(static_cast<std::uint64_t>(column), static_cast<std::uint64_t>(row));
  float shade = 0.9f + 0.2f * static_cast<float>(h >> 40) / static_cast<float>(1 << 24);
  if (in_u < kJoint || in_v < kJoint) shade *= 0.7f;
  m.albedo = m.albedo * shade;
  return m;
}

}  // namespace render
