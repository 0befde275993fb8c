#include "serve/work_sketch.h"

#include <OpenImageIO/imageio.h>
#include <gdal.h>

#include <cstdio>
#include <fstream>
#include <cctype>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <system_error>
#include <vector>

#include "generate/city/grey_image.h"
#include "generate/city/palette.h"
#include "generate/errors.h"
#include "generate/placement/obj_file.h"
#include "generate/placement/model_library.h"
#include "generate/sketch/like_place.h"

namespace exacity::serve {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* kEmptySketch =
    "{\"type\": \"FeatureCollection\", \"exacity\": {\"version\": 1, \"seed\": 1}, \"features\": []}\n";

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Written aside and renamed, so a reader never sees half a file.
void write_file(const fs::path& file, const std::string& bytes) {
  const fs::path aside = file.parent_path() / ("." + file.filename().string() + ".partial");
  {
    std::ofstream out(aside, std::ios::binary | std::ios::trunc);
    out << bytes;
    if (!out) throw UserError(file.string() + ": write failed (disk full?)");
  }
  fs::rename(aside, file);
}

// The sketch's JSON for the file check only: numbers beyond a double's range (which
// parse_sketch marks and names) read as 0 here, so no sketch escapes the check by them.
json json_for_check(std::string text) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    try {
      return json::parse(text);
    } catch (const json::out_of_range& e) {
      const std::string what = e.what();
      const auto open = what.find('\''), close = what.rfind('\'');
      const std::string literal = open < close ? what.substr(open + 1, close - open - 1) : "";
      const auto at = literal.empty() ? std::string::npos : text.find(literal);
      if (e.id != 406 || at == std::string::npos) return json();
      text.replace(at, literal.size(), "0");
    } catch (const json::exception&) {
      return json();  // malformed: parse_sketch says where, before reading any file
    }
  }
  return json();
}

// Every file the sketch's settings name (docs/sketch.md), with the key that names it.
std::vector<std::pair<std::string, std::string>> named_files(const json& ex) {
  std::vector<std::pair<std::string, std::string>> files;
  auto add = [&](const json& j, const char* key, const std::string& where) {
    if (j.is_object() && j.contains(key) && j[key].is_string()) files.emplace_back(where, j[key].get<std::string>());
  };
  if (ex.contains("terrain")) add(ex["terrain"], "heightmap", "\"exacity\".terrain.heightmap");
  add(ex, "grid", "\"exacity\".grid");
  add(ex, "like", "\"exacity\".like");
  if (ex.contains("channels") && ex["channels"].is_object())
    for (const auto& [name, c] : ex["channels"].items()) add(c, "image", "\"exacity\".channels." + name + ".image");
  if (ex.contains("zones") && ex["zones"].is_object())
    for (const auto& [name, z] : ex["zones"].items()) add(z, "grammar", "\"exacity\".zones." + name + ".grammar");
  return files;
}

// The file type an upload's first bytes say, as the extension it is stored under.
std::string image_extension(const std::string& bytes) {
  if (bytes.rfind("\x89PNG\r\n\x1a\n", 0) == 0) return ".png";
  if (bytes.rfind(std::string("II*\0", 4), 0) == 0 || bytes.rfind(std::string("MM\0*", 4), 0) == 0) return ".tif";
  if (bytes.rfind("\x76\x2f\x31\x01", 0) == 0) return ".exr";
  return "";
}

// "A,B,C,D" as n numbers; empty when it is not.
std::vector<double> numbers(const std::string& list, std::size_t n) {
  std::vector<double> out;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(item, &used));
      if (used != item.size()) return {};
    } catch (const std::exception&) {
      return {};
    }
  }
  return out.size() == n ? out : std::vector<double>{};
}

// The drawn features' extent, [min_x, min_y, max_x, max_y]; empty without coordinates.
std::vector<double> features_extent(const json& doc) {
  double box[4] = {1e300, 1e300, -1e300, -1e300};
  bool any = false;
  std::function<void(const json&)> visit = [&](const json& c) {
    if (c.is_array() && c.size() >= 2 && c[0].is_number() && c[1].is_number()) {
      const double x = c[0].get<double>(), y = c[1].get<double>();
      box[0] = std::min(box[0], x), box[1] = std::min(box[1], y), box[2] = std::max(box[2], x),
      box[3] = std::max(box[3], y);
      any = true;
    } else if (c.is_array()) {
      for (const json& inner : c) visit(inner);
    }
  };
  if (doc.contains("features") && doc["features"].is_array())
    for (const json& f : doc["features"])
      if (f.is_object() && f.contains("geometry") && f["geometry"].is_object() && f["geometry"].contains("coordinates"))
        visit(f["geometry"]["coordinates"]);
  if (!any || box[2] <= box[0] || box[3] <= box[1]) return {};
  return {box[0], box[1], box[2], box[3]};
}

}  // namespace

