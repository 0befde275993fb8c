// Coordinates Exacity can work in (docs/design.md, The sketch, GIS and OSM): metres. A sketch
// in longitude and latitude (a geographic CRS, or GeoJSON without a crs whose coordinates
// span under a degree within lon/lat ranges) is projected to its UTM zone through PROJ
// once, on input, before anything exact happens; outputs carry that CRS, and city.osm is
// projected back.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

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

// Projects the sketch document's features, and the bounds of its terrain and channels, to
// the UTM zone of its centre when it is in lon/lat, and sets its "crs"; whether it did.
// Throws UserError naming `path` when its crs is one PROJ does not know.
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
