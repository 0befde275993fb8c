// The vector layers in the GIS and CAD formats users open them in (docs/design.md, Outputs),
// written through OGR from the layers the GeoJSON files are written from (so every format
// holds the same features, attributes and doubles, and none reads another's file), and
// the street network and buildings as an OpenStreetMap file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "generate/city.h"

namespace exacity {

// The layers OUT/vector holds (the city's and the street clutter's), in their files' order.
std::vector<const Layer*> vector_files(const CityLayers& city, const Layer& clutter);

// Writes `formats` ("gpkg": OUT/city.gpkg, every layer; "fgb": OUT/vector/NAME.fgb; "shp":
// OUT/vector/shp/NAME.shp; "dxf": OUT/city.dxf, a CAD layer per layer; others are left to
// their writers: generate/export/formats.h) of `layers` (vector_files) into `dir`, in the
// sketch's CRS; each layer's fields are its features' properties, typed as GDAL's GeoJSON
// reader types them, so that each format holds what ogr2ogr makes of the GeoJSON file.
void write_vector_formats(const std::vector<const Layer*>& layers, const std::filesystem::path& dir,
                          const std::vector<std::string>& formats, const nlohmann::ordered_json& crs);

// OUT/city.osm: the centre lines as ways (a road read from OSM with the tags it was read
// with, others with the highway class a mapper would give them: primary, secondary,
// residential; width; bridge and layer), sharing a node wherever they meet, every building
// footprint as a closed way (building, height), and the street clutter as tagged nodes
// (street lamps, traffic signals, stops, benches, fire hydrants, trees), in lon/lat, with
// negative ids apart from any other city's, or ids from first_id up. Whether it was written: a sketch without a
// CRS (EPSG) has no place on Earth.
bool write_city_osm(const City& city, const std::filesystem::path& file, std::optional<std::int64_t> first_id = {});

}  // namespace exacity
