// Coordinates Exacity can work in (docs/design.md, The sketch, GIS and OSM): ground metres.
// A sketch whose CRS is not a map in metres true to scale where it lies (longitude and
// latitude, Web Mercator, feet, a projection far from scale 1 there) is projected to the
// UTM zone of its centre through PROJ once, on input, before anything exact happens;
// outputs carry that CRS, and city.osm is projected back.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geom/plain.h"

namespace exacity {

// Registers GDAL's drivers (once) and keeps its messages off the terminal: each failure is
// reported as one line of Exacity's, with CPLGetLastErrorMsg's text in it.
void start_gdal();

// A CRS by its EPSG code, as GeoJSON's "crs" member names it.
nlohmann::ordered_json crs_member(int epsg);
// The EPSG code a GeoJSON "crs" member names, if it names one.
std::optional<int> epsg_of(const nlohmann::ordered_json& crs);

// The UTM zone's EPSG code (WGS 84) for a point in lon/lat.
int utm_epsg(double lon, double lat);

// A sketch document as read from its file, in the file's own CRS.
struct SketchPart {
  nlohmann::ordered_json doc;
  std::filesystem::path path;
};

// Brings every part's features, and the bounds of the terrain and channels in its settings,
// from its own CRS to one CRS in metres, and sets each part's "crs" to it: the first CRS
// among the parts that is projected, in metres and within 1% of scale 1 at the sketch's
// centre (a national grid, UTM), else the UTM zone of the sketch's centre. A part without
// a crs is lon/lat when its positions lie in lon/lat ranges, are not all whole numbers and
// span under 30 degrees (or all but one feature's under 1); such positions spanning more
// with features mostly under 1 across are refused (places too far apart, a crs to name);
// any other part without a crs is in the other parts' CRS, else in metres with no place
// on Earth. Longitudes are read around the antimeridian where the sketch crosses
// it. Throws UserError, naming the extent and the feature farthest from the rest, when
// the CRS's scale at the extent's edge is more than 1% off (a sketch one flat map cannot
// hold), and naming the file when PROJ does not know its crs. The CRS's "crs" member,
// null when no part has a place on Earth.
nlohmann::ordered_json project_to_metres(std::vector<SketchPart>& parts);
// The same for one document; whether its positions or crs changed.
bool project_to_metres(nlohmann::ordered_json& doc, const std::filesystem::path& path);

// Points from a CRS in metres (EPSG `from`) to lon/lat, in place, for city.osm.
class ToLonLat {
 public:
  explicit ToLonLat(int from_epsg);
  ~ToLonLat();
  ToLonLat(const ToLonLat&) = delete;
  ToLonLat& operator=(const ToLonLat&) = delete;
  geom::Vec2 operator()(geom::Vec2 p) const;

 private:
  void* transform_;  // OGRCoordinateTransformation, kept out of this header
};

}  // namespace exacity
