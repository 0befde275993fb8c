// What the sketch's readers share (generate/sketch/sketch.cpp reads a GeoJSON document,
// sketch_files.cpp makes one from files of other formats or several files).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace exacity {

// Gives the zone types that get roads each of `defaults` they do not set themselves: a
// planned map's or a real place's roads are its streets already.
void default_street_zones(nlohmann::ordered_json& ex, const nlohmann::ordered_json& defaults);

// A document Exacity made (a grid map's; a sketch with its "grid" or --models applied) as
// text: JSON, each feature on a line of its own.
std::string document_text(const nlohmann::ordered_json& doc);

}  // namespace exacity
