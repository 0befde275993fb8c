#include "generate/export/gis_export.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <set>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <osmium/builder/osm_object_builder.hpp>
#include <osmium/io/any_output.hpp>
#include <osmium/memory/buffer.hpp>

#include "generate/errors.h"
#include "generate/export/geojson.h"
#include "generate/gis/projection.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
  throw UserError(file.string() + ": " + what + " (" + CPLGetLastErrorMsg() + "); check the disk and the folder's permissions");
}

GDALDatasetUniquePtr create(const char* driver_name, const fs::path& file) {
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  if (!driver) fail(file, std::string("GDAL has no ") + driver_name + " driver");
  GDALDatasetUniquePtr ds(driver->Create(file.string().c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!ds) fail(file, "cannot be created");
  return ds;
}

// A field of a layer in the formats OGR writes, as GDAL's GeoJSON reader would type it from
// the layer's file (so a GeoPackage of the layers is the one ogr2ogr makes of the GeoJSON):
// in the order the features first name it; integers (64-bit when one does not fit in 32),
// reals once any value is one, booleans, strings; lists and objects as their JSON text (no
// format here stores lists); a field that is null everywhere a string.
struct LayerField {
  std::string name;
  OGRFieldType type = OFTString;
  OGRFieldSubType subtype = OFSTNone;
  bool known = false;  // a value other than null seen
};

OGRFieldType ogr_type(const nlohmann::ordered_json& v, OGRFieldSubType& subtype) {
  subtype = OFSTNone;
  if (v.is_boolean()) return subtype = OFSTBoolean, OFTInteger;
  if (v.is_number_integer()) {
    const bool fits = v.is_number_unsigned() ? v.get<std::uint64_t>() <= INT32_MAX
                                             : v.get<std::int64_t>() >= INT32_MIN && v.get<std::int64_t>() <= INT32_MAX;
    return fits ? OFTInteger : OFTInteger64;
  }
  if (v.is_number_float()) return OFTReal;
  if (v.is_array() || v.is_object()) subtype = OFSTJSON;
  return OFTString;
}

// A field that met `v`: its type widened as the GeoJSON reader widens it.
void widen(LayerField& field, const nlohmann::ordered_json& v) {
  if (v.is_null()) return;
  OGRFieldSubType subtype;
  const OGRFieldType type = ogr_type(v, subtype);
  if (!field.known) {
    field.type = type, field.subtype = subtype, field.known = true;
    return;
  }
  if (field.type == type && field.subtype == subtype) return;
  const bool numbers = (field.type == OFTInteger || field.type == OFTInteger64 || field.type == OFTReal) &&
                       (type == OFTInteger || type == OFTInteger64 || type == OFTReal);
  if (numbers) {
    field.type = field.type == OFTReal || type == OFTReal ? OFTReal : OFTInteger64;
    field.subtype = OFSTNone;
  } else if (field.type == OFTInteger && type == OFTInteger) {
    field.subtype = OFSTNone;  // booleans and integers
  } else if (field.type != OFTString) {
    field.type = OFTString, field.subtype = OFSTNone;
  }
}

// The fields of a layer, from the properties its features write, in the GeoJSON reader's
// order: a field comes after every field some feature names just before it (where that
// makes no cycle with the orders met earlier), and of fields free to come next, the least
// by name first (Kahn's topological sort).
std::vector<LayerField> layer_fields(const Layer& layer) {
  std::vector<LayerField> fields;
  std::map<std::string, std::size_t> index;
  std::vector<std::set<std::size_t>> after;  // after[i]: the fields some feature names right after i
  auto reaches = [&](std::size_t from, std::size_t to) {
    std::vector<std::size_t> stack{from};
    std::set<std::size_t> seen{from};
    while (!stack.empty()) {
      const std::size_t n = stack.back();
      stack.pop_back();
      if (n == to) return true;
      for (std::size_t next : after[n])
        if (seen.insert(next).second) stack.push_back(next);
    }
    return false;
  };
  for (const VectorFeature& f : layer.features) {
    std::optional<std::size_t> previous;
    for (const auto& [key, value] : f.properties.items()) {
      auto [it, added] = index.try_emplace(key, fields.size());
      if (added) fields.push_back({key}), after.emplace_back();
      const std::size_t i = it->second;
      widen(fields[i], value);
      if (previous && *previous != i && !after[*previous].count(i) && !reaches(i, *previous)) after[*previous].insert(i);
      previous = i;
    }
  }
  std::vector<int> before(fields.size(), 0);
  for (const std::set<std::size_t>& next : after)
    for (std::size_t j : next) ++before[j];
  auto by_name = [&](std::size_t a, std::size_t b) { return fields[a].name < fields[b].name; };
  std::set<std::size_t, decltype(by_name)> ready(by_name);
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (!before[i]) ready.insert(i);
  std::vector<LayerField> sorted;
  while (!ready.empty()) {
    const std::size_t n = *ready.begin();
    ready.erase(ready.begin());
    sorted.push_back(fields[n]);
    for (std::size_t j : after[n])
      if (!--before[j]) ready.insert(j);
  }
  return sorted;
}

// A layer's geometry type; an empty layer's too (a format whose layer has none shows it as
// lines or "Unknown", and QGIS then offers the wrong symbols and refuses to append polygons).
OGRwkbGeometryType geometry_type(const Layer& layer) {
  if (layer.name == "clutter") return wkbPoint;
  return layer.lines ? wkbLineString : wkbPolygon;
}

std::unique_ptr<OGRGeometry> geometry(const Layer& layer, const VectorFeature& f) {
  auto points = [](OGRSimpleCurve& curve, const std::vector<geom::Vec2>& ps, bool closed) {
    curve.setNumPoints(static_cast<int>(ps.size() + closed), false);
    // + 0.0: a -0 as the GeoJSON file writes it (0).
    for (std::size_t i = 0; i < ps.size(); ++i) curve.setPoint(static_cast<int>(i), ps[i].x + 0.0, ps[i].y + 0.0);
    if (closed) curve.setPoint(static_cast<int>(ps.size()), ps.front().x + 0.0, ps.front().y + 0.0);
  };
  switch (geometry_type(layer)) {
    case wkbPoint: return std::make_unique<OGRPoint>(f.line.at(0).x + 0.0, f.line.at(0).y + 0.0);
    case wkbLineString: {
      auto line = std::make_unique<OGRLineString>();
      points(*line, f.line, false);
      return line;
    }
    default: {
      auto polygon = std::make_unique<OGRPolygon>();
      for (const geom::Ring* ring : [&] {
             std::vector<const geom::Ring*> rings{&f.polygon.outer};
             for (const geom::Ring& h : f.polygon.holes) rings.push_back(&h);
             return rings;
           }()) {
        auto r = std::make_unique<OGRLinearRing>();
        points(*r, *ring, true);
        polygon->addRingDirectly(r.release());
      }
      return polygon;
    }
  }
}

// JSON text as json-c writes it (JSON_C_TO_STRING_SPACED), which GDAL's GeoJSON reader
// gives a string field holding a list or an object: "[ 1, 2 ]", "{ "a": 0.5 }", doubles
// to 17 significant digits, '/' escaped.
void json_c_text(const nlohmann::ordered_json& v, std::string& out) {
  switch (v.type()) {
    case nlohmann::json::value_t::null: out += "null"; return;
    case nlohmann::json::value_t::boolean: out += v.get<bool>() ? "true" : "false"; return;
    case nlohmann::json::value_t::number_integer: out += std::to_string(v.get<std::int64_t>()); return;
    case nlohmann::json::value_t::number_unsigned: out += std::to_string(v.get<std::uint64_t>()); return;
    case nlohmann::json::value_t::number_float: {
      char text[40];
      std::snprintf(text, sizeof text, "%.17g", v.get<double>());
      out += text;
      if (!std::strpbrk(text, ".e") && (std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '-')) out += ".0";
      return;
    }
    case nlohmann::json::value_t::string: {
      out += '"';
      for (const char c : v.get_ref<const std::string&>()) {
        switch (c) {
          case '"': out += "\\\""; break;
          case '\\': out += "\\\\"; break;
          case '/': out += "\\/"; break;
          case '\b': out += "\\b"; break;
          case '\f': out += "\\f"; break;
          case '\n': out += "\\n"; break;
          case '\r': out += "\\r"; break;
          case '\t': out += "\\t"; break;
          default:
            if (static_cast<unsigned char>(c) < 0x20) {
              char u[8];
              std::snprintf(u, sizeof u, "\\u%04x", c);
              out += u;
            } else {
              out += c;
            }
        }
      }
      out += '"';
      return;
    }
    case nlohmann::json::value_t::array: {
      out += '[';
      bool first = true;
      for (const auto& e : v) out += first ? " " : ", ", json_c_text(e, out), first = false;
      out += " ]";
      return;
    }
    case nlohmann::json::value_t::object: {
      out += '{';
      bool first = true;
      for (const auto& [key, e] : v.items()) {
        out += first ? " " : ", ";
        json_c_text(key, out);
        out += ": ";
        json_c_text(e, out);
        first = false;
      }
      out += " }";
      return;
    }
    default: out += v.dump();
  }
}

// A value in a string field: a string as it is, else its JSON text.
std::string string_value(const nlohmann::ordered_json& v) {
  if (v.is_string()) return v.get<std::string>();
  std::string out;
  json_c_text(v, out);
  return out;
}

// Writes each layer into `target`, one layer each (GeoPackage, FlatGeobuf and Shapefile
// keep geometry and attributes; CRS set from the sketch's).
void copy_layers(const std::vector<const Layer*>& layers, GDALDataset& target, OGRSpatialReference* srs,
                 const fs::path& file, CSLConstList layer_options = nullptr) {
  // One transaction where the format has them (GeoPackage): a feature each is far slower.
  const bool transaction = target.StartTransaction() == OGRERR_NONE;
  for (const Layer* layer : layers) {
    const std::string& name = layer->name;
    const std::vector<LayerField> fields = layer_fields(*layer);
    // A GeoPackage's key column is "fid" unless told otherwise, and the buildings layer has a
    // field of that name (a mapped footprint's FID in its own file, a string or any number):
    // the key column is named apart then.
    CPLStringList options(layer_options);
    if (EQUAL(target.GetDriverName(), "GPKG") &&
        std::any_of(fields.begin(), fields.end(), [](const LayerField& f) { return EQUAL(f.name.c_str(), "fid"); }))
      options.SetNameValue("FID", "gpkg_fid");
    OGRLayer* to = target.CreateLayer(name.c_str(), srs, geometry_type(*layer), options.List());
    if (!to) fail(file, "cannot hold layer " + name);
    for (const LayerField& f : fields) {
      OGRFieldDefn field(f.name.c_str(), f.type);
      field.SetSubType(f.subtype);
      if (f.subtype == OFSTBoolean) field.SetWidth(1);  // as the GeoJSON reader gives a boolean
      if (to->CreateField(&field) != OGRERR_NONE) fail(file, "cannot hold field " + f.name);
    }
    for (const VectorFeature& f : layer->features) {
      OGRFeatureUniquePtr feature(OGRFeature::CreateFeature(to->GetLayerDefn()));
      feature->SetGeometryDirectly(geometry(*layer, f).release());
      int i = 0;
      for (const LayerField& field : fields) {
        const int at = i++;
        const auto v = f.properties.find(field.name);
        if (v == f.properties.end() || v->is_null()) continue;
        if (field.type == OFTString) feature->SetField(at, string_value(*v).c_str());
        else if (field.type == OFTReal) feature->SetField(at, v->get<double>());
        else if (v->is_boolean()) feature->SetField(at, v->get<bool>() ? 1 : 0);
        else feature->SetField(at, static_cast<GIntBig>(v->get<std::int64_t>()));
      }
      if (to->CreateFeature(feature.get()) != OGRERR_NONE) fail(file, "cannot take a feature of layer " + name);
    }
  }
  if (transaction && target.CommitTransaction() != OGRERR_NONE) fail(file, "cannot be written");
}

// A DXF file's entities carry their CAD layer in the "Layer" field.
void write_dxf(const std::vector<const Layer*>& layers, const fs::path& file) {
  GDALDatasetUniquePtr ds = create("DXF", file);
  OGRLayer* entities = ds->CreateLayer("entities", nullptr, wkbUnknown, nullptr);
  if (!entities) fail(file, "cannot hold entities");
  for (const Layer* layer : layers)
    for (const VectorFeature& f : layer->features) {
      OGRFeatureUniquePtr entity(OGRFeature::CreateFeature(entities->GetLayerDefn()));
      entity->SetField("Layer", layer->name.c_str());
      entity->SetGeometryDirectly(geometry(*layer, f).release());
      if (entities->CreateFeature(entity.get()) != OGRERR_NONE) fail(file, "cannot take an entity");
    }
}

}  // namespace

