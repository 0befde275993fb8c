// The settings the stages read (docs/design.md, The sketch): the city's (seed, CRS, each
// zone type's), and a zone type's, one struct per step. Each step reads and checks its own
// (generate/layout/road_settings.h, generate/parcels/parcel_settings.h,
// generate/placement/building_settings.h); where a zone chooses among alternatives (its
// road layout, lot layout, placer), the name is parsed there once, from that step's table,
// into the chosen alternative.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city/settings.h"
#include "generate/city/zone_type.h"

namespace exacity {

class RoadLayout;
struct LayoutSite;
class LotLayout;
class Placer;
struct ModelLibrary;
class Channels;

// Recursive road growth (docs/design.md, Road layouts). Every zone type has these, whatever its layout: growth also grows the
// large land a grammar leaves, as the zone at each seed, and block_area sizes the city.
struct GrowthSettings {
  double block_area = 12000;      // m²: faces above this are subdivided again
  double segment_length = 40;     // m: one growth step
  int branches = 4;               // roads grown from each seed point
  double jitter = 15;             // degrees: level-n orientation jitter is ±jitter/n
  double segment_deviation = 8;   // degrees: Δsegm at level 0, falling by 2 per level
  double origin_deviation = 30;   // degrees: Δorig
};

// A zone type's road layout as the sketch chose it from the table of road layouts
// (road_layout_types, generate/layout/road_settings.h), carrying that layout's own settings.
class RoadLayoutChoice {
 public:
  explicit RoadLayoutChoice(std::string name) : name_(std::move(name)) {}
  virtual ~RoadLayoutChoice() = default;
  const std::string& name() const { return name_; }
  // The layout of a region of the zone type.
  virtual std::unique_ptr<RoadLayout> make(const LayoutSite& site) const = 0;
  // Whether a region is the connected land of every zone type laid out so, each cell as
  // the zone it lies in (growth), rather than one zone type's.
  virtual bool spans_zone_types() const { return false; }
  // Whether the layout lays roads of its own: a generated road paves only such zones.
  virtual bool generates_roads() const { return true; }
  // The lot layout the zone takes unless it names one.
  virtual const char* default_lots() const { return "allocation"; }

 private:
  std::string name_;
};

struct RoadSettings {
  std::shared_ptr<const RoadLayoutChoice> layout;
  std::vector<double> road_widths{12, 8};  // m: at level n, road_widths[min(n, last)]
  bool bridges = false;                    // roads cross heightmap water in this zone, or stop at the shore
  GrowthSettings growth;
};

struct BlockSettings {
  double min_block_area = 200;  // m²: smaller blocks become green space
  double min_block_width = 6;   // m: so do thinner ones (2 x area / perimeter)
};

// A zone type's lot layout as the sketch chose it from the table of lot layouts
// (lot_layout_types, generate/parcels/parcel_settings.h), carrying that layout's own settings.
class LotLayoutChoice {
 public:
  explicit LotLayoutChoice(std::string name) : name_(std::move(name)) {}
  virtual ~LotLayoutChoice() = default;
  const std::string& name() const { return name_; }
  // The layout of the zone type's blocks; `library` may be null unless models_own_lots.
  virtual std::unique_ptr<LotLayout> make(ZoneType zone, const ModelLibrary* library, const Channels& channels) const = 0;
  // Its lots are the model library's own, each for one model (Lot::model), which stands
  // on it: no block is one lot when it fits none.
  virtual bool models_own_lots() const { return false; }

 private:
  std::string name_;
};

struct LotSettings {
  // "allocation" (lots along the street), "split" (recursive splitting) or "library" (the
  // lots the model library's entries ask for), with that layout's own settings.
  std::shared_ptr<const LotLayoutChoice> layout;
  double min_lot_area = 20;  // m²: smaller pieces of lots are dropped
};

// A zone type's placer as the sketch chose it from the table of placers (placer_types,
// generate/placement/building_settings.h), carrying that placer's own settings.
class PlacerChoice {
 public:
  explicit PlacerChoice(std::string name) : name_(std::move(name)) {}
  virtual ~PlacerChoice() = default;
  const std::string& name() const { return name_; }
  // The placer of the library's buildings on the zone type's lots; none when the library
  // has no building for it.
  virtual std::unique_ptr<Placer> make(const ModelLibrary& library, ZoneType zone, const Channels& channels) const = 0;
  // It stands models under others' overhangs (nesting), so the library's models are cut
  // into slabs.
  virtual bool nests() const { return false; }

 private:
  std::string name_;
};

struct BuildingSettings {
  double setback = 3;                 // m: footprints stand this far behind the street
  double building_gap = 4;            // m: between neighbouring footprints, and from the lot's other edges (half)
  Range footprint_width{8, 14};       // m: along the street
  Range footprint_depth{9, 14};       // m: back from the street
  double min_footprint_width = 6;     // m: no footprint narrower than this either way
  // m²: when given, footprint areas at equal steps of their distribution, smallest to
  // largest (a real place's, measured by --like): each footprint's area is drawn from it,
  // its shape from footprint_width and footprint_depth. Empty: sides drawn from those alone.
  std::vector<double> footprint_areas;
  double max_footprint_area = 2000;   // m²: no footprint larger
  // m: above 0, an extruded zone's lots build perimeter blocks (generate/placement/
  // perimeter.h): each lot's land this deep behind its street frontages, whatever its
  // size; the rows' sizes above apply only where that leaves nothing.
  double perimeter_depth = 0;
  // Above 0, the rows' lots are filled further, row behind row, until their footprints
  // cover this share of the lot (a real place's coverage, measured by --like); 0: one row.
  double lot_coverage = 0;
  double min_footprint_area = 30;     // m²: smaller footprints get no building
  double min_height = 4, max_height = 12;  // m: near the city centre; half that at its edge
  // "auto": gabled on near-rectangular residential footprints, hipped on the others, flat
  // elsewhere; or "flat", "gabled" (falls back to hipped), "hipped" for every footprint.
  std::string roof = "auto";
  double roof_pitch = 30;             // degrees
  double storey_height = 3;           // m: a mapped building's building:levels times this is its walls' height
  // How far apart placed models stand in their rows, centre to centre (a grammar's
  // _Dense/_Sparse): "dense" 1.25–1.5 model widths, "normal" 2–3, "sparse" 4–5.
  std::string density = "normal";
  // How the library's buildings fill a lot: "rows" along the street or "grid" (grid
  // filling), with that placer's own settings.
  std::shared_ptr<const PlacerChoice> placement;
  // A channel whose value takes the place of nearness to the city's centre in the
  // extruded buildings' heights (building_height); empty for none.
  std::string height_channel;
};

// One zone type's settings, each step's read by that step.
struct ZoneSettings {
  RoadSettings roads;
  BlockSettings blocks;
  LotSettings lots;
  BuildingSettings buildings;
};

// What the stages read of the sketch besides its drawn features (generate/city/features.h).
struct CitySettings {
  std::filesystem::path path;        // the sketch's file, which messages name
  std::uint64_t seed = 1;
  nlohmann::ordered_json crs;        // null when the sketch has none; copied as written
  std::map<ZoneType, ZoneSettings> zone_settings;
};

}  // namespace exacity
