// The sketch's drawn features and the specs of its images, as the stages read them
// (docs/design.md, The sketch).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "generate/city/zone_type.h"
#include "geom/plain.h"

namespace exacity {

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
  // Its OpenStreetMap tags (osm_id, highway, name, lanes, sidewalk ...: osm_road_tags), which
  // every export carries.
  std::vector<std::pair<std::string, std::string>> osm_tags;
  // Its sidewalks' widths, m, left and right of its lines' direction: its sidewalk tag's, else
  // its class's (StreetSettings::sidewalks).
  double sidewalk_left = 0, sidewalk_right = 0;
  // Its carriageway as mapped (OSM's width, or its lanes), m, which it keeps where it gives
  // way to a mapped building; else nothing.
  std::optional<double> carriageway = std::nullopt;
  double widest_sidewalk() const { return sidewalk_left > sidewalk_right ? sidewalk_left : sidewalk_right; }
};

// A building the sketch maps (OpenStreetMap's `building=*`, or any feature with a "building"
// property): kept as drawn, raised from its tags (docs/design.md, Mapped buildings). A
// tag that is absent or not a number in metres is nothing.
struct MappedBuilding {
  int index = 0;            // position in "features"
  std::string name;         // how messages and report.json name it: its source, else features[N]
  std::string osm_id;       // "way/123", "relation/45", a GIS export's osm_id; else empty
  std::string building;     // the building tag's value ("yes", "house")
  // Its identifier in a footprint layer (docs/gis.md): {"identificatie", BAG's} or {"fid",
  // the layer's FID}; else empty.
  std::pair<std::string, std::string> source_id;
  geom::Polygon polygon;    // as drawn, in metres: any orientation, maybe not simple
  std::optional<double> height, levels, roof_height;  // m, storeys, m
  // A building:part's bottom: min_height (m), else building:min_level (storeys skipped).
  std::optional<double> min_height, min_level;
  std::string roof_shape;   // roof:shape as tagged, or empty
  std::string problem;      // why it cannot be read as a footprint (a ring of 2 points); else empty
};

// What became of the land use (docs/gis.md): areas the extract's edge cut open, closed
// along it, and with "infer_zones" the street faces no zone covered, zoned from their
// mapped buildings or left open (the document's "land_use" member).
struct LandUseTally {
  int closed_along_bounds = 0;
  bool infer_zones = false;
  int street_faces = 0, faces_with_land_use = 0, left_open = 0;
  std::map<std::string, int> inferred;  // faces by the zone given them
};

// The sketch's own street graph (docs/design.md, Road layouts): how it is joined, what its streets carry.
struct StreetSettings {
  double snap = 0.5;                     // m: a line end this near another line is joined to it
  bool dead_ends_are_errors = false;     // "dead_ends": "error"
  std::map<RoadClass, double> sidewalks;  // m on each side, per class; none unless set
  double sidewalk(RoadClass c) const { return sidewalks.count(c) ? sidewalks.at(c) : 0.0; }
  // A sidewalk a road's own tag asks for (OSM's sidewalk=both): its class's width, else 2 m.
  double tagged_sidewalk(RoadClass c) const { return sidewalk(c) > 0 ? sidewalk(c) : 2.0; }
};

// A road end that meets no other road.
struct DeadEnd {
  int feature = 0;  // its road's position in "features"
  geom::Vec2 at;
};

// The features the stages read: the zones and roads as drawn, and how the roads were joined.
struct DrawnFeatures {
  std::vector<ZoneFeature> zones;
  std::vector<RoadFeature> roads;     // as joined by StreetSettings::snap
  std::vector<MappedBuilding> buildings;  // in sketch order
  // OSM's building:part areas (Simple 3D Buildings), `building` their building:part tag:
  // each raises the 3D of the kept building it lies in, whose outline stays the footprint.
  std::vector<MappedBuilding> building_parts;
  // Mapped buildings a reader left out, by why ("buildings whose way is not closed"), from
  // the counts of what OpenStreetMap's files left out.
  std::map<std::string, int> buildings_left_out;
  std::map<std::string, int> building_parts_left_out;  // the same of building:parts
  std::vector<std::string> buildings_left_out_named;  // the first few, "FILE layer L feature N: refused, why"
  LandUseTally land_use;
  StreetSettings streets;
  int joined_ends = 0;                // line ends moved by up to `snap` to meet another line
  std::vector<DeadEnd> dead_ends;
};

// The sketch reader's limits (docs/sketch.md, docs/limits.md). Coordinates Exacity computes exactly in:
// rounding its exact vertices to doubles moves them by under 2e-6 m out here; at 1e12 m
// (0.1 mm steps) written rings stop being simple.
inline constexpr double kMaxCoordinate = 1e10;
// The most blocks one run builds, as the reader counts them (the zones' area over their
// block_area; about half the blocks built): the 10 km benchmark city counts 6,290 and peaks at
// 1.1 GiB, tiled 3 x 3 it counts 56,581 (a million buildings) and peaks at 8.8 GiB (it was
// 15 GB when this limit was set), so this many fit in the project's 24 GiB machine.
inline constexpr double kMaxBlocks = 60000;
// Pairs of sketch pieces (road strokes, zone edges) crossing or overlapping, past 4 a piece:
// each is vertices of the exact map (a way zig-zagging over itself makes gigabytes).
inline constexpr std::size_t kMaxMeetings = 10000;
// A road's width, m.
inline constexpr double kMinRoadWidth = 0.5, kMaxRoadWidth = 500;

}  // namespace exacity
