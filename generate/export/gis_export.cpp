#include "generate/export/gis_export.h"

#include <algorithm>
#include <map>
#include <memory>

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

// A GeoJSON layer of OUT/vector, opened once for every format written from it.
struct SourceLayer {
  std::string name;
  GDALDatasetUniquePtr dataset;
  OGRLayer* layer = nullptr;
};

// The GeoJSON layers in OUT/vector, by name.
std::vector<SourceLayer> geojson_layers(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir / "vector"))
    if (entry.path().extension() == ".geojson") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<SourceLayer> out;
  for (const fs::path& file : files) {
    GDALDatasetUniquePtr dataset(GDALDataset::Open(file.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!dataset || dataset->GetLayerCount() != 1) fail(file, "cannot be read back");
    OGRLayer* layer = dataset->GetLayer(0);
    out.push_back({file.stem().string(), std::move(dataset), layer});
  }
  return out;
}

// Copies every GeoJSON layer into `target`, one layer each (GeoPackage, FlatGeobuf and
// Shapefile keep geometry and attributes; CRS set from the sketch's).
void copy_layers(const std::vector<const SourceLayer*>& layers, GDALDataset& target, OGRSpatialReference* srs,
                 const fs::path& file, CSLConstList layer_options = nullptr) {
  // One transaction where the format has them (GeoPackage): a feature each is far slower.
  const bool transaction = target.StartTransaction() == OGRERR_NONE;
  for (const SourceLayer* source : layers) {
    OGRLayer* from = source->layer;
    from->ResetReading();
    const std::string& name = source->name;
    OGRLayer* to = target.CreateLayer(name.c_str(), srs, from->GetGeomType(), const_cast<char**>(layer_options));
    if (!to) fail(file, "cannot hold layer " + name);
    // A list (a block's roads) is written as its JSON text: no format here stores lists.
    OGRFeatureDefn* defn = from->GetLayerDefn();
    std::vector<bool> list(defn->GetFieldCount());
    for (int i = 0; i < defn->GetFieldCount(); ++i) {
      OGRFieldDefn field(defn->GetFieldDefn(i));
      list[i] = field.GetType() == OFTIntegerList || field.GetType() == OFTInteger64List ||
                field.GetType() == OFTRealList || field.GetType() == OFTStringList;
      if (list[i]) field.SetType(OFTString), field.SetSubType(OFSTJSON);
      if (to->CreateField(&field) != OGRERR_NONE) fail(file, "cannot hold field " + std::string(field.GetNameRef()));
    }
    for (OGRFeatureUniquePtr f(from->GetNextFeature()); f; f.reset(from->GetNextFeature())) {
      OGRFeatureUniquePtr copy(OGRFeature::CreateFeature(to->GetLayerDefn()));
      copy->SetGeometry(f->GetGeometryRef());
      for (int i = 0; i < defn->GetFieldCount(); ++i) {
        if (!f->IsFieldSetAndNotNull(i)) continue;
        if (!list[i]) {
          copy->SetField(i, f->GetRawFieldRef(i));
          continue;
        }
        char* json = f->GetFieldAsSerializedJSon(i);
        const std::string values = json ? json : "[]";
        CPLFree(json);
        copy->SetField(i, values.c_str());
      }
      if (to->CreateFeature(copy.get()) != OGRERR_NONE) fail(file, "cannot take a feature of layer " + name);
    }
  }
  if (transaction && target.CommitTransaction() != OGRERR_NONE) fail(file, "cannot be written");
}

// A DXF file's entities carry their CAD layer in the "Layer" field.
void write_dxf(const std::vector<SourceLayer>& layers, const fs::path& file) {
  GDALDatasetUniquePtr ds = create("DXF", file);
  OGRLayer* entities = ds->CreateLayer("entities", nullptr, wkbUnknown, nullptr);
  if (!entities) fail(file, "cannot hold entities");
  for (const SourceLayer& source : layers) {
    OGRLayer* from = source.layer;
    from->ResetReading();
    for (OGRFeatureUniquePtr f(from->GetNextFeature()); f; f.reset(from->GetNextFeature())) {
      OGRFeatureUniquePtr entity(OGRFeature::CreateFeature(entities->GetLayerDefn()));
      entity->SetField("Layer", source.name.c_str());
      entity->SetGeometry(f->GetGeometryRef());
      if (entities->CreateFeature(entity.get()) != OGRERR_NONE) fail(file, "cannot take an entity");
    }
  }
}

}  // namespace

void write_vector_formats(const fs::path& dir, const std::vector<std::string>& formats, const nlohmann::ordered_json& crs) {
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
  const std::vector<SourceLayer> layers = geojson_layers(dir);
  std::vector<const SourceLayer*> all;
  for (const SourceLayer& l : layers) all.push_back(&l);
  for (const std::string& format : formats) {
    if (format == "gpkg") {
      GDALDatasetUniquePtr ds = create("GPKG", dir / "city.gpkg");
      copy_layers(all, *ds, srs.get(), dir / "city.gpkg");
    } else if (format == "fgb") {
      for (const SourceLayer& layer : layers) {
        const fs::path file = dir / "vector" / (layer.name + ".fgb");
        GDALDatasetUniquePtr ds = create("FlatGeobuf", file);
        copy_layers({&layer}, *ds, srs.get(), file);
      }
    } else if (format == "shp") {
      fs::create_directories(dir / "vector" / "shp");
      GDALDatasetUniquePtr ds = create("ESRI Shapefile", dir / "vector" / "shp");
      copy_layers(all, *ds, srs.get(), dir / "vector" / "shp", dbf_date);
    } else if (format == "dxf") {
      write_dxf(layers, dir / "city.dxf");
    }
  }
}

