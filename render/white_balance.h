// White balance (render/README.md, Tone mapping): the gains that make the light of a
// black body at a colour temperature neutral, as a camera set to that temperature does;
// 6500 K (the sRGB white, near enough) changes nothing.
#pragma once

#include "render/vec.h"

namespace render {

inline constexpr float kNeutralKelvin = 6500, kLeastKelvin = 1667, kMostKelvin = 25000;

// The linear sRGB colour of a black body at `kelvin` (1667 to 25000), luminance 1: its
// chromaticity on the Planckian locus (Kim et al. 2002's cubic fit) through CIE XYZ.
V3 black_body_rgb(float kelvin);

// Per-channel gains, luminance kept: a scene lit at `kelvin` looks as if lit at 6500 K.
V3 white_balance_gains(float kelvin);

}  // namespace render
