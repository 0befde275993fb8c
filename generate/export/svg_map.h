// OUT/map.svg: the vector layers drawn at their exact coordinates, to open in a browser.
#pragma once

#include <filesystem>

#include "generate/export/vector_layers.h"

namespace exacity {

void write_svg_map(const CityLayers& layers, const std::filesystem::path& file);

}  // namespace exacity
