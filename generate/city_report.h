// report.json: what the generate job made, counted and explained from the city and the
// exports' own counts (docs/design.md, Outputs).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city.h"
#include "generate/export/gltf_export.h"
#include "generate/export/mesh_export.h"
#include "generate/export/validate.h"
#include "generate/pipeline.h"

namespace exacity {

// What the write stages learnt, besides the city.
struct WrittenCity {
  std::optional<ThreeDCounts> three_d;  // none: not written (exacity serve writes them when first downloaded)
  std::vector<std::string> vector_formats;  // beside GeoJSON
  bool city_osm = false;                     // city.osm written (the sketch has a CRS)
  std::optional<Validation> validation;  // none: this build's kernel cannot check its own output
};

// The report, with the stages' timings under timings_s.
nlohmann::ordered_json city_report(const City& city, const WrittenCity& written, const nlohmann::ordered_json& timings);
void write_report(const nlohmann::ordered_json& report, const std::filesystem::path& dir);

}  // namespace exacity
