// Loading a sketch (docs/design.md, The sketch, GIS and OSM): a file of any format the
// program reads (GeoJSON, a grid map, a vector file OGR reads, an OSM extract) or several
// read as one, made into a GeoJSON document in metres when it is not one already, then read
// by parse_sketch (sketch.cpp).
#include <algorithm>

#include "generate/errors.h"
#include "generate/gis/osm_tags.h"
#include "generate/gis/projection.h"
#include "generate/gis/sketch_sources.h"
#include "generate/gis/zone_inference.h"
#include "generate/input_file.h"
#include "generate/sketch/grid_map.h"
#include "generate/sketch/sketch.h"
#include "generate/sketch/sketch_document.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

constexpr const char* kSketchFix =
    "give the path of a GeoJSON sketch, a grid map (.grid), a vector file OGR reads or an OSM extract";

void expect_readable(const fs::path& path, SketchSource source) {
  // OGR reads a folder of shapefiles as one sketch.
  if (source == SketchSource::Ogr && fs::is_directory(path)) return;
  expect_input(path, kMaxDataFileBytes, "the sketch", kSketchFix);
}

std::string file_text(const fs::path& path) { return read_input(path, kMaxDataFileBytes, "the sketch", kSketchFix); }

// An OSM extract's or another vector file's features as a GeoJSON document, with its own
// settings beside it (docs/design.md, The sketch, GIS and OSM).
nlohmann::ordered_json gis_document(const fs::path& path, SketchSource source) {
  nlohmann::ordered_json doc = source == SketchSource::Osm ? osm_sketch_document(path) : ogr_sketch_document(path);
  add_settings_beside(doc, path);
  return doc;
}

// Gives OSM-tagged features their zones and roads (generate/gis/osm_tags.h); land use
// that came with OSM's streets is laid out by them, unless the settings say otherwise.
bool apply_osm_tags_and_layout(nlohmann::ordered_json& doc, const std::vector<SketchFile>& files) {
  if (!apply_osm_tags(doc, files)) return false;
  if (doc["features"].empty()) {
    // Each file's counts, named by the file when there are several.
    std::string names, tags;
    for (const nlohmann::ordered_json* file : osm_file_counts(doc["osm"])) {
      const std::string name = (*file)["file"].get<std::string>();
      std::string counts;
      for (const auto& [why, count] : (*file)["skipped"].items()) counts += (counts.empty() ? "" : ", ") + why + " " + count.dump();
      names += (names.empty() ? "" : ", ") + name;
      tags += (tags.empty() ? "" : "; ") + (files.size() > 1 ? name + ": " : "") + (counts.empty() ? "none" : counts);
    }
    throw UserError(names + ": no feature's OpenStreetMap tags make a zone or a road (" + tags +
                    "); see docs/gis.md for the tags Exacity reads");
  }
  if (doc["osm"]["taken"].value("roads", 0) > 0) {
    if (!doc.contains("exacity") || doc["exacity"].is_null()) doc["exacity"] = nlohmann::ordered_json::object();
    default_street_zones(doc["exacity"], {{"layout", "streets"}});
  }
  return true;
}

// Street faces without land use zoned from their mapped buildings, where the settings ask
// (generate/gis/zone_inference.h); whether they did.
bool infer_zones_if_asked(nlohmann::ordered_json& doc) {
  if (!doc.contains("exacity") || !doc["exacity"].is_object() || doc["exacity"].value("infer_zones", nlohmann::ordered_json()) != true)
    return false;
  if (doc.contains("land_use")) return false;  // OUT/sketch.geojson, read again: its zones are inferred already
  infer_zones(doc);
  return true;
}

// Sketches of other formats, several files, and GeoJSON in lon/lat become a document in
// metres first (docs/design.md, The sketch, GIS and OSM); OUT/sketch.geojson keeps it.
Sketch made_sketch(const nlohmann::ordered_json& doc, const fs::path& path, bool read_grammars, const fs::path& models) {
  const std::string made = document_text(doc);
  Sketch sketch = parse_sketch(made, path, read_grammars, models);
  if (sketch.geojson.empty()) sketch.geojson = made;
  return sketch;
}

}  // namespace

nlohmann::ordered_json sketch_document(const fs::path& path) {
  const SketchSource source = sketch_source(path);
  expect_readable(path, source);
  if (source == SketchSource::GridMap)
    throw UserError(path.string() + ": a grid map maps no buildings; give an OSM extract or a file of footprints");
  nlohmann::ordered_json doc;
  if (source == SketchSource::Osm || source == SketchSource::Ogr) {
    doc = gis_document(path, source);
  } else {
    doc = nlohmann::ordered_json::parse(file_text(path), nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("features") || !doc["features"].is_array())
      throw UserError(path.string() + ": not a GeoJSON FeatureCollection; give an OSM extract or a file of footprints");
  }
  project_to_metres(doc, path);
  apply_osm_tags(doc, {{path, doc["features"].size()}});
  return doc;
}

