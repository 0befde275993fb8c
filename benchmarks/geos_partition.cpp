// The robustness benchmark's GEOS baseline (docs/benchmarks.md): the partition stage as a
// GIS user would write it with GEOS's overlay (OverlayNG, through its C API), in doubles.
// Zones (the last drawn on top, water zones too), water and road surfaces (the sketch's centre lines
// buffered by half their width) are overlaid into zones, water and road areas; each built
// zone's parts are blocks, and each block is cut into lots by a 25 m fishnet. No growth,
// no buildings: blocks and lots only. `--precision floating` uses GEOS's default overlay
// (floating precision, falling back to snapping and snap rounding where its noding fails,
// as GEOSIntersection does); `--precision fixed` snap-rounds every overlay on a 2^-24 m
// grid (a fixed precision model: GEOSIntersectionPrec and kin). The output is Exacity's layer
// format (vector/*.geojson and the sketch), so the same judge scores it.
//
//   exacity-geos generate SKETCH.geojson -o OUT [--precision floating|fixed] [-q] [--threads N]
//
// Exit 2 for bad input or usage, 3 when GEOS fails (an exception, NULL from an overlay).
#include <geos_c.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "benchmarks/geos_handle.h"
#include "benchmarks/partition_program.h"

namespace {

using json = nlohmann::ordered_json;
using exacity::bench::default_width;
using exacity::bench::Layers;
using exacity::bench::UsageError;

// m, the fixed precision model's cell: the snapped float build's grid (geom/exact.h), so
// the two snap-rounding baselines round alike.
constexpr double kFixedGrid = 1.0 / (1 << 24);
constexpr double kLotCell = 25;  // m, the fishnet that cuts blocks into lots

std::string geos_message;
void keep_message(const char* message, void*) { geos_message = message; }

// GEOS's reentrant C API; every overlay at the chosen precision (0: floating).
class Overlay {
 public:
  explicit Overlay(double grid) : ctx_(GEOS_init_r()), grid_(grid) {
    GEOSContext_setErrorMessageHandler_r(ctx_, keep_message, nullptr);
  }
  ~Overlay() { GEOS_finish_r(ctx_); }
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;

  using Free = exacity::bench::GeosFree;
  using Geometry = exacity::bench::GeosGeometry;

  GEOSContextHandle_t ctx() const { return ctx_; }
  // Takes a GEOS result; NULL is GEOS's failure.
  Geometry own(GEOSGeometry* g, const char* what) const {
    if (!g) throw std::runtime_error(std::string("GEOS failed in ") + what + ": " + geos_message);
    return Geometry(g, Free{ctx_});
  }
  Geometry read(const json& geometry) const {
    GEOSGeoJSONReader* reader = GEOSGeoJSONReader_create_r(ctx_);
    GEOSGeometry* g = GEOSGeoJSONReader_readGeometry_r(ctx_, reader, geometry.dump().c_str());
    GEOSGeoJSONReader_destroy_r(ctx_, reader);
    if (!g) throw UsageError("a geometry GEOS cannot read: " + geos_message);
    return Geometry(g, Free{ctx_});
  }
  Geometry intersection(const GEOSGeometry* a, const GEOSGeometry* b) const {
    return own(grid_ > 0 ? GEOSIntersectionPrec_r(ctx_, a, b, grid_) : GEOSIntersection_r(ctx_, a, b), "intersection");
  }
  Geometry difference(const GEOSGeometry* a, const GEOSGeometry* b) const {
    return own(grid_ > 0 ? GEOSDifferencePrec_r(ctx_, a, b, grid_) : GEOSDifference_r(ctx_, a, b), "difference");
  }
  Geometry union_of(const GEOSGeometry* a, const GEOSGeometry* b) const {
    return own(grid_ > 0 ? GEOSUnionPrec_r(ctx_, a, b, grid_) : GEOSUnion_r(ctx_, a, b), "union");
  }
  // The union of the parts (given away), noded: a union of lines splits them where they meet.
  Geometry union_all(std::vector<Geometry> parts, int type) const {
    std::vector<GEOSGeometry*> raw;
    for (Geometry& g : parts) raw.push_back(g.release());
    Geometry all =
        own(GEOSGeom_createCollection_r(ctx_, type, raw.data(), static_cast<unsigned>(raw.size())), "collect");
    return own(grid_ > 0 ? GEOSUnaryUnionPrec_r(ctx_, all.get(), grid_) : GEOSUnaryUnion_r(ctx_, all.get()), "union");
  }
  Geometry box(double x0, double y0, double x1, double y1) const {
    return own(GEOSGeom_createRectangle_r(ctx_, x0, y0, x1, y1), "box");
  }

