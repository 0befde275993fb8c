// Reading a city's layer files again after an edit (docs/design.md, Regions and
// regenerating): each file's features kept by the text of their lines, so a reading parses
// only the lines it has not read.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "generate/export/geojson.h"
#include "generate/export/vector_layers.h"

namespace exacity {

// A layer file's features as its last read read them, by the text of each one's line
// (write_geojson writes a feature a line).
struct ReadLines {
  struct Read {
    VectorFeature feature;
    bool line_string = false;
  };
  struct TextHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view text) const { return std::hash<std::string_view>{}(text); }
  };
  std::unordered_map<std::string, Read, TextHash, std::equal_to<>> by_text;
  int reused = 0, parsed = 0;  // lines of the last read
};

// read_geojson's layer, problems and all, parsing only what `known` does not hold: a file
// laid out as write_geojson lays it out (the collection's first line, then a feature a
// line, each but the last ending in a comma, then "]}") whose feature lines not known are
// each in write_geojson's layout (its scanner takes them) is read line by line, each line that `known` holds taken as read then
// (a JSON value's reading depends on its text alone); any other file is read whole.
// Afterwards `known` holds this read's lines.
Layer read_geojson(const std::filesystem::path& file, std::vector<std::string>& problems, ReadLines& known);

// read_layers, each layer read as above with the ReadLines under its name in `known`.
CityLayers read_layers(const std::filesystem::path& vector_dir, std::vector<std::string>& problems,
                       std::map<std::string, ReadLines>& known);

}  // namespace exacity