std::vector<const Layer*> vector_files(const CityLayers& city, const Layer& clutter) {
  std::vector<const Layer*> layers{&city.zones,  &city.water, &city.roads,     &city.road_areas,
                                   &city.blocks, &city.lots,  &city.buildings, &clutter};
  std::sort(layers.begin(), layers.end(), [](const Layer* a, const Layer* b) { return a->name < b->name; });
  return layers;
}

void write_vector_formats(const std::vector<const Layer*>& layers, const fs::path& dir,
                          const std::vector<std::string>& formats, const nlohmann::ordered_json& crs) {
  if (std::all_of(formats.begin(), formats.end(), [](const std::string& f) { return f == "geojson"; })) return;
  start_gdal();
  // Same sketch, same bytes (docs/design.md, Determinism): GeoPackage stamps its tables and
  // DBF its header with the date of writing, unless told which.
  const CPLConfigOptionSetter date("OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z", false);
  const char* const dbf_date[] = {"DBF_DATE_LAST_UPDATE=2000-01-01", nullptr};
  std::unique_ptr<OGRSpatialReference> srs;
  if (const std::optional<int> epsg = epsg_of(crs)) {
    srs = std::make_unique<OGRSpatialReference>();
    if (srs->importFromEPSG(*epsg) != OGRERR_NONE) srs.reset();
    else srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  }
  for (const std::string& format : formats) {
    if (format == "gpkg") {
      GDALDatasetUniquePtr ds = create("GPKG", dir / "city.gpkg");
      copy_layers(layers, *ds, srs.get(), dir / "city.gpkg");
    } else if (format == "fgb") {
      fs::create_directories(dir / "vector");
      for (const Layer* layer : layers) {
        const fs::path file = dir / "vector" / (layer->name + ".fgb");
        GDALDatasetUniquePtr ds = create("FlatGeobuf", file);
        copy_layers({layer}, *ds, srs.get(), file);
      }
    } else if (format == "shp") {
      fs::create_directories(dir / "vector" / "shp");
      GDALDatasetUniquePtr ds = create("ESRI Shapefile", dir / "vector" / "shp");
      copy_layers(layers, *ds, srs.get(), dir / "vector" / "shp", dbf_date);
    } else if (format == "dxf") {
      write_dxf(layers, dir / "city.dxf");
    }
  }
}

