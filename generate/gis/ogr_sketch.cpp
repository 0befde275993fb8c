#include <algorithm>
#include <cctype>
#include <functional>
#include <map>
#include <memory>

#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "generate/errors.h"
#include "generate/input_file.h"
#include "generate/gis/osm_tags.h"
#include "generate/gis/projection.h"
#include "generate/gis/sketch_sources.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// The EPSG code of a layer's CRS, if PROJ can name one.
std::optional<int> epsg_of(const OGRSpatialReference& srs) {
  OGRSpatialReference copy(srs);
  const char* code = copy.GetAuthorityCode(nullptr);
  if (!code && copy.AutoIdentifyEPSG() == OGRERR_NONE) code = copy.GetAuthorityCode(nullptr);
  const char* authority = copy.GetAuthorityName(nullptr);
  if (!code || !authority || lower(authority) != "epsg") return std::nullopt;
  return std::atoi(code);
}

// Text as UTF-8: not UTF-8 (an old shapefile's Latin-1 names, a layer named in Latin-1, or a
// stray byte), it is read as Latin-1, so that every name is text the sketch's JSON and the
// messages can hold.
std::string utf8(const char* text) {
  if (CPLIsUTF8(text, -1)) return text;
  char* recoded = CPLRecode(text, CPL_ENC_ISO8859_1, CPL_ENC_UTF8);
  std::string out(recoded);
  CPLFree(recoded);
  return out;
}

// A field's value as JSON, or null when the feature has no such field or it is unset.
ordered_json field(OGRFeature& f, const char* name) {
  const int i = f.GetFieldIndex(name);
  if (i < 0 || !f.IsFieldSetAndNotNull(i)) return nullptr;
  switch (f.GetFieldDefnRef(i)->GetType()) {
    case OFTInteger:
    case OFTInteger64: return f.GetFieldAsInteger64(i);
    case OFTReal: return f.GetFieldAsDouble(i);
    default: return utf8(f.GetFieldAsString(i));
  }
}

// A polygon of a layer whose features' order decides which covers which where they overlap.
struct Cover {
  std::unique_ptr<OGRGeometry> geometry;
  OGREnvelope box;
  std::string source;
};

// A FlatGeobuf written with its spatial index (GDAL's default) holds its features in the
// index's order, not the order they were drawn in; where zones overlap, the later one covers
// the earlier, so that order is lost. Refused where it would matter: two zones overlapping.
void expect_order_kept(std::vector<Cover>& covers, const std::string& where) {
  std::sort(covers.begin(), covers.end(), [](const Cover& a, const Cover& b) { return a.box.MinX < b.box.MinX; });
  for (std::size_t i = 0; i < covers.size(); ++i)
    for (std::size_t j = i + 1; j < covers.size() && covers[j].box.MinX <= covers[i].box.MaxX; ++j) {
      if (!covers[i].box.Intersects(covers[j].box) || !covers[i].geometry->Intersects(covers[j].geometry.get())) continue;
      std::unique_ptr<OGRGeometry> common(covers[i].geometry->Intersection(covers[j].geometry.get()));
      if (common && !common->IsEmpty() && common->getDimension() == 2)
        throw UserError(where + ": " + covers[i].source.substr(where.size() + 1) + " and " +
                        covers[j].source.substr(where.size() + 1) +
                        " overlap, and this FlatGeobuf keeps its features in its spatial index's order, not the order "
                        "they were drawn in, so which covers the other is unknown; write it without the index "
                        "(ogr2ogr -lco SPATIAL_INDEX=NO) or as a GeoPackage");
    }
}

}  // namespace

SketchSource sketch_source(const fs::path& path) {
  const std::string ext = lower(path.extension().string());
  if (ext == ".geojson" || ext == ".json") return SketchSource::GeoJson;
  if (ext == ".grid") return SketchSource::GridMap;
  if (ext == ".osm" || ext == ".pbf") return SketchSource::Osm;
  return SketchSource::Ogr;
}

fs::path settings_beside(const fs::path& path) {
  fs::path stem = path.stem();
  if (lower(path.extension().string()) == ".pbf" && lower(stem.extension().string()) == ".osm") stem = stem.stem();
  return path.parent_path() / (stem.string() + ".exacity.json");
}

bool add_settings_beside(ordered_json& doc, const fs::path& path) {
  const fs::path file = settings_beside(path);
  if (!fs::is_regular_file(file)) return false;
  if (doc.contains("exacity"))
    throw UserError(file.string() + ": the sketch " + path.filename().string() +
                    " has settings of its own (\"exacity\"); keep one of the two");
  ordered_json settings =
      ordered_json::parse(read_input(file, kMaxSettingsFileBytes, "the settings", "write them as a JSON object"), nullptr, false);
  if (settings.is_discarded() || !settings.is_object())
    throw UserError(file.string() + ": not a JSON object of settings; write it as the \"exacity\" member of a sketch is written");
  doc["exacity"] = std::move(settings);
  return true;
}