  // The polygons (or lines) of a result, each as a GeoJSON geometry, empty ones left out.
  std::vector<json> parts(const GEOSGeometry* g, int wanted) const {
    std::vector<json> out;
    const int n = GEOSGetNumGeometries_r(ctx_, g);
    for (int i = 0; i < n; ++i) {
      const GEOSGeometry* part = GEOSGetGeometryN_r(ctx_, g, i);
      if (GEOSisEmpty_r(ctx_, part)) continue;
      const int type = GEOSGeomTypeId_r(ctx_, part);
      if (type == GEOS_GEOMETRYCOLLECTION || type == GEOS_MULTIPOLYGON || type == GEOS_MULTILINESTRING) {
        if (part != g)
          for (json& p : parts(part, wanted)) out.push_back(std::move(p));
        continue;
      }
      if (type != wanted) continue;  // lines and points an overlay of areas left behind
      if (type == GEOS_POLYGON) {
        json rings = json::array({positions(GEOSGetExteriorRing_r(ctx_, part))});
        for (int h = 0; h < GEOSGetNumInteriorRings_r(ctx_, part); ++h)
          rings.push_back(positions(GEOSGetInteriorRingN_r(ctx_, part, h)));
        out.push_back({{"type", "Polygon"}, {"coordinates", rings}});
      } else {
        out.push_back({{"type", "LineString"}, {"coordinates", positions(part)}});
      }
    }
    return out;
  }

 private:
  json positions(const GEOSGeometry* line) const {
    json out = json::array();
    const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(ctx_, line);
    unsigned n = 0;
    GEOSCoordSeq_getSize_r(ctx_, seq, &n);
    for (unsigned k = 0; k < n; ++k) {
      double x = 0, y = 0;
      GEOSCoordSeq_getXY_r(ctx_, seq, k, &x, &y);
      out.push_back({x, y});
    }
    return out;
  }

