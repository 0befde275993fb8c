// The city's vector and 3D formats as one table: each format's name, the files it writes
// into the output folder and its writer. The CLI's --vector-format takes the optional
// vector formats' names from it, the pipeline runs its writers (the vector formats in the
// export stage, the 3D formats in the 3D export), and docs/outputs.md names every file it
// lists (a test checks).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/export/geojson.h"
#include "generate/export/gltf_export.h"
#include "generate/export/meshed_city.h"
#include "generate/export/mesh_export.h"

namespace exacity {

struct ThreeDCounts {
  MeshCounts mesh;
  GltfCounts gltf;
};

// What a writer writes from: the vector layers (vector_files: the export stage's formats)
// or the meshed city (the 3D export's), into `dir`.
struct FormatInput {
  const std::filesystem::path& dir;
  const std::vector<const Layer*>* layers = nullptr;
  const nlohmann::ordered_json* crs = nullptr;  // the sketch's, with the layers
  const MeshedCity* meshed = nullptr;
  bool cityjson_seq = false;  // CityJSON's writer writes city.city.jsonl as well
  ThreeDCounts* counts = nullptr;  // what the 3D writers count
};

enum class FormatKind {
  Vector,          // always written (validate reads it)
  OptionalVector,  // with --vector-format NAME
  ThreeD,          // in the 3D export
};

struct CityFormat {
  const char* name;
  FormatKind kind;
  const char* files;  // as OUT/... names them
  void (*write)(const FormatInput&);
};

extern const std::vector<CityFormat> kCityFormats;

// The names --vector-format takes: every vector format's.
std::vector<std::string> vector_format_names();
// The optional vector formats as --vector-format's help lists them: "gpkg (OUT/city.gpkg), ...".
std::string optional_vector_formats_text();

}  // namespace exacity
