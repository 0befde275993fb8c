// A grid map, a planned map grid: a city drawn as text, one character a cell (docs/sketch.md, Grid
// maps). The reader turns it into a sketch's features, so that every check of the sketch
// reader applies to it and OUT/sketch.geojson holds what was read.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace exacity {

// The grid map `text`, read from `path` (which names it in errors), as GeoJSON features: a
// zone Polygon for each connected region of equal cells (outer rings counter-clockwise,
// holes clockwise), then a road LineString for each straight band of road cells, its ends
// run on to the centre line of the road they meet. Each feature's "grid_cell" property
// names the file, line and column of its first cell. Throws UserError naming the file, the
// line and the column of the mistake.
nlohmann::ordered_json grid_map_features(const std::string& text, const std::filesystem::path& path);

// A whole sketch of the grid map: its features, the zone types that get roads laid out by
// "streets" (a planned city: the map's roads are its only streets).
nlohmann::ordered_json grid_map_sketch(const std::string& text, const std::filesystem::path& path);

// The zone types a grid map lays out by "streets" unless a sketch says otherwise.
inline constexpr const char* kGridMapStreetZones[] = {"residential", "commercial", "industrial"};

}  // namespace exacity
