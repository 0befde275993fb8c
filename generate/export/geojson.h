// Vector layers as GeoJSON: written with shortest round-trip doubles, closed rings, outer
// rings counter-clockwise and holes clockwise; read back for validation.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city/format_number.h"
#include "geom/plain.h"

namespace exacity {

struct VectorFeature {
  nlohmann::ordered_json properties;
  geom::Polygon polygon;  // for polygon layers
  geom::Polyline line;    // for line layers; for point layers, the one point
};

struct Layer {
  std::string name;
  bool lines = false;
  std::vector<VectorFeature> features;
};

void write_geojson(const Layer& layer, const nlohmann::ordered_json& crs, const std::filesystem::path& file);

// A layer of Points, each feature's line holding its one point.
void write_point_geojson(const Layer& layer, const nlohmann::ordered_json& crs, const std::filesystem::path& file);

// Reads a layer written by write_geojson or write_point_geojson (or any GeoJSON of
// Polygons, LineStrings or Points).
// Anything malformed is appended to `problems`, one line each, and skipped.
Layer read_geojson(const std::filesystem::path& file, std::vector<std::string>& problems);

}  // namespace exacity
