// A zone type's road settings ("exacity".zones.TYPE, docs/design.md, The sketch): which
// layout lays out its roads, and each layout's own settings, read and checked here.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "generate/city/settings.h"
#include "generate/city/zone_type.h"

namespace exacity {

struct Grammar;

// Recursive road growth (docs/design.md, Road layouts).
struct GrowthSettings {
  double block_area = 12000;      // m²: faces above this are subdivided again
  double segment_length = 40;     // m: one growth step
  int branches = 4;               // roads grown from each seed point
  double jitter = 15;             // degrees: level-n orientation jitter is ±jitter/n
  double segment_deviation = 8;   // degrees: Δsegm at level 0, falling by 2 per level
  double origin_deviation = 30;   // degrees: Δorig
};

// The split grammar (docs/design.md, Road layouts).
struct GrammarSettings {
  std::shared_ptr<const Grammar> file;  // read with the sketch
  int depth = 8;                        // rules applied at most, from a root down
  bool grow_large_pieces = true;        // land over 4 x block_area is grown by recursive growth
};

// The Voronoi layout (docs/design.md, Road layouts).
struct VoronoiSettings {
  double cell_size = 180;         // m: one point per square this size
  double junction_spacing = 60;   // m: junctions at about this step along the cells' roads
};

struct RoadSettings {
  // "growth", "grammar", "voronoi" or "streets" (the street graph: none are generated; the sketch's
  // roads are the whole network).
  std::string layout = "growth";
  std::vector<double> road_widths{12, 8};  // m: at level n, road_widths[min(n, last)]
  bool bridges = false;                    // roads cross heightmap water in this zone, or stop at the shore
  GrowthSettings growth;
  GrammarSettings grammar;
  VoronoiSettings voronoi;
};

RoadSettings default_road_settings(ZoneType type);
double road_width(const RoadSettings& s, int level);

// The keys read_road_settings reads.
const std::set<std::string>& road_setting_keys();

// `settings` over `defaults`. With `read_grammars` false (for `exacity validate`, which reads
// a copy of the sketch away from its files), grammar files are named but not read.
RoadSettings read_road_settings(const SettingsReader& settings, RoadSettings defaults, bool read_grammars);

}  // namespace exacity