namespace {

using OsmTagList = std::vector<std::pair<std::string, std::string>>;

// Nodes by their position as written, so centre lines meeting at a vertex share one; each
// node's index, from 0, in the order first met.
class OsmNodes {
 public:
  std::size_t at(geom::Vec2 p) {
    auto [it, added] = index_.try_emplace({p.x, p.y}, order_.size());
    if (added) order_.push_back(p);
    return it->second;
  }
  const std::vector<geom::Vec2>& positions() const { return order_; }

 private:
  std::map<std::pair<double, double>, std::size_t> index_;
  std::vector<geom::Vec2> order_;
};

struct OsmWay {
  std::vector<std::size_t> nodes;  // indices into OsmNodes
  OsmTagList tags;
};

// A building with courtyards: a multipolygon relation of its rings' ways.
struct OsmMultipolygon {
  std::vector<std::pair<std::size_t, const char*>> members;  // indices into the ways, and their roles
  OsmTagList tags;
};

std::string osm_number(double v) { return format_number(std::round(v * 100) / 100); }

std::pair<const char*, const char*> osm_clutter_tag(ModelKind kind) {
  switch (kind) {
    case ModelKind::Lamp: return {"highway", "street_lamp"};
    case ModelKind::TrafficLight: return {"highway", "traffic_signals"};
    case ModelKind::Sign: return {"highway", "stop"};
    case ModelKind::Bench: return {"amenity", "bench"};
    case ModelKind::Hydrant: return {"emergency", "fire_hydrant"};
    default: return {"natural", "tree"};
  }
}

// The highway tag a mapper would give a road Exacity laid out (or one drawn without OSM
// tags): its roads meet at level junctions and carry sidewalks, so none is a motorway; a
// highway is a city's primary road, a main road a secondary one, a local road a residential
// street.
const char* osm_highway(RoadClass road_class) {
  return road_class == RoadClass::Highway ? "primary" : road_class == RoadClass::Main ? "secondary" : "residential";
}

// A road's tags: the OSM tags it was read with (its highway class, name, lanes, sidewalk ...;
// its way's id as exacity:osm_id, as a mapped building's), else the class a mapper would
// give it; its width as built, and bridge and layer on bridges the way does not tag.
OsmTagList road_tags(const RoadLine& road, int id) {
  OsmTagList tags;
  for (const auto& [key, value] : road.osm_tags) tags.push_back({key == "osm_id" ? "exacity:osm_id" : key, value});
  auto tagged = [&](const char* key) { return std::any_of(tags.begin(), tags.end(), [&](const auto& t) { return t.first == key; }); };
  if (!tagged("highway")) tags.insert(tags.begin(), {"highway", osm_highway(road.road_class)});
  tags.push_back({"width", osm_number(road.width)});
  if (road.bridge && !tagged("bridge")) {
    tags.push_back({"bridge", "yes"});
    if (!tagged("layer")) tags.push_back({"layer", "1"});
  }
  tags.push_back({"exacity:id", std::to_string(id)});
  return tags;
}

// New objects carry negative ids (JOSM's convention), and two cities must not share one, or
// `osmium merge` of their files keeps one city's object of each id: the ids are
// -(K * 2^32 + n) for n from 1, K in [1, 2^24) a hash of every node's location, so the same
// city always has the same ids and different cities ids apart (by chance of 1 in 2^24).
std::int64_t first_osm_id(const std::vector<osmium::Location>& locations) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a
  for (const osmium::Location& l : locations)
    for (std::int32_t v : {l.x(), l.y()})
      for (int byte = 0; byte < 4; ++byte) hash = (hash ^ ((static_cast<std::uint32_t>(v) >> (8 * byte)) & 0xff)) * 1099511628211ull;
  const std::int64_t key = static_cast<std::int64_t>(hash % ((1u << 24) - 1)) + 1;
  return key << 32;
}

}  // namespace

