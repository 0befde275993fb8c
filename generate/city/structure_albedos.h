// Which of its zone's facade and roof albedos (palette.h) a structure has: the renderer's
// choice, which city.glb's materials follow so the 3D view looks like the still.
#pragma once

#include <cstdint>

#include "generate/city/palette.h"
#include "generate/city/random.h"

namespace exacity {

struct StructureAlbedos {
  int facade = 0, roof = 0;  // indices into facade_albedos(zone) and roof_albedos(zone)
};

// For structure `id` (an extruded building, or a placed model's foundation) of a city
// seeded `seed`.
inline StructureAlbedos structure_albedos(ZoneType zone, std::uint64_t seed, int id) {
  Random pick(mix(seed, static_cast<std::uint64_t>(id)));
  StructureAlbedos out;
  out.facade = static_cast<int>(pick.next() % facade_albedos(zone).size());
  out.roof = static_cast<int>(pick.next() % roof_albedos(zone).size());
  return out;
}

}  // namespace exacity