namespace {

GDALDatasetUniquePtr open_vector(const fs::path& path) {
  start_gdal();
  CPLErrorReset();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!ds)
    throw UserError(path.string() + ": OGR cannot read it as a vector file (" +
                    (CPLGetLastErrorMsg()[0] ? std::string(CPLGetLastErrorMsg()) : "no driver recognises it") +
                    "); give GeoJSON, GeoPackage, Shapefile, KML, FlatGeobuf, GML or an OSM extract");
  return ds;
}

// Every feature of every layer with a geometry, with its geometry as GeoJSON (2D, linear, in
// the first such layer's CRS, which becomes the document's crs): `layer_read` says whether a
// layer is read (and refuses one that cannot be), `feature_read` adds a feature to `doc`.
void read_features(GDALDataset& ds, const fs::path& path, ordered_json& doc,
                   const std::function<void(OGRLayer&, const std::string& where)>& layer_read,
                   const std::function<void(OGRFeature&, const std::string& source, ordered_json geometry)>& feature_read) {
  std::unique_ptr<OGRSpatialReference> crs;  // the first spatial layer's; the others are brought to it
  for (OGRLayer* layer : ds.GetLayers()) {
    if (layer->GetGeomType() == wkbNone) continue;  // a table without geometry (QGIS's styles, say)
    const std::string where = path.string() + " layer " + utf8(layer->GetName());
    layer_read(*layer, where);
    std::unique_ptr<OGRCoordinateTransformation> to_crs;
    if (const OGRSpatialReference* srs = layer->GetSpatialRef()) {
      if (!crs) {
        crs = std::make_unique<OGRSpatialReference>(*srs);
        crs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        const std::optional<int> epsg = epsg_of(*crs);
        if (!epsg)
          throw UserError(where + ": its CRS (" + (crs->GetName() ? utf8(crs->GetName()) : "unnamed") +
                          ") has no EPSG code; reproject the file to an EPSG CRS, e.g. ogr2ogr -t_srs EPSG:<code>");
        doc["crs"] = crs_member(*epsg);
      } else if (!srs->IsSame(crs.get())) {
        OGRSpatialReference from(*srs);
        from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        to_crs.reset(OGRCreateCoordinateTransformation(&from, crs.get()));
        if (!to_crs) throw UserError(where + ": PROJ cannot bring its CRS to the first layer's; reproject it");
      }
    }
    const bool order_lost = lower(ds.GetDriverName()) == "flatgeobuf" && layer->TestCapability(OLCFastSpatialFilter);
    std::vector<Cover> covers;
    layer->ResetReading();
    for (OGRFeatureUniquePtr f(layer->GetNextFeature()); f; f.reset(layer->GetNextFeature())) {
      const std::string source = where + " feature " + std::to_string(f->GetFID());
      ordered_json geometry = nullptr;
      if (const OGRGeometry* g = f->GetGeometryRef()) {
        std::unique_ptr<OGRGeometry> linear(g->hasCurveGeometry() ? g->getLinearGeometry() : g->clone());
        linear->flattenTo2D();
        if (to_crs && linear->transform(to_crs.get()) != OGRERR_NONE)
          throw UserError(source + ": could not be brought to the first layer's CRS; check its coordinates");
        char* text = linear->exportToJson();
        geometry = ordered_json::parse(text ? text : "null", nullptr, false);
        CPLFree(text);
        // Only a file that lost its order pays for the fields' look-ups.
        if (order_lost && linear->getDimension() == 2 && field(*f, "road").is_null() && field(*f, "building").is_null() &&
            field(*f, "building:part").is_null()) {
          Cover& c = covers.emplace_back(Cover{std::move(linear), {}, source});
          c.geometry->getEnvelope(&c.box);
        }
      }
      feature_read(*f, source, std::move(geometry));
    }
    expect_order_kept(covers, where);
  }
}

// A field's value by the first of `names` the layer has (any case), or null.
ordered_json first_field(OGRFeature& f, std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (ordered_json v = field(f, name); !v.is_null()) return v;
  return nullptr;
}

// BAG's statuses of a building not standing (planned, being built, demolished, registered
// in error); the others ("Pand in gebruik", "Verbouwing pand" ...) stand.
bool not_standing(const std::string& status) {
  for (const char* s : {"Bouwvergunning verleend", "Bouw gestart", "Niet gerealiseerd pand", "Pand gesloopt",
                        "Pand ten onrechte opgevoerd"})
    if (status == s) return true;
  return false;
}

}  // namespace