std::string WorkSketch::text() const {
  std::lock_guard lock(mutex_);
  return fs::is_regular_file(file()) ? read_file(file()) : kEmptySketch;
}

bool WorkSketch::stored() const {
  std::lock_guard lock(mutex_);
  return fs::is_regular_file(file());
}

Sketch WorkSketch::load() const {
  std::lock_guard lock(mutex_);
  if (!fs::is_regular_file(file())) throw UserError("no sketch yet: draw one, or PUT /api/sketch");
  return check(read_file(file()));
}

Sketch WorkSketch::check(const std::string& text) const {
  const json doc = json_for_check(text);
  if (doc.is_object() && doc.contains("exacity") && doc["exacity"].is_object()) {
    const json& ex = doc["exacity"];
    for (const auto& [where, name] : named_files(ex)) {
      std::string why;
      if (!work_.holds(name, why)) throw UserError(file().string() + ": " + where + " " + why);
    }
    if (ex.contains("models") && ex["models"].is_string()) check_library(ex["models"].get<std::string>());
  }
  return parse_sketch(text, file());
}

void WorkSketch::check_library(const std::string& manifest) const {
  const std::string where = file().string() + ": \"exacity\".models ";
  std::string why;
  if (!work_.holds(manifest, why)) throw UserError(where + why);
  // The manifest names OBJ files, and each OBJ its .mtl files: all must be in the work folder
  // too (the model library stage reads them; a file missing here is named there).
  const json doc = json::parse(read_file(work_.root() / manifest), nullptr, false);
  if (!doc.is_object() || !doc.contains("models") || !doc["models"].is_array()) return;
  for (std::size_t i = 0; i < doc["models"].size(); ++i) {
    const json& entry = doc["models"][i];
    if (!entry.is_object() || !entry.contains("file") || !entry["file"].is_string()) continue;
    const fs::path obj = fs::path(manifest).parent_path() / entry["file"].get<std::string>();
    if (!work_.holds(obj, why)) throw UserError(where + manifest + ": models[" + std::to_string(i) + "].file " + why);
    for (const std::string& mtl : material_files(work_.root() / obj)) {
      const fs::path material = obj.parent_path() / mtl;
      if (!work_.holds(material, why)) throw UserError(where + obj.generic_string() + ": mtllib " + why);
      for (const std::string& image : texture_files(work_.root() / material))
        if (!work_.holds(material.parent_path() / image, why))
          throw UserError(where + material.generic_string() + ": map_Kd " + why);
    }
  }
}

Sketch WorkSketch::put(const std::string& text) {
  Sketch sketch = check(text);
  std::lock_guard lock(mutex_);
  write_file(file(), text);
  return sketch;
}