  GEOSContextHandle_t ctx_;
  double grid_;
};

// The partition: the layers, by name, as GeoJSON FeatureCollections.
Layers partition(const json& sketch, const Overlay& geos) {
  struct Zone {
    std::string type;
    Overlay::Geometry area;
  };
  std::vector<Zone> zones;
  std::vector<Overlay::Geometry> water_parts, surfaces, centre_lines;
  for (const json& f : sketch.at("features")) {
    const json& props = f.value("properties", json::object());
    if (props.contains("zone")) {
      Overlay::Geometry drawn = geos.read(f.at("geometry"));
      // Rings that cross or touch themselves, as drawn: made valid as a GIS user would.
      Overlay::Geometry area = geos.own(GEOSMakeValid_r(geos.ctx(), drawn.get()), "make valid");
      zones.push_back({props["zone"].get<std::string>(), std::move(area)});
    } else if (props.contains("road")) {
      Overlay::Geometry line = geos.read(f.at("geometry"));
      const double width = props.contains("width") ? props["width"].get<double>() : default_width(props["road"]);
      surfaces.push_back(geos.own(
          GEOSBufferWithStyle_r(geos.ctx(), line.get(), width / 2, 8, GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_MITRE, 4.0),
          "buffer"));
      centre_lines.push_back(std::move(line));
    }
  }
  // Each zone's part on top: the last drawn wins, a water zone as any other.
  std::vector<Overlay::Geometry> on_top(zones.size());
  Overlay::Geometry above = geos.union_all({}, GEOS_GEOMETRYCOLLECTION);
  for (std::size_t i = zones.size(); i-- > 0;) {
    on_top[i] = geos.difference(zones[i].area.get(), above.get());
    above = geos.union_of(above.get(), zones[i].area.get());
  }
  // The city's extent: every drawn zone, water included.
  const Overlay::Geometry& extent = above;
  for (std::size_t i = 0; i < zones.size(); ++i)
    if (zones[i].type == "water") water_parts.push_back(geos.own(GEOSGeom_clone_r(geos.ctx(), on_top[i].get()), "clone"));
  const Overlay::Geometry water = geos.union_all(std::move(water_parts), GEOS_GEOMETRYCOLLECTION);
  // Water over road over the zone on top.
  const Overlay::Geometry roads = geos.difference(
      geos.intersection(geos.union_all(std::move(surfaces), GEOS_GEOMETRYCOLLECTION).get(), extent.get()).get(),
      water.get());
  std::vector<Overlay::Geometry> own_area(zones.size());
  for (std::size_t i = 0; i < zones.size(); ++i)
    if (zones[i].type != "water") own_area[i] = geos.difference(on_top[i].get(), roads.get());

  Layers layers;
  auto add = [&](const char* layer, json geometry, json properties) {
    return layers.add(layer, std::move(geometry), std::move(properties));
  };
  for (json& p : geos.parts(water.get(), GEOS_POLYGON)) add("water", std::move(p), json::object());
  for (json& p : geos.parts(roads.get(), GEOS_POLYGON)) add("road_areas", std::move(p), {{"bridge", false}});
  for (std::size_t i = 0; i < zones.size(); ++i) {
    const std::string& type = zones[i].type;
    if (type == "water") continue;  // in the water layer
    for (json& p : geos.parts(own_area[i].get(), GEOS_POLYGON)) {
      add("zones", p, {{"zone", type}});
      if (type == "park") continue;
      const int block = add("blocks", p, {{"zone", type}});
      // The block cut by the fishnet: each cell's share of it is a lot.
      const Overlay::Geometry area = geos.read(p);
      double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
      GEOSGeom_getXMin_r(geos.ctx(), area.get(), &x0), GEOSGeom_getYMin_r(geos.ctx(), area.get(), &y0);
      GEOSGeom_getXMax_r(geos.ctx(), area.get(), &x1), GEOSGeom_getYMax_r(geos.ctx(), area.get(), &y1);
      for (double x = std::floor(x0 / kLotCell) * kLotCell; x < x1; x += kLotCell)
        for (double y = std::floor(y0 / kLotCell) * kLotCell; y < y1; y += kLotCell) {
          const Overlay::Geometry cell = geos.box(x, y, x + kLotCell, y + kLotCell);
          for (json& lot : geos.parts(geos.intersection(area.get(), cell.get()).get(), GEOS_POLYGON))
            add("lots", std::move(lot), {{"zone", type}, {"block", block}});
        }
    }
  }
  // The drawn centre lines, noded where they meet: every piece is a road the sketch drew.
  const Overlay::Geometry network = geos.union_all(std::move(centre_lines), GEOS_GEOMETRYCOLLECTION);
  for (json& line : geos.parts(network.get(), GEOS_LINESTRING))
    add("roads", std::move(line), {{"level", nullptr}, {"region", nullptr}, {"bridge", false}});
  return layers;
}

}  // namespace

int main(int argc, char** argv) {
  double grid = 0;
  return exacity::bench::partition_main(
      argc, argv, "exacity-geos", "exacity-geos generate SKETCH.geojson -o OUT [--precision floating|fixed]",
      [&](const std::string& name, const std::string& value) {
        if (name != "--precision") return false;
        if (value != "floating" && value != "fixed") throw UsageError("--precision: floating or fixed, not " + value);
        grid = value == "fixed" ? kFixedGrid : 0;
        return true;
      },
      [&](const json& sketch) { return partition(sketch, Overlay(grid)); });
}
