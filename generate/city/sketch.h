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
#include "geom/plain.h"

namespace exacity {

struct Grammar;

struct Range {
  double min = 0, max = 0;
  friend bool operator==(const Range&, const Range&) = default;
};

// Road growth parameters of one zone type (used from the road-network stage on).
struct ZoneParams {
  // How the zone's roads are laid out: "growth" (seed 000's recursive growth), "grammar"
  // (seed 002's split grammar from a file), "voronoi" (seed 003's Voronoi streets) or
  // "streets" (seed 004: none are generated; the sketch's roads are the whole network).
  std::string layout = "growth";
  std::shared_ptr<const Grammar> grammar;  // "grammar": the file, read with the sketch
  int grammar_depth = 8;                   // rules applied at most, from a root down
  double cell_size = 180;                  // m: "voronoi": one point per square this size
  double junction_spacing = 60;            // m: "voronoi": junctions at about this step along the cells' roads
  double block_area = 12000;        // m²: faces above this are subdivided again
  double segment_length = 40;       // m: one growth step
  int branches = 4;                 // roads grown from each seed point
  double jitter = 15;               // degrees: level-n orientation jitter is ±jitter/n
  double segment_deviation = 8;     // degrees: Δsegm at level 0, falling by 2 per level
  double origin_deviation = 30;     // degrees: Δorig
  std::vector<double> road_widths{12, 8};  // m: at level n, road_widths[min(n, last)]
  double min_block_area = 200;      // m²: smaller blocks become green space
  double min_block_width = 6;       // m: so do thinner ones (2 x area / perimeter)
  bool bridges = false;             // roads cross heightmap water in this zone, or stop at the shore
  // Lots: "allocation" (seed 000 measured from the street: lots side by side along every
  // road edge of a block, corner lots at its corners, the block's middle left open; four
  // quarters in industrial blocks) or "split" (seed 003: halve perpendicular to the longest
  // edge down to lot_area).
  std::string lots = "allocation";
  Range lot_width{14, 24};          // m: frontage of an allocated lot, drawn per street side
  double lot_depth = 30;            // m: how far allocated lots reach back from the street
  double lot_area = 600;            // m²: split stops below this
  double min_lot_edge = 3;          // m: allocated lots with a shorter edge are dropped
  double min_lot_area = 20;         // m²: smaller pieces of lots are dropped
  double setback = 3;               // m: footprints stand this far behind the street
  double building_gap = 4;          // m: between neighbouring footprints, and from the lot's other edges (half)
  Range footprint_width{8, 14};     // m: along the street
  Range footprint_depth{9, 14};     // m: back from the street
  double min_footprint_width = 6;   // m: no footprint narrower than this either way
  double max_footprint_area = 2000; // m²: no footprint larger
  double min_height = 4, max_height = 12;  // m: near the city centre; half that at its edge
  double min_footprint_area = 30;   // m²: smaller footprints get no building
  // "auto": gabled on near-rectangular residential footprints, hipped on the others, flat
  // elsewhere; or "flat", "gabled" (falls back to hipped), "hipped" for every footprint.
  std::string roof = "auto";
  double roof_pitch = 30;           // degrees
  // How far apart placed models stand in their rows, centre to centre (seed 002's
  // _Dense/_Sparse): "dense" 1.25–1.5 model widths, "normal" 2–3, "sparse" 4–5.
  std::string density = "normal";
};

struct TerrainSpec {
  std::filesystem::path heightmap;  // resolved against the sketch's folder
  geom::Box bounds;
  double low = 0, high = 100;       // heights of the image's lowest and highest values
};

struct ZoneFeature {
  int index = 0;                    // position in "features"
  ZoneType type = ZoneType::Residential;
  std::vector<geom::Polygon> polygons;  // rings as drawn: any orientation, maybe self-intersecting
};

struct RoadFeature {
  int index = 0;
  RoadClass road_class = RoadClass::Highway;
  double width = 24;
  std::vector<geom::Polyline> lines;
};

// The sketch's own street graph (seed 004): how it is joined, what its streets carry.
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
  std::map<ZoneType, ZoneParams> zone_params;
  std::vector<ZoneFeature> zones;
  std::vector<RoadFeature> roads;     // as joined by StreetSettings::snap
  StreetSettings streets;
  int joined_ends = 0;                // line ends moved by up to `snap` to meet another line
  std::vector<DeadEnd> dead_ends;
};

ZoneParams default_params(ZoneType type);
double road_width(const ZoneParams& p, int level);
double default_width(RoadClass road_class);

// Throws UserError with one line naming the file, the feature and the fix. With
// `read_grammars` false (for `exacity validate`, which reads a copy of the sketch away from
// its files), grammar files are named but not read.
Sketch load_sketch(const std::filesystem::path& path, bool read_grammars = true);
Sketch parse_sketch(const std::string& text, const std::filesystem::path& path, bool read_grammars = true);

}  // namespace exacity
