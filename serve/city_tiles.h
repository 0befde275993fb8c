// The 3D view's levels of detail: the city cut into square tiles, each written at three
// levels, and the ground once (docs/design.md, Serving: tiles).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "generate/city.h"

namespace exacity::serve {

// The tiles' side for a city box: 250 m, or more so a side holds at most 16 tiles.
double tile_size(const geom::Box& city);

// Writes `dir`/index.json (what GET /api/tiles.json answers), `dir`/ground.glb (city.glb's
// ground) and, for each tile holding structures, `dir`/X_Y/0.glb (its buildings, models and
// clutter as city.glb has them), 1.glb (a box per building or model) and 2.glb (a box per
// block and zone). A structure belongs to the tile of its mesh's centre, clutter to the tile
// where it stands. Checks generate/cancel.h's flag tile by tile. Returns the index.
nlohmann::json write_city_tiles(const City& city, const std::filesystem::path& dir);

}  // namespace exacity::serve
