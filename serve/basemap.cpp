#include "serve/basemap.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <cpl_conv.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <gdal_utils.h>
#include <ogr_srs_api.h>

#include "generate/errors.h"
#include "generate/gis/projection.h"

namespace exacity::serve {
namespace fs = std::filesystem;

namespace {

// A source with more pixels than this and no overviews would be read whole to make the
// picture: seconds to minutes of a request thread.
constexpr double kMostSourcePixels = 268435456;  // 16384 x 16384

struct DatasetClose {
  void operator()(GDALDatasetH d) const { GDALClose(d); }
};
using Dataset = std::unique_ptr<std::remove_pointer_t<GDALDatasetH>, DatasetClose>;

std::string gdal_message() {
  const std::string text = CPLGetLastErrorMsg();
  return text.empty() ? "" : " (" + text + ")";
}

// The GeoTIFF, opened by GDAL's GeoTIFF driver alone: no other format, and no file it names
// elsewhere (a VRT could name any file of the machine).
Dataset open_geotiff(const BasemapImage& image) {
  start_gdal();
  CPLErrorReset();
  const char* drivers[] = {"GTiff", nullptr};
  Dataset ds(GDALOpenEx(image.file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr));
  if (!ds)
    throw UserError("basemap " + image.name + ": not a GeoTIFF GDAL reads" + gdal_message() +
                    "; name a .tif file below the work folder");
  return ds;
}

std::string srs_name(OGRSpatialReferenceH srs) {
  const char* authority = OSRGetAuthorityName(srs, nullptr);
  const char* code = OSRGetAuthorityCode(srs, nullptr);
  if (authority && code) return std::string(authority) + ":" + code;
  const char* name = OSRGetName(srs);
  return name ? name : "a CRS without a name";
}

std::string box_text(double x0, double y0, double x1, double y1) {
  char text[160];
  std::snprintf(text, sizeof text, "%.1f, %.1f to %.1f, %.1f", x0, y0, x1, y1);
  return text;
}

// argv for GDAL's utilities, which take their options as a command line.
struct Arguments {
  CPLStringList list;
  Arguments& operator<<(const std::string& a) {
    list.AddString(a.c_str());
    return *this;
  }
};

}  // namespace

geom::Box sketch_surroundings(const Sketch& sketch) {
  geom::Box box = geom::Box::none();
  for (const ZoneFeature& z : sketch.zones)
    for (const geom::Polygon& p : z.polygons)
      for (geom::Vec2 v : p.outer) box.add(v);
  for (const RoadFeature& r : sketch.roads)
    for (const geom::Polyline& l : r.lines)
      for (geom::Vec2 v : l) box.add(v);
  if (box.holds_nothing()) box = {0, 0, 0, 0};
  const double grow = std::max({box.width(), box.height(), 100.0});
  return {box.min_x - grow, box.min_y - grow, box.max_x + grow, box.max_y + grow};
}

BasemapImage place_basemap(const ConfinedFolder& work, const std::string& name, const Sketch& sketch) {
  BasemapImage image;
  image.name = printable(name);
  if (name.empty()) throw UserError("basemap: no file named; name a GeoTIFF below the work folder");
  try {
    image.file = work.resolve(name);
  } catch (const PathRefused& e) {
    throw UserError(std::string("basemap ") + e.what() + "; name a GeoTIFF below the work folder as it is");
  }
  if (!fs::is_regular_file(image.file))
    throw UserError("basemap " + image.name + ": no such file in the work folder; copy the GeoTIFF there first");
  const Dataset ds = open_geotiff(image);
  double transform[6];
  if (GDALGetGeoTransform(ds.get(), transform) != CE_None)
    throw UserError("basemap " + image.name +
                    ": has no georeferencing (no geotransform); give it one with gdal_translate -a_ullr and -a_srs");
  const OGRSpatialReferenceH source_srs = GDALGetSpatialRef(ds.get());
  const std::optional<int> epsg = sketch.crs.is_null() ? std::nullopt : epsg_of(sketch.crs);
  if (epsg && !source_srs)
    throw UserError("basemap " + image.name + ": has no CRS while the sketch is in EPSG:" + std::to_string(*epsg) +
                    "; give it its CRS (gdal_edit.py -a_srs EPSG:<code>)");
  if (!epsg && source_srs)
    throw UserError("basemap " + image.name + ": is in " + srs_name(source_srs) +
                    " while the sketch has no place on Earth (no \"crs\"); give the sketch its \"crs\"");
  if (epsg) image.target_srs = "EPSG:" + std::to_string(*epsg);

  const double pixels = double(GDALGetRasterXSize(ds.get())) * GDALGetRasterYSize(ds.get());
  GDALRasterBandH first = GDALGetRasterBand(ds.get(), 1);
  if (!first) throw UserError("basemap " + image.name + ": has no bands");
  if (pixels > kMostSourcePixels && GDALGetOverviewCount(first) == 0)
    throw UserError("basemap " + image.name + ": " + std::to_string(GDALGetRasterXSize(ds.get())) + " x " +
                    std::to_string(GDALGetRasterYSize(ds.get())) +
                    " pixels and no overviews; add them (gdaladdo) or make it smaller (gdal_translate -outsize)");

  // Its natural extent and pixel size in the sketch's CRS, as gdalwarp would choose them.
  char** options = nullptr;
  if (epsg) options = CSLSetNameValue(options, "DST_SRS", image.target_srs.c_str());
  CPLErrorReset();
  void* transformer = GDALCreateGenImgProjTransformer2(ds.get(), nullptr, options);
  CSLDestroy(options);
  if (!transformer)
    throw UserError("basemap " + image.name + ": cannot be brought into " + image.target_srs + gdal_message());
  double out_transform[6], bounds[4];
  int out_width = 0, out_height = 0;
  const CPLErr suggested = GDALSuggestedWarpOutput2(ds.get(), GDALGenImgProjTransform, transformer, out_transform,
                                                    &out_width, &out_height, bounds, 0);
  GDALDestroyGenImgProjTransformer(transformer);
  if (suggested != CE_None)
    throw UserError("basemap " + image.name + ": cannot be brought into " + image.target_srs + gdal_message());
  const double x0 = bounds[0], y0 = bounds[1], x1 = bounds[2], y1 = bounds[3];

  const geom::Box around = sketch_surroundings(sketch);
  const double cx0 = std::max(x0, around.min_x), cy0 = std::max(y0, around.min_y);
  const double cx1 = std::min(x1, around.max_x), cy1 = std::min(y1, around.max_y);
  if (!(cx0 < cx1 && cy0 < cy1))
    throw UserError("basemap " + image.name + ": lies at " + box_text(x0, y0, x1, y1) +
                    (epsg ? " in " + image.target_srs : std::string()) + ", away from the sketch (" +
                    box_text(around.min_x, around.min_y, around.max_x, around.max_y) + ")");
  // At its own resolution, or coarser so the longer side fits.
  const double pixel = std::max(out_transform[1], std::max(cx1 - cx0, cy1 - cy0) / kBasemapSide);
  image.extent = {cx0, cy0, cx1, cy1};
  image.width = std::clamp(static_cast<int>(std::ceil((cx1 - cx0) / pixel - 1e-9)), 1, kBasemapSide);
  image.height = std::clamp(static_cast<int>(std::ceil((cy1 - cy0) / pixel - 1e-9)), 1, kBasemapSide);
  return image;
}

std::string basemap_png(const BasemapImage& image) {
  const Dataset ds = open_geotiff(image);
  // Colours first: a palette expanded, other than 8-bit samples stretched to 0..255, the
  // first band (grey) or three (RGB) kept, with the alpha band when there is one.
  const int bands = GDALGetRasterCount(ds.get());
  GDALRasterBandH first = GDALGetRasterBand(ds.get(), 1);
  const auto interpretation = [&](int band) { return GDALGetRasterColorInterpretation(GDALGetRasterBand(ds.get(), band)); };
  Arguments colours;
  colours << "-of" << "VRT";
  bool alpha = false;
  if (GDALGetRasterColorTable(first)) {
    colours << "-b" << "1" << "-expand" << "rgba";
    alpha = true;
  } else {
    const int kept = bands >= 3 ? 3 : 1;
    for (int b = 1; b <= kept; ++b) colours << "-b" << std::to_string(b);
    if (bands > kept && interpretation(kept + 1) == GCI_AlphaBand) {
      colours << "-b" << std::to_string(kept + 1);
      alpha = true;
    }
    if (GDALGetRasterDataType(first) != GDT_Byte) colours << "-ot" << "Byte" << "-scale";
  }
  CPLErrorReset();
  std::unique_ptr<GDALTranslateOptions, decltype(&GDALTranslateOptionsFree)> translate(
      GDALTranslateOptionsNew(colours.list.List(), nullptr), GDALTranslateOptionsFree);
  const Dataset coloured(GDALTranslate("", ds.get(), translate.get(), nullptr));
  if (!coloured) throw UserError("basemap " + image.name + ": cannot be read" + gdal_message());

  Arguments warp;
  warp << "-of" << "MEM" << "-r" << "bilinear" << "-dstalpha";
  if (alpha) warp << "-srcalpha";
  if (!image.target_srs.empty()) warp << "-t_srs" << image.target_srs;
  warp << "-te";
  for (double v : image.extent) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    warp << text;
  }
  warp << "-ts" << std::to_string(image.width) << std::to_string(image.height);
  std::unique_ptr<GDALWarpAppOptions, decltype(&GDALWarpAppOptionsFree)> warp_options(
      GDALWarpAppOptionsNew(warp.list.List(), nullptr), GDALWarpAppOptionsFree);
  GDALDatasetH source = coloured.get();
  const Dataset warped(GDALWarp("", nullptr, 1, &source, warp_options.get(), nullptr));
  if (!warped) throw UserError("basemap " + image.name + ": cannot be warped" + gdal_message());

  // Through GDAL's in-memory files, one name per call: requests run side by side.
  static std::atomic<unsigned> calls{0};
  const std::string png_name = "/vsimem/exacity-basemap-" + std::to_string(++calls) + ".png";
  GDALDriverH png_driver = GDALGetDriverByName("PNG");
  Dataset png(GDALCreateCopy(png_driver, png_name.c_str(), warped.get(), FALSE, nullptr, nullptr, nullptr));
  const bool written = png != nullptr;
  png.reset();  // closed: the file is whole
  vsi_l_offset length = 0;
  GByte* bytes = written ? VSIGetMemFileBuffer(png_name.c_str(), &length, TRUE) : nullptr;
  if (!bytes) {
    VSIUnlink(png_name.c_str());
    throw InternalError("basemap " + image.name + ": cannot be written as PNG" + gdal_message());
  }
  std::string out(reinterpret_cast<const char*>(bytes), static_cast<std::size_t>(length));
  CPLFree(bytes);
  return out;
}

}  // namespace exacity::serve