bool write_city_osm(const City& city, const fs::path& file, std::optional<std::int64_t> first_given_id) {
  const std::optional<int> epsg = epsg_of(city.settings.crs);
  if (!epsg) return false;
  const ToLonLat to_lon_lat(*epsg);
  OsmNodes nodes;
  std::vector<OsmWay> ways;
  auto way = [&](const std::vector<geom::Vec2>& points, OsmTagList tags) {
    OsmWay w{{}, std::move(tags)};
    for (geom::Vec2 p : points) w.nodes.push_back(nodes.at(p));
    ways.push_back(std::move(w));
  };
  for (std::size_t i = 0; i < city.ground.roads.size(); ++i) {
    const RoadLine& road = city.ground.roads[i];
    if (road.line.size() >= 2) way(road.line, road_tags(road, static_cast<int>(i)));
  }
  std::vector<OsmMultipolygon> multipolygons;
  auto closed = [](std::vector<geom::Vec2> ring) {
    ring.push_back(ring.front());
    return ring;
  };
  // A footprint: a closed way, or with courtyards as OSM maps them: the tags on a
  // multipolygon relation, its rings untagged ways.
  auto area = [&](const geom::Polygon& polygon, OsmTagList tags) {
    if (polygon.holes.empty()) return way(closed(polygon.outer), std::move(tags));
    OsmMultipolygon& m = multipolygons.emplace_back();
    m.tags = std::move(tags);
    m.tags.insert(m.tags.begin(), {"type", "multipolygon"});
    m.members.push_back({ways.size(), "outer"});
    way(closed(polygon.outer), {});
    for (const geom::Ring& hole : polygon.holes) {
      m.members.push_back({ways.size(), "inner"});
      way(closed(hole), {});
    }
  };
  std::map<int, const Building*> with_parts;
  for (const Building& b : city.buildings)
    if (!b.parts.empty()) with_parts[b.stable_id] = &b;  // by the id the layer writes
  for (const VectorFeature& b : city.layers.buildings.features) {
    if (b.properties.value("kind", std::string("building")) != "building") continue;
    // A mapped building keeps its building tag and says where it came from.
    const bool mapped = b.properties.value("mapped", false);
    OsmTagList tags{{"building", mapped ? b.properties.value("building", std::string("yes")) : std::string("yes")}};
    if (b.properties.contains("height") && b.properties["height"].is_number())
      tags.push_back({"height", osm_number(b.properties["height"].get<double>())});
    const int id = b.properties.value("id", -1);
    tags.push_back({"exacity:id", std::to_string(id)});
    if (mapped) {
      tags.push_back({"exacity:mapped", "yes"});
      if (b.properties.contains("osm_id") && b.properties["osm_id"].is_string())
        tags.push_back({"exacity:osm_id", b.properties["osm_id"].get<std::string>()});
      // A footprint layer's identifier: BAG's as OSM's Dutch buildings carry it, the number
      // without "NL.IMBAG.Pand." and its leading zeros; else the layer's FID.
      if (b.properties.contains("identificatie") && b.properties["identificatie"].is_string()) {
        std::string bag = b.properties["identificatie"].get<std::string>();
        bag = bag.substr(bag.find_last_of('.') + 1);
        bag.erase(0, std::min(bag.find_first_not_of('0'), bag.size() - 1));
        tags.push_back({"ref:bag", bag});
      }
      if (b.properties.contains("fid") && b.properties["fid"].is_string())
        tags.push_back({"exacity:fid", b.properties["fid"].get<std::string>()});
    }
    area(b.polygon, std::move(tags));
    // Its building:parts as OSM's Simple 3D Buildings maps them, after its outline.
    if (auto it = with_parts.find(id); it != with_parts.end())
      for (const BuildingPart& part : it->second->parts) {
        OsmTagList part_tags{{"building:part", part.tag}, {"height", osm_number(part.height)}};
        if (part.bottom > 0) part_tags.push_back({"min_height", osm_number(part.bottom)});
        if (part.roof != "flat") part_tags.push_back({"roof:shape", part.roof});
        if (!part.osm_id.empty()) part_tags.push_back({"exacity:osm_id", part.osm_id});
        area(part.polygon, std::move(part_tags));
      }
  }
  // Street clutter as the tagged nodes mappers use for it, after the ways' nodes.
  std::vector<osmium::Location> locations;
  for (geom::Vec2 p : nodes.positions()) {
    const geom::Vec2 ll = to_lon_lat(p);
    locations.push_back(osmium::Location{ll.x, ll.y});
  }
  for (const Clutter& c : city.clutter.items) {
    const geom::Vec2 ll = to_lon_lat(c.spot);
    locations.push_back(osmium::Location{ll.x, ll.y});
  }
  const std::int64_t first_id = first_osm_id(locations);
  // The n-th of `count` objects of a type: ids rise through the file, as `osmium merge` and
  // GDAL's OSM driver require of each input; new objects' from the most negative to
  // -(first_id + 1), or the user's range from its first id.
  auto id = [&](std::size_t n, std::size_t count) {
    if (first_given_id) return static_cast<osmium::object_id_type>(*first_given_id + static_cast<std::int64_t>(n));
    return static_cast<osmium::object_id_type>(-(first_id + static_cast<std::int64_t>(count - n)));
  };

  osmium::memory::Buffer node_buffer{1024 * 1024, osmium::memory::Buffer::auto_grow::yes};
  for (std::size_t i = 0; i < locations.size(); ++i) {
    {
      osmium::builder::NodeBuilder node{node_buffer};
      node.set_id(id(i, locations.size())).set_version(1).set_visible(true);
      node.set_location(locations[i]);
      node.set_user("exacity");
      if (i >= nodes.positions().size()) {
        osmium::builder::TagListBuilder tags{node};
        const auto [key, value] = osm_clutter_tag(city.clutter.items[i - nodes.positions().size()].instance.kind);
        tags.add_tag(key, value);
      }
    }
    node_buffer.commit();
  }
  osmium::memory::Buffer way_buffer{1024 * 1024, osmium::memory::Buffer::auto_grow::yes};
  for (std::size_t i = 0; i < ways.size(); ++i) {
    {
      osmium::builder::WayBuilder builder{way_buffer};
      builder.set_id(id(i, ways.size())).set_version(1).set_visible(true);
      builder.set_user("exacity");
      {
        osmium::builder::WayNodeListBuilder refs{builder};
        for (std::size_t n : ways[i].nodes) refs.add_node_ref(id(n, locations.size()));
      }
      osmium::builder::TagListBuilder tag_list{builder};
      for (const auto& [k, v] : ways[i].tags) tag_list.add_tag(k, v);
    }
    way_buffer.commit();
  }
  osmium::memory::Buffer relation_buffer{1024 * 1024, osmium::memory::Buffer::auto_grow::yes};
  for (std::size_t i = 0; i < multipolygons.size(); ++i) {
    {
      osmium::builder::RelationBuilder builder{relation_buffer};
      builder.set_id(id(i, multipolygons.size())).set_version(1).set_visible(true);
      builder.set_user("exacity");
      {
        osmium::builder::RelationMemberListBuilder members{builder};
        for (const auto& [w, role] : multipolygons[i].members)
          members.add_member(osmium::item_type::way, id(w, ways.size()), role);
      }
      osmium::builder::TagListBuilder tag_list{builder};
      for (const auto& [k, v] : multipolygons[i].tags) tag_list.add_tag(k, v);
    }
    relation_buffer.commit();
  }
  try {
    osmium::io::Header header;
    header.set("generator", "exacity");
    osmium::io::Writer writer{file.string(), header, osmium::io::overwrite::allow};
    writer(std::move(node_buffer));
    writer(std::move(way_buffer));
    if (!multipolygons.empty()) writer(std::move(relation_buffer));
    writer.close();
  } catch (const std::exception& e) {
    throw UserError(file.string() + ": cannot be written (" + e.what() + ")");
  }
  return true;
}

}  // namespace exacity
