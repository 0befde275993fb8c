#include "generate/gis/zone_inference.h"

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <ogr_geometry.h>

#include "generate/gis/ogr_polygon.h"

namespace exacity {
using nlohmann::ordered_json;

namespace {

using Geometry = std::unique_ptr<OGRGeometry>;

Geometry from_json(const ordered_json& geometry) {
  if (!geometry.is_object()) return nullptr;
  return Geometry(OGRGeometryFactory::createFromGeoJson(geometry.dump().c_str()));
}

ordered_json to_json(const OGRGeometry& g) {
  char* text = g.exportToJson();
  ordered_json out = ordered_json::parse(text ? text : "null", nullptr, false);
  CPLFree(text);
  return out.is_discarded() ? nullptr : out;
}

double area_of(const OGRGeometry& g) {
  const OGRwkbGeometryType t = wkbFlatten(g.getGeometryType());
  if (t == wkbPolygon) return g.toPolygon()->get_Area();
  if (t == wkbMultiPolygon) return g.toMultiPolygon()->get_Area();
  if (t == wkbGeometryCollection) return g.toGeometryCollection()->get_Area();
  return 0;
}

// The zone a building's tag says it stands in, or empty when the tag does not say.
std::string zone_of_tag(const std::string& tag) {
  static const std::set<std::string> residential{"house",     "residential", "apartments", "detached",
                                                 "semidetached_house", "terrace", "bungalow", "dormitory",
                                                 "farm",      "cabin",       "houseboat",  "garage",
                                                 "garages",   "shed",        "carport"};
  static const std::set<std::string> commercial{"commercial", "retail",     "office",   "supermarket", "kiosk",
                                                "hotel",      "shop",       "public",   "civic",       "government",
                                                "school",     "university", "college",  "kindergarten", "hospital",
                                                "church",     "chapel",     "mosque",   "temple",      "train_station",
                                                "transportation"};
  static const std::set<std::string> industrial{"industrial", "warehouse", "factory", "manufacture", "hangar",
                                                "storage_tank", "service"};
  if (residential.count(tag)) return "residential";
  if (commercial.count(tag)) return "commercial";
  if (industrial.count(tag)) return "industrial";
  return "";
}

// An untagged building ("yes") this large or larger is taken for a shop's or an office's.
constexpr double kLargeBuilding = 500;  // m2
// m: the streets' centre lines grown by this to find the faces between them.
constexpr double kHair = 0.01;
// A face whose part outside every zone is under this share of it is covered by land use.
constexpr double kOpenShare = 0.1;

// The polygons of a GEOS result (a difference may hold lines and points where the zones
// touch a face's edge), without those under a square metre.
OGRMultiPolygon polygons_of(const OGRGeometry& g) {
  OGRMultiPolygon out;
  const OGRwkbGeometryType t = wkbFlatten(g.getGeometryType());
  if (t == wkbPolygon) {
    if (g.toPolygon()->get_Area() >= 1) out.addGeometry(&g);
  } else if (t == wkbMultiPolygon || t == wkbGeometryCollection) {
    for (const OGRGeometry* part : *g.toGeometryCollection())
      if (wkbFlatten(part->getGeometryType()) == wkbPolygon && part->toPolygon()->get_Area() >= 1) out.addGeometry(part);
  }
  return out;
}

struct MappedFootprint {
  std::unique_ptr<OGRPoint> centre;
  double area = 0;
  std::string zone;
};

}  // namespace

void infer_zones(ordered_json& doc) {
  ordered_json& features = doc["features"];
  OGRMultiLineString streets;
  OGRMultiPolygon zoned;
  std::vector<MappedFootprint> buildings;
  for (const ordered_json& f : features) {
    if (!f.is_object() || !f.contains("properties") || !f["properties"].is_object() || !f.contains("geometry")) continue;
    const ordered_json& p = f["properties"];
    Geometry g = from_json(f["geometry"]);
    if (!g) continue;
    const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
    if (p.contains("road")) {
      if (type == wkbLineString) streets.addGeometry(g.get());
      else if (type == wkbMultiLineString)
        for (const OGRLineString* l : *g->toMultiLineString()) streets.addGeometry(l);
    } else if (p.contains("zone") || p.contains("building")) {
      // Drawn rings may cross themselves: GEOS's MakeValid first.
      Geometry valid(g->MakeValid());
      if (!valid) continue;
      if (p.contains("building")) {
        MappedFootprint b{std::make_unique<OGRPoint>(), area_of(*valid), ""};
        if (valid->Centroid(b.centre.get()) != OGRERR_NONE) continue;
        const std::string tag = p["building"].is_string() ? p["building"].get<std::string>() : "yes";
        b.zone = zone_of_tag(tag);
        if (b.zone.empty()) b.zone = b.area < kLargeBuilding ? "residential" : "commercial";
        buildings.push_back(std::move(b));
        continue;
      }
      for (const OGRPolygon* part : polygons_of(*valid)) zoned.addGeometry(part);
    }
  }
  ordered_json counts{{"street_faces", 0}, {"faces_with_land_use", 0}, {"inferred", ordered_json::object()}, {"left_open", 0}};
  // The faces: the land the streets' centre lines (each grown by a hair, which GEOS's buffer
  // unions and nodes wherever they cross) enclose, within a box around them; the land
  // reaching the box is enclosed by none.
  std::vector<std::unique_ptr<OGRPolygon>> faces;
  if (!streets.IsEmpty()) {
    OGREnvelope e;
    streets.getEnvelope(&e);
    const OGRPolygon box = box_around(e, 1);
    Geometry lines(streets.Buffer(kHair, 2));
    Geometry between(lines ? box.Difference(lines.get()) : nullptr);
    if (between)
      for (const OGRPolygon* part : polygons_of(*between)) {
        OGREnvelope p;
        part->getEnvelope(&p);
        if (p.MinX > e.MinX - 1 && p.MinY > e.MinY - 1 && p.MaxX < e.MaxX + 1 && p.MaxY < e.MaxY + 1)
          faces.emplace_back(part->clone());
      }
  }
  Geometry land(zoned.IsEmpty() ? nullptr : zoned.UnionCascaded());
  std::map<std::string, int> inferred;
  for (const std::unique_ptr<OGRPolygon>& face : faces) {
      counts["street_faces"] = counts["street_faces"].get<int>() + 1;
      Geometry difference(land ? face->Difference(land.get()) : face->clone());
      const Geometry open = difference ? Geometry(polygons_of(*difference).clone()) : nullptr;
      if (!open || open->IsEmpty() || area_of(*open) < kOpenShare * area_of(*face)) {
        counts["faces_with_land_use"] = counts["faces_with_land_use"].get<int>() + 1;
        continue;
      }
      std::map<std::string, double> votes;
      OGREnvelope bounds;
      open->getEnvelope(&bounds);
      for (const MappedFootprint& b : buildings) {
        const double x = b.centre->getX(), y = b.centre->getY();
        if (x < bounds.MinX || x > bounds.MaxX || y < bounds.MinY || y > bounds.MaxY || !b.centre->Within(open.get())) continue;
        votes[b.zone] += b.area;
      }
      if (votes.empty()) {
        counts["left_open"] = counts["left_open"].get<int>() + 1;
        continue;
      }
      std::string zone = votes.begin()->first;
      for (const auto& [z, area] : votes)
        if (area > votes[zone]) zone = z;
      ++inferred[zone];
      ordered_json geometry = to_json(*open);
      if (geometry.is_null()) continue;
      features.push_back({{"type", "Feature"},
                          {"properties", {{"zone", zone}, {"source", "street face " + std::to_string(counts["street_faces"].get<int>() - 1) +
                                                                         " (zone inferred from its mapped buildings)"}}},
                          {"geometry", std::move(geometry)}});
    }
  for (const auto& [zone, n] : inferred) counts["inferred"][zone] = n;
  doc["land_use"] = std::move(counts);
}

}  // namespace exacity
