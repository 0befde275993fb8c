// A vector file read through OGR, as `exacity generate` reads a GeoPackage: the bytes are a
// GeoJSON text (features, fields, a crs, as mutations make them), which GDAL turns into a
// GeoPackage in memory (/vsimem/); that file is then read by the sketch reader the CLI
// uses (OGR, projected to metres, OSM tags applied, the sketch's checks): a Sketch or one
// UserError. Texts GDAL itself cannot read or convert are no finding of Exacity's.
#include <cstddef>
#include <cstdint>
#include <string>

#include <gdal_priv.h>
#include <gdal_utils.h>

#include "fuzz/fuzz_target.h"
#include "generate/sketch/sketch.h"
#include "generate/gis/projection.h"

namespace {

// The GeoPackage GDAL makes of `geojson`, or empty when it makes none.
std::string geopackage_of(const std::string& geojson) {
  const std::string source = "/vsimem/exacity-fuzz.geojson", target = "/vsimem/exacity-fuzz.gpkg";
  VSIFCloseL(VSIFileFromMemBuffer(source.c_str(), reinterpret_cast<GByte*>(const_cast<char*>(geojson.data())),
                                  static_cast<vsi_l_offset>(geojson.size()), FALSE));
  std::string bytes;
  GDALDatasetH in = GDALOpenEx(source.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (in) {
    char* argv[] = {const_cast<char*>("-f"), const_cast<char*>("GPKG"), nullptr};
    GDALVectorTranslateOptions* options = GDALVectorTranslateOptionsNew(argv, nullptr);
    GDALDatasetH out = GDALVectorTranslate(target.c_str(), nullptr, 1, &in, options, nullptr);
    GDALVectorTranslateOptionsFree(options);
    if (out) {
      GDALClose(out);  // written in full only on close
      vsi_l_offset length = 0;
      if (GByte* buffer = VSIGetMemFileBuffer(target.c_str(), &length, FALSE))
        bytes.assign(reinterpret_cast<const char*>(buffer), length);
    }
    GDALClose(in);
  }
  VSIUnlink(target.c_str());
  VSIUnlink(source.c_str());
  return bytes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  exacity::start_gdal();
  const std::string gpkg = geopackage_of(std::string(reinterpret_cast<const char*>(data), size));
  if (gpkg.empty()) return 0;
  const auto dir = exacity::fuzz::scratch();
  exacity::fuzz::write(dir / "fuzz.gpkg", gpkg);
  exacity::fuzz::expect_user_errors_only([&] { exacity::load_sketch(dir / "fuzz.gpkg"); });
  return 0;
}
