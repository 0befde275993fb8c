// Validating the city of an edited sketch where it changed (docs/design.md, Regions and
// regenerating): the previous city's polygons kept, by what they are with ids left out.
#pragma once

#include <filesystem>
#include <memory>

#include "generate/export/validate.h"

namespace exacity {

// The polygons of a city that passed validation: each one's text with ids left out, its id,
// what it names (a lot its block, a building its lot) and its box.
struct ValidatedPolygons;

// validate_output, whose checks of the tiling other than against the drawn sketch run only
// in a window around the polygons that changed since `last` (when it holds a city that
// passed); a window that finds a problem is checked again whole, so the problems are the
// whole check's. Afterwards `last` holds this city's polygons if it passed, else nothing.
// `tile_side` as for validate_output.
Validation validate_output(const std::filesystem::path& dir, std::shared_ptr<ValidatedPolygons>& last,
                           double tile_side = 0);

}  // namespace exacity
