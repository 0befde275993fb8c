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

#include "generate/city/zone_type.h"
#include "generate/layout/road_settings.h"
#include "generate/parcels/parcel_settings.h"
#include "generate/placement/building_settings.h"
#include "geom/plain.h"

namespace exacity {

// One zone type's settings, each step's read by that step (generate/city/settings.h).
struct ZoneSettings {
  RoadSettings roads;
  BlockSettings blocks;
  LotSettings lots;
  BuildingSettings buildings;
};

struct TerrainSpec {
  std::filesystem::path heightmap;  // resolved against the sketch's folder
  geom::Box bounds;
  double low = 0, high = 100;       // heights of the image's lowest and highest values
};

// A channel: a greyscale image stretched over `bounds` (generate/city/channels.h).
struct ChannelSpec {
  std::string name;
  std::filesystem::path image;  // resolved against the sketch's folder
  geom::Box bounds;
};

struct ZoneFeature {
  int index = 0;                    // position in "features"
  ZoneType type = ZoneType::Residential;
  std::vector<geom::Polygon> polygons;  // rings as drawn: any orientation, maybe self-intersecting
  std::string grid_cell;            // a grid map's region: FILE:LINE:COLUMN of its first cell; else empty
  std::string source;               // a feature read from another format: FILE layer L feature N, FILE way N
};

struct RoadFeature {
  int index = 0;
  RoadClass road_class = RoadClass::Highway;
  double width = 24;
  std::vector<geom::Polyline> lines;
  // Its OpenStreetMap tags (highway, name, ...: osm_road_tags), which city.osm writes back.
  std::vector<std::pair<std::string, std::string>> osm_tags;
};

// The sketch's own street graph (docs/design.md, Road layouts): how it is joined, what its streets carry.
struct StreetSettings {
  double snap = 0.5;                     // m: a line end this near another line is joined to it
  bool dead_ends_are_errors = false;     // "dead_ends": "error"
  std::map<RoadClass, double> sidewalks;  // m on each side, per class; none unless set
  double sidewalk(RoadClass c) const { return sidewalks.count(c) ? sidewalks.at(c) : 0.0; }
};

// A road end that meets no other road.
struct DeadEnd {
  int feature = 0;  // its road's position in "features"
  geom::Vec2 at;
};

struct Sketch {
  std::filesystem::path path;
  std::uint64_t seed = 1;
  nlohmann::ordered_json crs;       // null when the sketch has none; copied as written
  std::optional<TerrainSpec> terrain;
  std::filesystem::path models;     // empty when the sketch names no model library
  std::string camera;               // the still's camera (exacity render's --camera syntax), or empty
  std::vector<ChannelSpec> channels;  // in name order
  double channel_sharpness = 4;     // the exponent of a model's channel affinity
  // Exacity's own trees and lamps ("builtin_models"), for the kinds the library lacks.
  bool builtin_trees = true, builtin_lamps = true;
  std::map<ZoneType, ZoneSettings> zone_settings;
  std::vector<ZoneFeature> zones;
  std::vector<RoadFeature> roads;     // as joined by StreetSettings::snap
  StreetSettings streets;
  int joined_ends = 0;                // line ends moved by up to `snap` to meet another line
  std::vector<DeadEnd> dead_ends;
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
  // The document read when it is not the file at `path` (a grid map; a sketch naming one in
  // "grid", whose features it holds; `generate --models`), else empty. OUT/sketch.geojson
  // holds it, so that validate and render read the sketch generate read.
  std::string geojson;
};

// The sketch reader's limits (docs/sketch.md, docs/limits.md). Coordinates Exacity computes exactly in:
// rounding its exact vertices to doubles moves them by under 2e-6 m out here; at 1e12 m
// (0.1 mm steps) written rings stop being simple.
inline constexpr double kMaxCoordinate = 1e10;
// The most blocks one run builds (the zones' area over their block_area): the 10 km
// benchmark city's 12,700 blocks peak at 4.1 GiB.
inline constexpr double kMaxBlocks = 50000;
// Pairs of sketch pieces (road strokes, zone edges) crossing or overlapping, past 4 a piece:
// each is vertices of the exact map (a way zig-zagging over itself makes gigabytes).
inline constexpr std::size_t kMaxMeetings = 10000;
// A road's width, m.
inline constexpr double kMinRoadWidth = 0.5, kMaxRoadWidth = 500;

ZoneSettings default_zone_settings(ZoneType type);
// A zone type's settings over its defaults, each step's read by that step; the caller checks
// the keys (SettingsReader::expect_keys). With `read_grammars` false, grammar files are
// named but not read.
ZoneSettings read_zone_settings(const SettingsReader& settings, ZoneType type, bool read_grammars);
double default_width(RoadClass road_class);

// Throws UserError with one line naming the file, the feature and the fix. With
// `read_grammars` false (for `exacity validate`, which reads a copy of the sketch away from
// its files), grammar files are named but not read. A path ending in .grid is a grid map
// (generate/city/grid_map.h); a sketch's "exacity".grid names one, whose features come
// before the sketch's own. A non-empty `models` is a model library in place of the
// sketch's "models" (`generate --models`).
Sketch load_sketch(const std::filesystem::path& path, bool read_grammars = true,
                   const std::filesystem::path& models = {});
// Several sketch files read as one (a land use layer and a streets layer, say): their
// features in the order given, each named by its file; they share one CRS (a file without
// one is taken to be in the others') and at most one of them has settings. Messages and
// relative paths are the first file's.
Sketch load_sketch(const std::vector<std::filesystem::path>& paths, bool read_grammars = true,
                   const std::filesystem::path& models = {});
Sketch parse_sketch(const std::string& text, const std::filesystem::path& path, bool read_grammars = true,
                    const std::filesystem::path& models = {});

}  // namespace exacity