namespace {

// Nodes by their position as written, so centre lines meeting at a vertex share one.
class OsmNodes {
 public:
  explicit OsmNodes(const ToLonLat& to_lon_lat) : to_lon_lat_(to_lon_lat) {}
  std::int64_t at(geom::Vec2 p) {
    auto [it, added] = ids_.try_emplace({p.x, p.y}, static_cast<std::int64_t>(ids_.size() + 1));
    if (added) order_.push_back(p);
    return it->second;
  }
  void write(osmium::memory::Buffer& buffer) const {
    for (std::size_t i = 0; i < order_.size(); ++i) {
      const geom::Vec2 ll = to_lon_lat_(order_[i]);
      osmium::builder::NodeBuilder node{buffer};
      node.set_id(static_cast<osmium::object_id_type>(i + 1)).set_version(1).set_visible(true);
      node.set_location(osmium::Location{ll.x, ll.y});
      node.set_user("exacity");
    }
    buffer.commit();
  }
  std::int64_t count() const { return static_cast<std::int64_t>(order_.size()); }

 private:
  const ToLonLat& to_lon_lat_;
  std::map<std::pair<double, double>, std::int64_t> ids_;
  std::vector<geom::Vec2> order_;
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

const char* osm_highway(const std::string& road_class) {
  return road_class == "highway" ? "motorway" : road_class == "main" ? "primary" : "residential";
}

}  // namespace

bool write_city_osm(const City& city, const fs::path& file) {
  const std::optional<int> epsg = epsg_of(city.sketch.crs);
  if (!epsg) return false;
  const ToLonLat to_lon_lat(*epsg);
  OsmNodes nodes(to_lon_lat);
  osmium::memory::Buffer ways{1024 * 1024, osmium::memory::Buffer::auto_grow::yes};
  std::int64_t way_id = 0;
  auto way = [&](const std::vector<geom::Vec2>& points, const std::vector<std::pair<std::string, std::string>>& tags) {
    {
      osmium::builder::WayBuilder builder{ways};
      builder.set_id(++way_id).set_version(1).set_visible(true);
      builder.set_user("exacity");
      {
        osmium::builder::WayNodeListBuilder refs{builder};
        for (geom::Vec2 p : points) refs.add_node_ref(nodes.at(p));
      }
      osmium::builder::TagListBuilder tag_list{builder};
      for (const auto& [k, v] : tags) tag_list.add_tag(k, v);
    }
    ways.commit();
  };
  for (const VectorFeature& road : city.layers.roads.features) {
    if (road.line.size() < 2) continue;
    const auto& p = road.properties;
    std::vector<std::pair<std::string, std::string>> tags{{"highway", osm_highway(p.value("class", std::string("local")))}};
    if (p.contains("width") && p["width"].is_number()) tags.push_back({"width", osm_number(p["width"].get<double>())});
    if (p.value("bridge", false)) tags.push_back({"bridge", "yes"}), tags.push_back({"layer", "1"});
    tags.push_back({"exacity:id", std::to_string(p.value("id", -1))});
    way(road.line, tags);
  }
  for (const VectorFeature& b : city.layers.buildings.features) {
    if (b.properties.value("kind", std::string("building")) != "building") continue;
    std::vector<geom::Vec2> ring = b.polygon.outer;
    ring.push_back(ring.front());  // a closed way
    std::vector<std::pair<std::string, std::string>> tags{{"building", "yes"}};
    if (b.properties.contains("height") && b.properties["height"].is_number())
      tags.push_back({"height", osm_number(b.properties["height"].get<double>())});
    tags.push_back({"exacity:id", std::to_string(b.properties.value("id", -1))});
    way(ring, tags);
  }
  osmium::memory::Buffer node_buffer{1024 * 1024, osmium::memory::Buffer::auto_grow::yes};
  nodes.write(node_buffer);
  // Street clutter as the tagged nodes mappers use for it.
  std::int64_t node_id = nodes.count();
  for (const Clutter& c : city.clutter.items) {
    const geom::Vec2 ll = to_lon_lat(c.spot);
    {
      osmium::builder::NodeBuilder node{node_buffer};
      node.set_id(++node_id).set_version(1).set_visible(true);
      node.set_location(osmium::Location{ll.x, ll.y});
      node.set_user("exacity");
      osmium::builder::TagListBuilder tags{node};
      const auto [key, value] = osm_clutter_tag(c.instance.kind);
      tags.add_tag(key, value);
    }
    node_buffer.commit();
  }
  try {
    osmium::io::Header header;
    header.set("generator", "exacity");
    osmium::io::Writer writer{file.string(), header, osmium::io::overwrite::allow};
    writer(std::move(node_buffer));
    writer(std::move(ways));
    writer.close();
  } catch (const std::exception& e) {
    throw UserError(file.string() + ": cannot be written (" + e.what() + ")");
  }
  return true;
}

}  // namespace exacity