ordered_json ogr_sketch_document(const fs::path& path) {
  GDALDatasetUniquePtr ds = open_vector(path);
  ordered_json doc = {{"type", "FeatureCollection"}, {"features", ordered_json::array()}};
  auto layer_read = [](OGRLayer& layer, const std::string& where) {
    OGRFeatureDefn* defn = layer.GetLayerDefn();
    const bool osm_tagged = std::any_of(osm_keys().begin(), osm_keys().end(),
                                        [&](const std::string& key) { return defn->GetFieldIndex(key.c_str()) >= 0; });
    if (defn->GetFieldIndex("zone") < 0 && defn->GetFieldIndex("road") < 0 && !osm_tagged)
      throw UserError(where + ": has neither a \"zone\" nor a \"road\" field, nor OpenStreetMap's landuse or highway; add "
                      "one (zones: residential, commercial, industrial, park, water; roads: highway, main, local), give "
                      "a layer of building footprints with --buildings FILE, or remove the layer");
  };
  read_features(*ds, path, doc, layer_read, [&](OGRFeature& f, const std::string& source, ordered_json geometry) {
    ordered_json properties = ordered_json::object();
    for (const char* name : {"zone", "road", "width", "name"})
      if (ordered_json v = field(f, name); !v.is_null()) properties[name] = std::move(v);
    for (const std::string& key : osm_keys())
      if (ordered_json v = field(f, key.c_str()); !v.is_null() && !properties.contains(key)) properties[key] = std::move(v);
    properties["source"] = source;
    doc["features"].push_back({{"type", "Feature"}, {"properties", std::move(properties)}, {"geometry", std::move(geometry)}});
  });
  return doc;
}

ordered_json footprint_document(const fs::path& path) {
  GDALDatasetUniquePtr ds = open_vector(path);
  ordered_json doc = {{"type", "FeatureCollection"}, {"features", ordered_json::array()}};
  std::map<std::string, int> refused;
  ordered_json named = ordered_json::array();  // the first few refused, as report.json names the placement's
  auto refuse = [&](const std::string& source, const std::string& why) {
    if (named.size() < 20) named.push_back(source + ": refused, " + why);
    ++refused[why];
  };
  auto layer_read = [](OGRLayer& layer, const std::string& where) {
    const OGRwkbGeometryType type = wkbFlatten(layer.GetGeomType());
    if (type != wkbUnknown && type != wkbPolygon && type != wkbMultiPolygon && type != wkbCurvePolygon &&
        type != wkbMultiSurface && type != wkbGeometryCollection)
      throw UserError(where + ": holds " + lower(OGRGeometryTypeToName(type)) + "s, not building footprints; give "
                      "--buildings a file of polygons, or draw the footprints");
  };
  read_features(*ds, path, doc, layer_read, [&](OGRFeature& f, const std::string& source, ordered_json geometry) {
    const std::string type = geometry.is_object() ? geometry.value("type", "") : "";
    if (type != "Polygon" && type != "MultiPolygon") return refuse(source, "buildings that are not polygons");
    const ordered_json status = field(f, "status");
    if (status.is_string() && not_standing(status.get<std::string>()))
      return refuse(source, "buildings not standing (BAG's status " + status.get<std::string>() + ")");
    ordered_json building = field(f, "building");
    ordered_json p{{"building", building.is_string() && !building.get<std::string>().empty() ? building : ordered_json("yes")}};
    // Heights as OSM tags them, as Overture and Microsoft's footprints name them, and BAG 3D's
    // roof height above the ground.
    ordered_json height = first_field(f, {"height", "hoogte"});
    if (height.is_number() && height.get<double>() <= 0) height = nullptr;  // Microsoft's -1: not measured
    const ordered_json roof = first_field(f, {"b3_h_dak_70p", "h_dak_70p"}), ground = first_field(f, {"b3_h_maaiveld", "h_maaiveld"});
    if (height.is_null() && roof.is_number() && ground.is_number()) height = roof.get<double>() - ground.get<double>();
    if (!height.is_null()) p["height"] = height;
    if (ordered_json v = first_field(f, {"building:levels", "levels", "num_floors", "floors", "storeys", "stories",
                                         "b3_bouwlagen", "bouwlagen", "aantal_bouwlagen"});
        !v.is_null())
      p["building:levels"] = v;
    if (ordered_json v = first_field(f, {"roof:shape", "roof_shape"}); !v.is_null()) p["roof:shape"] = v;
    if (ordered_json v = first_field(f, {"roof:height", "roof_height"}); !v.is_null()) p["roof:height"] = v;
    if (ordered_json v = first_field(f, {"name"}); !v.is_null()) p["name"] = v;
    // Its identifier in its source, which every export keeps: BAG's, else the layer's FID.
    if (ordered_json id = field(f, "identificatie"); id.is_string() && !id.get<std::string>().empty()) p["identificatie"] = id;
    else if (id.is_number_integer()) p["identificatie"] = id.dump();
    else if (f.GetFID() != OGRNullFID) p["fid"] = f.GetFID();
    p["source"] = source;
    doc["features"].push_back({{"type", "Feature"}, {"properties", std::move(p)}, {"geometry", std::move(geometry)}});
  });
  // What was refused is counted as an extract's left-out buildings are (report.json's
  // mapped_buildings).
  ordered_json skipped = ordered_json::object();
  for (const auto& [why, n] : refused) skipped[why] = n;
  doc["osm"] = {{"file", path.string()}, {"skipped", skipped}, {"buildings_named", std::move(named)}};
  if (doc["features"].empty())
    throw UserError(path.string() + ": has no building footprints (polygons) to keep" +
                    (refused.empty() ? std::string() : " (" + std::to_string(refused.begin()->second) + " " + refused.begin()->first + ")") +
                    "; give --buildings a file of footprint polygons");
  return doc;
}

}  // namespace exacity
