// OUT/city.obj and city.mtl: every building's mesh at full double precision (shortest
// round-trip decimals), x east, y north, z up, in metres; one material per zone and
// surface class.
#pragma once

#include <filesystem>
#include <vector>

#include "generate/buildings.h"

namespace exacity {

struct ObjCounts {
  std::size_t vertices = 0, faces = 0;
};

ObjCounts write_obj(const std::vector<Building>& buildings, const std::filesystem::path& obj_file);

}  // namespace exacity
