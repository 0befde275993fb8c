#include "generate/export/formats.h"

#include "generate/cancellable_invoke.h"
#include "generate/export/cityjson_export.h"
#include "generate/export/gis_export.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

// Each layer into vector/NAME.geojson, the layers at once; the street clutter's as points.
void write_geojson_layers(const FormatInput& in) {
  const std::vector<const Layer*>& layers = *in.layers;
  for_each_cancellable(layers.size(), [&](std::size_t i) {
    const Layer& l = *layers[i];
    const fs::path file = in.dir / "vector" / (l.name + ".geojson");
    l.name == "clutter" ? write_point_geojson(l, *in.crs, file) : write_geojson(l, *in.crs, file);
  });
}

template <const char* kName>
void write_ogr(const FormatInput& in) {
  write_vector_formats(*in.layers, in.dir, {kName}, *in.crs);
}
constexpr char kGpkg[] = "gpkg", kFgb[] = "fgb", kShp[] = "shp", kDxf[] = "dxf";

}  // namespace

const std::vector<CityFormat> kCityFormats{
    {"geojson", FormatKind::Vector, "vector/*.geojson", write_geojson_layers},
    {kGpkg, FormatKind::OptionalVector, "city.gpkg", write_ogr<kGpkg>},
    {kFgb, FormatKind::OptionalVector, "vector/*.fgb", write_ogr<kFgb>},
    {kShp, FormatKind::OptionalVector, "vector/shp/", write_ogr<kShp>},
    {kDxf, FormatKind::OptionalVector, "city.dxf", write_ogr<kDxf>},
    {"cityjson", FormatKind::ThreeD, "city.city.json",
     [](const FormatInput& in) {
       write_cityjson(*in.meshed, in.dir / "city.city.json", in.cityjson_seq ? in.dir / "city.city.jsonl" : fs::path());
     }},
    {"gltf", FormatKind::ThreeD, "city.glb",
     [](const FormatInput& in) { in.counts->gltf = write_gltf(*in.meshed, in.dir / "city.glb"); }},
    {"obj", FormatKind::ThreeD, "city.obj",  // with city.mtl, and city.ply in the same walk
     [](const FormatInput& in) { in.counts->mesh = write_meshes(*in.meshed, in.dir / "city.obj", in.dir / "city.ply"); }},
};

std::vector<std::string> vector_format_names() {
  std::vector<std::string> names;
  for (const CityFormat& f : kCityFormats)
    if (f.kind != FormatKind::ThreeD) names.push_back(f.name);
  return names;
}

std::string optional_vector_formats_text() {
  std::vector<const CityFormat*> optional;
  for (const CityFormat& f : kCityFormats)
    if (f.kind == FormatKind::OptionalVector) optional.push_back(&f);
  std::string text;
  for (std::size_t i = 0; i < optional.size(); ++i) {
    text += i == 0 ? "" : i + 1 == optional.size() ? " or " : ", ";
    text += std::string(optional[i]->name) + " (OUT/" + optional[i]->files + ")";
  }
  return text;
}

}  // namespace exacity
