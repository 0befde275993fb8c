// OUT/map.svg: the ground and the footprints drawn at their exact coordinates, to open in a
// browser.
#pragma once

#include <filesystem>

#include "generate/city/ground.h"
#include "generate/placement/buildings.h"
#include "generate/placement/clutter.h"

namespace exacity {

// Street clutter is drawn as dots where each piece stands, over the roads.
void write_svg_map(const Ground& ground, const std::vector<Building>& buildings,
                   const std::vector<ModelInstance>& models, const std::filesystem::path& file,
                   const std::vector<Clutter>& clutter = {});

}  // namespace exacity