Sketch load_sketch(const fs::path& path, bool read_grammars, const fs::path& models) {
  const SketchSource source = sketch_source(path);
  expect_readable(path, source);
  if (source == SketchSource::Osm || source == SketchSource::Ogr) {
    nlohmann::ordered_json doc = gis_document(path, source);
    project_to_metres(doc, path);
    apply_osm_tags_and_layout(doc, {{path, doc["features"].size()}});
    infer_zones_if_asked(doc);
    return made_sketch(doc, path, read_grammars, models);
  }
  const std::string text = file_text(path);
  // A grid map is read as the sketch of its features; errors in it name its lines.
  if (source == SketchSource::GridMap) return made_sketch(grid_map_sketch(text, path), path, read_grammars, models);
  nlohmann::ordered_json doc = nlohmann::ordered_json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return parse_sketch(text, path, read_grammars, models);  // it says what is wrong
  // The settings first: their terrain and channel bounds are in the sketch's CRS too.
  const bool beside = add_settings_beside(doc, path);
  const bool projected = project_to_metres(doc, path);
  const bool tagged = doc.contains("features") && doc["features"].is_array() &&
                      apply_osm_tags_and_layout(doc, {{path, doc["features"].size()}});
  const bool inferred = infer_zones_if_asked(doc);
  if (!projected && !beside && !tagged && !inferred) return parse_sketch(text, path, read_grammars, models);
  return made_sketch(doc, path, read_grammars, models);
}

Sketch load_sketch(const std::vector<fs::path>& paths, bool read_grammars, const fs::path& models,
                   const std::vector<fs::path>& footprints) {
  if (paths.empty()) throw UserError("no sketch given; give a GeoJSON sketch, a grid map, a vector file or an OSM extract");
  if (paths.size() == 1 && footprints.empty()) return load_sketch(paths[0], read_grammars, models);
  std::vector<SketchPart> parts;
  for (const fs::path& path : footprints) {
    // Read as the sketch's files are, after them: a folder of shapefiles, or any one file.
    if (!fs::is_directory(path)) expect_input(path, kMaxDataFileBytes, "the building footprints", "give a vector file of footprint polygons");
  }
  for (std::size_t k = 0; k < paths.size() + footprints.size(); ++k) {
    const bool footprint = k >= paths.size();
    const fs::path& path = footprint ? footprints[k - paths.size()] : paths[k];
    if (footprint) {
      parts.push_back({footprint_document(path), path});
      continue;
    }
    const SketchSource source = sketch_source(path);
    expect_readable(path, source);
    if (source == SketchSource::GridMap)
      throw UserError(path.string() + ": a grid map is a whole sketch and cannot be given with others; give it alone, "
                      "or name it in a sketch's \"exacity\".grid");
    nlohmann::ordered_json part;
    if (source == SketchSource::GeoJson) {
      const std::string text = file_text(path);
      part = nlohmann::ordered_json::parse(text, nullptr, false);
      if (part.is_discarded() || !part.is_object() || !part.contains("features") || !part["features"].is_array()) {
        parse_sketch(text, path, false);  // says what is wrong with it
        throw UserError(path.string() + ": not a GeoJSON FeatureCollection; give one");
      }
      add_settings_beside(part, path);
    } else {
      part = gis_document(path, source);
    }
    // Every feature is named by its own file in messages.
    for (std::size_t i = 0; i < part["features"].size(); ++i) {
      nlohmann::ordered_json& f = part["features"][i];
      if (f.is_object() && f.contains("properties") && f["properties"].is_object() && !f["properties"].contains("source"))
        f["properties"]["source"] = path.string() + " features[" + std::to_string(i) + "]";
    }
    parts.push_back({std::move(part), path});
  }
  // Each file from its own CRS to the one they share.
  const nlohmann::ordered_json crs = project_to_metres(parts);
  nlohmann::ordered_json doc = {{"type", "FeatureCollection"}, {"features", nlohmann::ordered_json::array()}};
  if (!crs.is_null()) doc["crs"] = crs;
  fs::path settings_from;
  std::vector<SketchFile> files;
  for (SketchPart& p : parts) {
    nlohmann::ordered_json& part = p.doc;
    if (part.contains("exacity")) {
      if (doc.contains("exacity"))
        throw UserError(p.path.string() + ": has settings, and so has " + settings_from.string() +
                        "; sketches given together take their settings from one of them");
      doc["exacity"] = std::move(part["exacity"]), settings_from = p.path;
    }
    files.push_back({p.path, part["features"].size()});
    for (nlohmann::ordered_json& f : part["features"]) doc["features"].push_back(std::move(f));
  }
  // An extract's own counts (what reading it left out and mended) stay with its file.
  if (std::any_of(parts.begin(), parts.end(), [](const SketchPart& p) { return p.doc.contains("osm"); })) {
    doc["osm"]["files"] = nlohmann::ordered_json::array();
    for (SketchPart& p : parts) {
      nlohmann::ordered_json counts = {{"file", p.path.string()}};
      if (p.doc.contains("osm") && p.doc["osm"].is_object())
        for (auto& [key, value] : p.doc["osm"].items())
          if (key != "file") counts[key] = std::move(value);
      doc["osm"]["files"].push_back(std::move(counts));
    }
  }
  apply_osm_tags_and_layout(doc, files);
  infer_zones_if_asked(doc);
  return made_sketch(doc, paths[0], read_grammars, models);
}

}  // namespace exacity
