// The sketch: a GeoJSON FeatureCollection with Exacity's settings in the "exacity" member
// (docs/design.md, The sketch).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city/features.h"
#include "generate/city/zone_settings.h"

namespace exacity {

// The settings (path, seed, CRS, zone settings) and the drawn features are what the stages
// read; the rest is the pipeline's and the exports'.
struct Sketch : CitySettings, DrawnFeatures {
  std::optional<TerrainSpec> terrain;
  std::filesystem::path models;     // empty when the sketch names no model library
  std::string camera;               // the still's camera (exacity render's --camera syntax), or empty
  std::vector<ChannelSpec> channels;  // in name order
  double channel_sharpness = 4;     // the exponent of a model's channel affinity
  // Exacity's own trees and lamps ("builtin_models"), for the kinds the library lacks.
  bool builtin_trees = true, builtin_lamps = true;
  // What each file read left out of OpenStreetMap's features, by the tag that makes no zone
  // or road ("highway=footway"), and the areas osmium could not assemble that it mended
  // (rings the extract's edge cut closed along it), each named: the document's "osm"
  // member (generate/gis/osm_tags.h), a file each.
  struct OsmCounts {
    std::string file;
    std::map<std::string, int> left_out;
    std::vector<std::string> repaired;
  };
  std::vector<OsmCounts> osm_counts;
  std::map<std::string, int> osm_taken;  // the features whose tags made zones, roads, rivers, buildings, of all files
  // The document read when it is not the file at `path` (a grid map; a sketch naming one in
  // "grid", whose features it holds; `generate --models`), else empty. OUT/sketch.geojson
  // holds it, so that validate and render read the sketch generate read.
  std::string geojson;
  // The real place whose mapped buildings give the zone parameters ("like", resolved
  // against the sketch's folder; generate/sketch/like_place.h), or empty.
  std::filesystem::path like;
  // The document read but its features (settings, CRS, ...), as JSON: with the roads, what
  // every region of the city shares (generate/regenerate.h).
  std::string settings_text;
};

ZoneSettings default_zone_settings(ZoneType type);
// A zone type's settings over its defaults, each step's read by that step; the caller checks
// the keys (SettingsReader::expect_keys). With `read_grammars` false, grammar files are
// named but not read.
ZoneSettings read_zone_settings(const SettingsReader& settings, ZoneType type, bool read_grammars);
double default_width(RoadClass road_class);

// Throws UserError with one line naming the file, the feature and the fix. With
// `read_grammars` false (for `exacity validate`, which reads a copy of the sketch away from
// its files), grammar files are named but not read. A path ending in .grid is a grid map
// (generate/sketch/grid_map.h); a sketch's "exacity".grid names one, whose features come
// before the sketch's own. A non-empty `models` is a model library in place of the
// sketch's "models" (`generate --models`).
Sketch load_sketch(const std::filesystem::path& path, bool read_grammars = true,
                   const std::filesystem::path& models = {});
// Several sketch files read as one (a land use layer and a streets layer, say): their
// features in the order given, each named by its file; they share one CRS (a file without
// one is taken to be in the others') and at most one of them has settings. Messages and
// relative paths are the first file's. `footprints` are files of building footprints
// (`generate --buildings`, generate/gis/sketch_sources.h's footprint_document), read after
// them as mapped buildings.
Sketch load_sketch(const std::vector<std::filesystem::path>& paths, bool read_grammars = true,
                   const std::filesystem::path& models = {}, const std::vector<std::filesystem::path>& footprints = {});
// A file as the sketch reader reads it, before its features are: a GeoJSON document in
// metres, OpenStreetMap's tags made zones, roads and mapped buildings (a file of real
// footprints, say, that has no zone or road and that load_sketch would refuse).
nlohmann::ordered_json sketch_document(const std::filesystem::path& path);
// The features of such a document, each checked as parse_sketch checks it; none need be a
// zone or a road.
DrawnFeatures read_drawn_features(const nlohmann::ordered_json& doc, const std::filesystem::path& path);
Sketch parse_sketch(const std::string& text, const std::filesystem::path& path, bool read_grammars = true,
                    const std::filesystem::path& models = {});

}  // namespace exacity
