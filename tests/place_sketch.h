// A measured place for `--like` (docs/gis.md), shared by the CLI's tests of it
// (like_test.cpp) and the page's upload of it (serve_test.cpp).
#pragma once

#include <nlohmann/json.hpp>

namespace place_sketch {

// A closed rectangle as GeoJSON polygon coordinates.
inline nlohmann::ordered_json rectangle(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}};
}

// A residential zone 330 m by 100 m along a road 10 m wide on y = 0, and `buildings` mapped
// footprints 10 m deep standing 5 m behind the road's surface (y = 10), 4 m apart, 10 m wide
// and 2 m more each: twelve give areas 100 to 320 m² in steps of 20 (median 200, 90th
// percentile 300).
inline nlohmann::ordered_json measured_place(int buildings = 12) {
  nlohmann::ordered_json features = nlohmann::ordered_json::array();
  features.push_back({{"type", "Feature"}, {"properties", {{"zone", "residential"}}},
                      {"geometry", {{"type", "Polygon"}, {"coordinates", rectangle(0, 0, 330, 100)}}}});
  features.push_back({{"type", "Feature"}, {"properties", {{"road", "local"}, {"width", 10}}},
                      {"geometry", {{"type", "LineString"}, {"coordinates", {{-10, 0}, {340, 0}}}}}});
  double x = 10;
  for (int i = 0; i < buildings; ++i) {
    const double w = 10 + 2 * i;
    features.push_back({{"type", "Feature"}, {"properties", {{"building", "house"}, {"height", 6 + i}}},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", rectangle(x, 10, x + w, 20)}}}});
    x += w + 4;
  }
  return {{"type", "FeatureCollection"}, {"features", features}};
}

}  // namespace place_sketch
