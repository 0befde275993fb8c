// A local GeoTIFF drawn under the sketch on the page (docs/serve.md, The page: Basemap):
// GDAL reprojects it into the sketch's CRS over the sketch's surroundings, as a PNG the
// page lays at its extent.
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "generate/sketch/sketch.h"
#include "geom/plain.h"
#include "serve/confined_folder.h"

namespace exacity::serve {

// The features' box grown by its size each way (at least 100 m): where a basemap is wanted.
geom::Box sketch_surroundings(const Sketch& sketch);

// What the page shows: the GeoTIFF's part over the sketch's surroundings, in the sketch's
// CRS (or, for a sketch and a GeoTIFF with no CRS, in the coordinates they share).
struct BasemapImage {
  std::filesystem::path file;
  std::string name;                 // as the user gave it, below the work folder
  std::array<double, 4> extent{};   // min x, min y, max x, max y in the sketch's coordinates
  int width = 0, height = 0;        // pixels
  std::string target_srs;           // "EPSG:N", empty without a CRS
};

// The most pixels a side of the picture has.
constexpr int kBasemapSide = 2048;

// Where the GeoTIFF `name` (a path below the work folder, by its rules) lies over the
// sketch. Throws UserError: a refused or missing name, a file GDAL's GeoTIFF driver does
// not read, no georeferencing, a CRS on one side only, a GeoTIFF nowhere near the sketch,
// or one too large to read without overviews.
BasemapImage place_basemap(const ConfinedFolder& work, const std::string& name, const Sketch& sketch);

// The picture as PNG: 8-bit grey or RGB with an alpha band (transparent where the GeoTIFF
// has no data or does not reach). Throws UserError when GDAL cannot read or warp it.
std::string basemap_png(const BasemapImage& image);

}  // namespace exacity::serve
