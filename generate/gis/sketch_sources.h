// Sketches from the GIS and OSM ecosystems (docs/design.md, The sketch, GIS and OSM): a
// vector file in any format OGR reads, or an OpenStreetMap extract, made into a GeoJSON
// sketch document that the sketch reader then reads like any other, so every check of a
// drawn sketch applies to them.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace exacity {

enum class SketchSource { GeoJson, GridMap, Osm, Ogr };
// By the file's extension: .geojson and .json are GeoJSON, .grid a grid map, .osm and .pbf
// OpenStreetMap, anything else (a folder of shapefiles included) a vector file for OGR.
SketchSource sketch_source(const std::filesystem::path& path);

// The settings file beside a sketch: its name with ".exacity.json" in place of its extension
// (town.gpkg -> town.exacity.json, town.osm.pbf -> town.exacity.json).
std::filesystem::path settings_beside(const std::filesystem::path& path);

// Every feature of every layer with a geometry: its geometry (2D, linear, in the first such
// layer's CRS) and its "zone", "road", "width" and "name" fields, and OSM's tags (osm_keys); "source" names it for
// messages (FILE layer NAME feature FID). The document's crs is that layer's, by EPSG code.
// Throws UserError naming the file (and the layer) when OGR cannot read it.
nlohmann::ordered_json ogr_sketch_document(const std::filesystem::path& path);

// A file of building footprints in any format OGR reads (`generate --buildings`): every
// polygon of every layer a mapped building (a "building" property, "yes" unless a field
// says which), raised from the fields OSM, Overture, Microsoft's footprints or BAG 3D name
// heights, levels and roofs by; features that are no polygons, and buildings BAG's
// status says do not stand, are counted in the "osm" member's "skipped" as an extract's
// left-out buildings are. Throws UserError for a layer of points or lines, or no footprint.
nlohmann::ordered_json footprint_document(const std::filesystem::path& path);

// An OpenStreetMap extract (.osm or .osm.pbf, read with libosmium) in lon/lat, as OSM is
// (EPSG:4326; project_to_metres then projects it with its settings' bounds): its highways,
// rivers and canals as lines and its land use and water as areas, each with the tags
// apply_osm_tags (generate/gis/osm_tags.h) makes zones and roads of; what they make
// nothing of is counted in the "osm" member. Throws UserError.
nlohmann::ordered_json osm_sketch_document(const std::filesystem::path& path);

// The settings beside the sketch into the document's "exacity" member (a GeoJSON's own
// member and such a file both: UserError). Whether there was one.
bool add_settings_beside(nlohmann::ordered_json& doc, const std::filesystem::path& path);

}  // namespace exacity
