// report.json: what the generate job made, counted and explained from the city and the
// exports' own counts (docs/design.md, Outputs).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city.h"
#include "generate/export/validate.h"
#include "generate/pipeline.h"

namespace exacity {

// What the 3D export and validation learnt, besides the city.
struct WrittenCity {
  std::optional<ThreeDCounts> three_d;  // none: not written (exacity serve writes them when first downloaded)
  std::optional<Validation> validation;  // none: this build's kernel cannot check its own output,
  bool validation_later = false;         // or it is checked after this report is written (validate_written)
};

// What report.json says of the network, the blocks and the lots (the road network, the
// roads generated, the blocks and green spaces, the map's size, the empty zones, the
// footprints by zone): build_city counts it into City::exact_report before it frees them,
// and city_report reads it there.
nlohmann::ordered_json exact_work_report(const City& city);

// The report of what the city holds, made before the 3D export (so that what only it reads
// of the city, its map and layers, can be freed then): `vector_formats` written beside
// GeoJSON, `city_osm` whether city.osm was (the sketch has a CRS). The 3D exports' counts,
// the validation and the timings are left for complete_report, in their places. `sketch`
// gives what its readers took and left out of OpenStreetMap's features.
nlohmann::ordered_json city_report(const Sketch& sketch, const City& city, const std::vector<std::string>& vector_formats,
                                   bool city_osm);
// Fills in those (the 3D exports' counts left out when they were not written), with the stages' timings under timings_s; reads only the city's cache.
void complete_report(nlohmann::ordered_json& report, const City& city, const WrittenCity& written,
                     const nlohmann::ordered_json& timings);
// report.json's "validation" as `written` says.
void report_validation(nlohmann::ordered_json& report, const WrittenCity& written);
// Written aside and renamed, so a reader of the folder never sees half of it.
void write_report(const nlohmann::ordered_json& report, const std::filesystem::path& dir);

}  // namespace exacity
