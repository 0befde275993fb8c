// The grid of docs/design.md's grid-line rule (Exactness rule 2): every line Exacity creates passes through two
// points of this grid, so exact coordinates stay rationals of bounded size.
#pragma once

#include <cmath>

#include "geom/plain.h"

namespace geom {

// 1/1024 m: a power of two, so grid points are exact doubles and adding two of them
// loses nothing for coordinates up to 2^42 m.
inline constexpr double kGridStep = 1.0 / 1024.0;

inline double snap(double v) { return std::nearbyint(v / kGridStep) * kGridStep; }
inline Vec2 snap(Vec2 p) { return {snap(p.x), snap(p.y)}; }

}  // namespace geom