Sketch WorkSketch::put_heightmap(const std::string& bytes, const std::string& bounds, const std::string& height) {
  const std::string extension = image_extension(bytes);
  if (extension.empty())
    throw UserError("the heightmap upload is not a PNG, TIFF or EXR image; save the heightmap in one of those");
  nlohmann::ordered_json doc = nlohmann::ordered_json::parse(text(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) doc = nlohmann::ordered_json::parse(kEmptySketch);
  nlohmann::ordered_json& terrain = doc["exacity"]["terrain"];
  if (!terrain.is_object()) terrain = nlohmann::ordered_json::object();
  std::vector<double> box = numbers(bounds, 4), range = numbers(height, 2);
  if (!bounds.empty() && box.empty())
    throw UserError("?bounds=" + bounds + ": expected MIN_X,MIN_Y,MAX_X,MAX_Y in metres");
  if (!height.empty() && range.empty()) throw UserError("?height=" + height + ": expected LOWEST,HIGHEST in metres");
  if (box.empty() && terrain.contains("bounds")) box = terrain["bounds"].get<std::vector<double>>();
  if (box.empty()) box = features_extent(json::parse(doc.dump()));
  if (box.empty())
    throw UserError("the heightmap needs bounds: draw the city's zones first, or give ?bounds=MIN_X,MIN_Y,MAX_X,MAX_Y");
  if (range.empty())
    range = terrain.contains("height") ? terrain["height"].get<std::vector<double>>() : std::vector<double>{0, 100};
  terrain["heightmap"] = "heightmap" + extension;
  terrain["bounds"] = box;
  terrain["height"] = range;

  // Read as the terrain stage reads it before anything is replaced.
  const fs::path upload = work_.root() / (".heightmap-upload" + extension);
  write_file(upload, bytes);
  const std::string text = doc.dump(1) + "\n";
  Sketch sketch;
  try {
    read_grey_image(upload, "heightmap", "the upload");
    sketch = check(text);
  } catch (...) {
    fs::remove(upload);
    throw;
  }
  std::lock_guard lock(mutex_);
  for (const char* other : {".png", ".tif", ".exr"}) fs::remove(work_.root() / (std::string("heightmap") + other));
  fs::rename(upload, work_.root() / ("heightmap" + extension));
  write_file(file(), text);
  return sketch;
}

namespace {

// Why an uploaded file's name cannot be a path below the library's folder; empty when it
// can.
std::string upload_name_problem(const std::string& name) {
  if (name.empty()) return "has no name";
  if (name.size() > 255) return "is longer than 255 characters";
  const std::string why = name_problem(name);
  return why.empty() ? "" : "has " + why;
}

// Refuses an upload of no files, or one whose file names cannot be paths below `folder` or
// come twice; `what` names the upload, `fix` says what to choose.
void check_upload_names(const std::string& what, const std::vector<std::pair<std::string, std::string>>& files,
                        const std::string& folder, const std::string& fix) {
  if (files.empty()) throw UserError(what + " holds no files; " + fix);
  std::set<std::string> names;
  for (const auto& [name, bytes] : files) {
    if (const std::string why = upload_name_problem(name); !why.empty())
      throw UserError(what + ": the file name \"" + printable(name) + "\" " + why + "; upload files by their paths below " + folder);
    if (!names.insert(name).second) throw UserError(what + ": \"" + name + "\" comes twice; send it once");
  }
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A real place's files (generate --like): the place itself, or a shapefile's companion.
// Formats read by OGR are the ones named here and no other (an OGR VRT, say, could read any
// file on the machine): checked by the driver GDAL picks for the file's bytes.
const std::map<std::string, const char*> kPlaceFormats{
    {".osm", nullptr}, {".pbf", nullptr}, {".geojson", nullptr}, {".json", nullptr},
    {".gpkg", "GPKG"}, {".fgb", "FlatGeobuf"}, {".shp", "ESRI Shapefile"}};
const std::set<std::string> kShapefileCompanions{".shx", ".dbf", ".prj", ".cpg"};
const std::string kPlaceFiles =
    "an OSM extract (.osm, .osm.pbf) or building footprints as .geojson, .gpkg, .fgb or a .shp with its .shx, .dbf and .prj";

}  // namespace

std::string WorkSketch::replace_folder(const std::string& folder,
                                       const std::vector<std::pair<std::string, std::string>>& files,
                                       const std::string& key, const std::string& named,
                                       const std::function<void(const std::string&)>& take) {
  const fs::path root = work_.root(), target = root / folder, incoming = root / ("." + folder + "-upload"),
                 previous = root / ("." + folder + "-previous");
  fs::remove_all(incoming);
  for (const auto& [name, bytes] : files) {
    fs::create_directories((incoming / name).parent_path());
    std::ofstream out(incoming / name, std::ios::binary);
    out << bytes;
    if (!out) throw UserError((incoming / name).string() + ": write failed (disk full?)");
  }
  // Checked where it will stay, so a bad upload's message names its files as a generation
  // would; the folder there before waits aside until the new one is taken.
  fs::remove_all(previous);
  if (fs::exists(target)) fs::rename(target, previous);
  fs::rename(incoming, target);
  nlohmann::ordered_json doc = nlohmann::ordered_json::parse(
      fs::is_regular_file(file()) ? read_file(file()) : std::string(kEmptySketch), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) doc = nlohmann::ordered_json::parse(kEmptySketch);
  doc["exacity"][key] = folder + "/" + named;
  const std::string text = doc.dump(1) + "\n";
  try {
    take(text);
  } catch (...) {
    fs::remove_all(target);
    if (fs::exists(previous)) fs::rename(previous, target);
    throw;
  }
  fs::remove_all(previous);
  write_file(file(), text);
  return text;
}

Sketch WorkSketch::put_library(const std::vector<std::pair<std::string, std::string>>& files) {
  const std::string upload = "the model library upload";
  check_upload_names(upload, files, "the library's folder", "choose the library's .json file with its OBJ and .mtl files");
  std::string manifest;
  for (const auto& [name, bytes] : files) {
    if (fs::path(name).extension() != ".json") continue;
    if (!manifest.empty())
      throw UserError(upload + " has two .json files (\"" + manifest + "\", \"" + name +
                      "\"); upload one library, its manifest the one .json file");
    manifest = name;
  }
  if (manifest.empty())
    throw UserError(upload + " has no .json manifest; choose the library's .json file with its OBJ and .mtl files");
  std::lock_guard lock(mutex_);
  Sketch sketch;
  replace_folder("models", files, "models", manifest, [&](const std::string& text) {
    check_library("models/" + manifest);  // before the library stage reads any file it names
    load_model_library(work_.root() / "models" / manifest);
    sketch = check(text);
  });
  return sketch;
}

Sketch WorkSketch::put_like(const std::vector<std::pair<std::string, std::string>>& files) {
  const std::string upload = "the place upload";
  check_upload_names(upload, files, "the place's folder", "choose " + kPlaceFiles);
  std::string place;
  for (const auto& [name, bytes] : files) {
    const std::string extension = lower(fs::path(name).extension().string());
    if (kShapefileCompanions.count(extension)) continue;
    if (!kPlaceFormats.count(extension))
      throw UserError(upload + ": \"" + name + "\" is not a file of a place exacity serve reads; choose " + kPlaceFiles);
    if (!place.empty())
      throw UserError(upload + " has two places (\"" + place + "\", \"" + name + "\"); upload one, with a shapefile's companions");
    place = name;
  }
  if (place.empty()) throw UserError(upload + " has only a shapefile's companions; choose its .shp file with them");
  std::lock_guard lock(mutex_);
  Sketch sketch;
  replace_folder("like", files, "like", place, [&](const std::string& text) {
    const fs::path stored = work_.root() / "like" / place;
    if (const char* format = kPlaceFormats.at(lower(stored.extension().string()))) {
      GDALAllRegister();
      GDALDriverH driver = GDALIdentifyDriverEx(stored.c_str(), GDAL_OF_VECTOR, nullptr, nullptr);
      if (!driver || std::string(GDALGetDriverShortName(driver)) != format)
        throw UserError(stored.string() + ": not a " + format + " file, as its name says; save it as one");
    }
    sketch = check(text);
    Sketch measured = sketch;
    measured.geojson = text;  // like_place reads the sketch's settings from it, not from the file it replaces
    like_place(measured, sketch.like);
  });
  return sketch;
}

nlohmann::ordered_json WorkSketch::like_measured() const {
  Sketch sketch = load();
  if (sketch.like.empty()) return nullptr;
  const std::string file = sketch.like.lexically_relative(work_.root()).generic_string();
  nlohmann::ordered_json measured = like_place(sketch, sketch.like);  // the sketch then names no place
  measured["file"] = file;
  return measured;
}

std::optional<std::string> WorkSketch::heightmap_preview() const {
  const Sketch sketch = load();
  if (!sketch.terrain) return std::nullopt;
  const GreyImage image = read_grey_image(sketch.terrain->heightmap, "heightmap", "\"exacity\".terrain.heightmap");
  std::vector<unsigned char> pixels(static_cast<std::size_t>(image.width) * image.height * 4);
  unsigned water[3] = {0, 0, 0};
  std::sscanf(kMapWater, "#%2x%2x%2x", &water[0], &water[1], &water[2]);
  for (std::size_t i = 0; i < image.values.size(); ++i) {
    const float v = image.values[i];
    unsigned char* p = &pixels[i * 4];
    for (int c = 0; c < 3; ++c)
      p[c] = v == 0 ? static_cast<unsigned char>(water[c]) : static_cast<unsigned char>(40 + 215 * v);
    p[3] = 255;
  }
  static std::mutex preview_mutex;  // one preview file, written by one request at a time
  std::lock_guard lock(preview_mutex);
  const fs::path preview = work_.root() / ".heightmap-preview.png";
  auto out = OIIO::ImageOutput::create(preview.string());
  if (!out || !out->open(preview.string(), OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::UINT8)) ||
      !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close())
    throw InternalError(preview.string() + ": cannot write the heightmap's preview");
  return read_file(preview);
}

std::string WorkSketch::import_library(const fs::path& manifest) {
  // Into work/models, each file at its place relative to the manifest; one that is not below
  // the manifest's folder has no such place.
  const fs::path from = manifest.parent_path(), to = work_.root() / "models";
  auto bring = [&](const fs::path& relative, const std::string& named_by) {
    const fs::path clean = relative.lexically_normal();
    if (relative.is_absolute() || clean.empty() || *clean.begin() == "..")
      throw UserError(
          named_by + " \"" + relative.generic_string() +
          "\": exacity serve copies a model library's files below its manifest's folder only; move it there");
    std::error_code ec;
    fs::create_directories((to / clean).parent_path(), ec);
    fs::copy_file(from / clean, to / clean, fs::copy_options::overwrite_existing, ec);
    if (ec) throw UserError((from / clean).string() + ": cannot copy into the work folder (" + ec.message() + ")");
  };
  bring(manifest.filename(), manifest.string());
  const json doc = json::parse(read_file(manifest), nullptr, false);
  for (const json& entry :
       doc.is_object() && doc.contains("models") && doc["models"].is_array() ? doc["models"] : json::array())
    if (entry.is_object() && entry.contains("file") && entry["file"].is_string()) {
      const fs::path obj = entry["file"].get<std::string>();
      bring(obj, manifest.string() + ": file");
      for (const std::string& mtl : material_files(from / obj)) {
        const fs::path material = obj.parent_path() / mtl;
        bring(material, (from / obj).string() + ": mtllib");
        for (const std::string& image : texture_files(from / material))
          bring(material.parent_path() / image, (from / material).string() + ": map_Kd");
      }
    }
  return "models/" + manifest.filename().string();
}

void WorkSketch::import(const fs::path& path) {
  const Sketch original = load_sketch(path);
  nlohmann::ordered_json doc =
      nlohmann::ordered_json::parse(original.geojson.empty() ? read_file(path) : original.geojson);
  nlohmann::ordered_json& ex = doc["exacity"];
  // Each named file comes along under a name of its own in the work folder.
  auto bring = [&](const fs::path& from, const std::string& name) {
    std::error_code ec;
    fs::copy_file(from, work_.root() / name, fs::copy_options::overwrite_existing, ec);
    if (ec) throw UserError(from.string() + ": cannot copy into the work folder (" + ec.message() + ")");
    return name;
  };
  if (original.terrain)
    ex["terrain"]["heightmap"] =
        bring(original.terrain->heightmap, "heightmap" + original.terrain->heightmap.extension().string());
  int channel = 0;  // numbered: a channel's name may hold any character
  for (const ChannelSpec& c : original.channels)
    ex["channels"][c.name]["image"] =
        bring(c.image, "channel-" + std::to_string(++channel) + c.image.extension().string());
  if (ex.contains("zones") && ex["zones"].is_object())
    for (auto& [name, zone] : ex["zones"].items())
      if (zone.is_object() && zone.contains("grammar") && zone["grammar"].is_string())
        zone["grammar"] = bring(path.parent_path() / zone["grammar"].get<std::string>(), name + ".grammar");
  if (!original.models.empty()) ex["models"] = import_library(original.models);
  // The real place it looks like into work/like, with a shapefile's companions.
  if (!original.like.empty()) {
    fs::remove_all(work_.root() / "like");
    fs::create_directories(work_.root() / "like");
    const fs::path& place = original.like;
    ex["like"] = bring(place, "like/" + place.filename().string());
    if (lower(place.extension().string()) == ".shp")
      for (const std::string& companion : kShapefileCompanions) {
        const fs::path other = fs::path(place).replace_extension(companion);
        if (fs::exists(other)) bring(other, "like/" + other.filename().string());
      }
  }
  if (ex.is_null()) doc.erase("exacity");
  put(doc.dump(1) + "\n");
}

}  // namespace exacity::serve
