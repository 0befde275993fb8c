// The sketch the server holds: work/sketch.geojson and the heightmap beside it, checked as
// the CLI checks a sketch before anything is stored (docs/design.md, Serving).
#pragma once

#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/sketch/sketch.h"
#include "serve/confined_folder.h"

namespace exacity::serve {

class WorkSketch {
 public:
  explicit WorkSketch(const ConfinedFolder& work) : work_(work) {}

  std::filesystem::path file() const { return work_.root() / "sketch.geojson"; }
  // The stored sketch's text; without one, an empty sketch (which PUT would refuse).
  std::string text() const;
  bool stored() const;
  // Reads the stored sketch as generate does. Throws UserError.
  Sketch load() const;
  // Checks `text` (parse_sketch, and every file it names is inside the work folder), then
  // stores it. Throws UserError with the CLI's one-line message.
  Sketch put(const std::string& text);
  // Stores an uploaded heightmap (PNG, TIFF or EXR, read as the terrain stage reads it) and
  // points the sketch's terrain at it; `bounds` and `height` ("A,B,C,D", "LOW,HIGH") default to
  // the sketch's own, else the drawn features' extent and 0..100 m. Throws UserError.
  Sketch put_heightmap(const std::string& bytes, const std::string& bounds, const std::string& height);
  // A model library uploaded as files, each named by its path below the library's folder
  // (the manifest, the one .json file; OBJ, .mtl and texture files): stored as work/models in
  // place of the library there, read as the model library stage reads it, and named by the
  // sketch's "models". Throws UserError (a bad library's message is the CLI's); then the work
  // folder and the sketch stay as they were.
  Sketch put_library(const std::vector<std::pair<std::string, std::string>>& files);
  // A real place uploaded as files (generate --like): an OSM extract, or footprints as
  // GeoJSON, GeoPackage, FlatGeobuf or a shapefile with its .shx, .dbf, .prj and .cpg, the
  // one file that is no shapefile's companion the place. Stored as work/like in place of the
  // files there, measured as generate measures it (a file it cannot measure is refused with
  // the CLI's message) and named by the sketch's "like". Throws UserError; then the work
  // folder and the sketch stay as they were.
  Sketch put_like(const std::vector<std::pair<std::string, std::string>>& files);
  // What the place the sketch's "like" names measures and sets, as report.json's "like" holds
  // it, with its file named in the work folder; null when the sketch names none. Throws UserError.
  nlohmann::ordered_json like_measured() const;
  // An 8-bit picture of the heightmap for the page: grey by height, its water (value 0) in
  // the map's water colour; nullopt when the sketch has none.
  std::optional<std::string> heightmap_preview() const;
  // Copies a sketch from elsewhere into the work folder (exacity serve SKETCH): its heightmap,
  // channel images, grammars and model library come along, and the copy names them. Throws
  // UserError.
  void import(const std::filesystem::path& sketch);

 private:
  Sketch check(const std::string& text) const;
  // Refuses a model library whose manifest, OBJ or .mtl files are not all in the work folder.
  void check_library(const std::string& manifest) const;
  // Copies a model library into work/models; returns the manifest's name there.
  std::string import_library(const std::filesystem::path& manifest);
  // Writes `files` as work/FOLDER in place of the folder there and returns the sketch's text
  // with `key` naming `named` (a path below it); then `take(sketch_text)` checks it. When that
  // throws, the folder and the sketch from before are put back. Call with mutex_ held.
  std::string replace_folder(const std::string& folder, const std::vector<std::pair<std::string, std::string>>& files,
                             const std::string& key, const std::string& named,
                             const std::function<void(const std::string&)>& take);
  void store(const std::string& text);
  const ConfinedFolder& work_;
  mutable std::mutex mutex_;
};

}  // namespace exacity::serve
