#include "render/white_balance.h"

namespace render {

V3 black_body_rgb(float kelvin) {
  const double t = std::clamp(static_cast<double>(kelvin), 1667.0, 25000.0);
  const double t1 = 1e3 / t, t2 = t1 * t1, t3 = t2 * t1;  // in thousands of kelvin, inverted
  const double x = t <= 4000 ? -0.2661239 * t3 - 0.2343589 * t2 + 0.8776956 * t1 + 0.179910
                             : -3.0258469 * t3 + 2.1070379 * t2 + 0.2226347 * t1 + 0.240390;
  const double x2 = x * x, x3 = x2 * x;
  const double y = t <= 2222   ? -1.1063814 * x3 - 1.34811020 * x2 + 2.18555832 * x - 0.20219683
                   : t <= 4000 ? -0.9549476 * x3 - 1.37418593 * x2 + 2.09137015 * x - 0.16748867
                               : 3.0817580 * x3 - 5.87338670 * x2 + 3.75112997 * x - 0.37001483;
  // XYZ with Y = 1, then the sRGB primaries (IEC 61966-2-1); luminance is Y, so 1.
  const double X = x / y, Y = 1, Z = (1 - x - y) / y;
  return {static_cast<float>(3.2406 * X - 1.5372 * Y - 0.4986 * Z),
          static_cast<float>(-0.9689 * X + 1.8758 * Y + 0.0415 * Z),
          static_cast<float>(0.0557 * X - 0.2040 * Y + 1.0570 * Z)};
}

V3 white_balance_gains(float kelvin) {
  if (kelvin == kNeutralKelvin) return {1, 1, 1};  // exactly: the default changes no byte
  const V3 neutral = black_body_rgb(kNeutralKelvin), light = black_body_rgb(kelvin);
  // Below about 1900 K the locus leaves sRGB's blue; a floor keeps the gain finite.
  const V3 gains{neutral.x / std::max(light.x, 0.01f), neutral.y / std::max(light.y, 0.01f),
                 neutral.z / std::max(light.z, 0.01f)};
  return gains / luminance(gains);
}

}  // namespace render
