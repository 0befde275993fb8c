// What OpenStreetMap's tags make of a feature (docs/design.md, The sketch, GIS and OSM): the
// one table behind an OSM extract and behind GeoJSON or OGR features exported from OSM
// (their "landuse", "highway" ... columns, and GDAL's "other_tags").
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace exacity {

// A tag's value by key, or nothing.
using OsmTags = std::function<std::optional<std::string>(const std::string& key)>;

struct OsmMeaning {
  enum Kind { Untagged, Zone, Road, River, Building, BuildingPart, LeftOut } kind = Untagged;
  std::string type;  // the zone type or road class; a building's building tag, a part's building:part tag
  double width = 0;  // roads and rivers, metres
  std::string why;   // LeftOut: the tag that says what it is ("highway=footway")
  // LeftOut unless it bounds land: a footway is a local street of `width` where it runs
  // along a zone's edge (apply_osm_tags), else left out as `why` says.
  bool road_where_it_bounds_land = false;
  bool width_mapped = false;  // a road's width from its width or lanes tag, not its class's
};

// A way or line: a highway, or a river or canal.
OsmMeaning osm_line_meaning(const OsmTags& tags);
// An area: land use, parks, water; else a building (`building=*` but `no`), else a
// building:part (Simple 3D Buildings).
OsmMeaning osm_area_meaning(const OsmTags& tags);

// The keys read, in the order they are looked at; an OGR layer with any of them as a field
// is read for them.
const std::vector<std::string>& osm_keys();

// The tags a mapped building or building:part is raised from (generate/city/features.h,
// MappedBuilding).
const std::vector<std::string>& osm_building_keys();

// The tags a road keeps from OpenStreetMap (or from a GIS file exported from it), which
// every export carries as they were read: its highway class, name, ref, lanes, sidewalk ...
const std::vector<std::string>& osm_road_keys();
// Those of a feature's properties (columns, or GDAL's "other_tags"), in osm_road_keys' order,
// after its "osm_id" as "way/N" where it has one.
std::vector<std::pair<std::string, std::string>> osm_road_tags(const nlohmann::ordered_json& properties);
// A road's sidewalks, metres left and right of its way's direction, from its OSM tags:
// `sidewalk` for both sides, then `sidewalk:both`, then `sidewalk:left` / `sidewalk:right`
// (the newer scheme; the more specific tag wins). A side is `tagged` wide where a tag puts
// a sidewalk on it (both, yes, left, right), unless `sidewalk:<side>:width`,
// `sidewalk:both:width` or `sidewalk:width` gives a width in (0, 50] m; none for no, none
// or separate (a sidewalk drawn as a footway of its own); `untagged` where no tag says.
// A value it cannot read is as if absent; the tag is still carried to every export.
std::pair<double, double> osm_sidewalks(const std::vector<std::pair<std::string, std::string>>& tags, double untagged,
                                        double tagged);

// A file read into a sketch document: its path, and how many of the document's features
// (in order, after the files before it) are its.
struct SketchFile {
  std::filesystem::path path;
  std::size_t features = 0;
};

// Gives every feature of a sketch document in metres that has OSM tags but no "zone" or
// "road" the zone or road its tags make (a river its centre line widened to water by GEOS;
// an area without its rings of fewer than 3 distinct points, as OSM exports have them);
// features the tags make nothing of are taken out and counted by tag, each in its own
// file's counts, in the document's "osm" member: {"file": F, "skipped": {"highway=footway":
// N, ...}} for one file, {"files": [{"file": F, "skipped": ...}, ...]} for several (an
// extract's own "repaired" list stays with its file). Every feature keeps its place in
// the user's file as its "source" for messages. Features with neither OSM tags nor a zone
// or road are left for the sketch reader to refuse. Whether anything changed.
bool apply_osm_tags(nlohmann::ordered_json& doc, const std::vector<SketchFile>& files);

// The "osm" member's counts of each file: {"file": F, "skipped": ..., "repaired": ...}
// (null where there are none).
std::vector<const nlohmann::ordered_json*> osm_file_counts(const nlohmann::ordered_json& osm);

}  // namespace exacity
