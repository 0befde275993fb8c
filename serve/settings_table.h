// The tables GET /api/settings and GET /api/palette serve (serve/settings_routes.cpp).
#pragma once

#include <nlohmann/json.hpp>

#include "generate/city/zone_type.h"

namespace exacity::serve {

// A zone type's settings as the steps read them: per key its kind, bounds, default, choices,
// unit and description, in the order read.
nlohmann::json zone_settings_table(ZoneType type);
// The page's colours (the sketch's and the SVG map's), the roads' default widths and the
// renderer's sun, as the program has them.
nlohmann::json palette_table();

}  // namespace exacity::serve
