// City statistics: what a city is made of, measured from its vector layers, so the same
// figures can be had for a generated city and for real footprints or streets
// (docs/design.md, Plausibility). Measures, not topology: computed in doubles.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "generate/export/geojson.h"
#include "generate/city/features.h"
#include "generate/city/zone_settings.h"
#include "generate/export/vector_layers.h"

namespace exacity {

// Per zone (and "all"): block, lot and footprint areas (median, 95th percentile, largest),
// the share of block area in blocks over 4x the zone's block_area, the share of lots that
// share an edge with a road area, footprints with an interior angle under 30 degrees and
// under 5 m across (the shorter side of the smallest enclosing rectangle). The streets:
// junctions by degree, dead ends (ends that meet no other centre line inside the city's
// edge), street length and junctions per km2.
// Any layer may be empty; `sketch` (may be null) gives the zones' block_area and the drawn
// city's edge.
nlohmann::ordered_json city_statistics(const CityLayers& layers, const CitySettings* settings = nullptr,
                                       const DrawnFeatures* drawn = nullptr);

// The same figures for real data: a GeoJSON file of footprints (Polygons, MultiPolygons)
// and/or streets (LineStrings, MultiLineStrings), in metres or lon/lat (projected about its
// centre). Throws UserError when the file cannot be read.
nlohmann::ordered_json real_statistics(const std::filesystem::path& file);

// The statistics as an aligned text table.
std::string format_statistics(const nlohmann::ordered_json& statistics);

}  // namespace exacity
