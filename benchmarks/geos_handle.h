// A GEOS geometry owned through GEOS's reentrant C API: freed in the context that made it.
// The judge and the GEOS baseline both hold their geometries so.
#pragma once

#include <geos_c.h>

#include <memory>

namespace exacity::bench {

struct GeosFree {
  GEOSContextHandle_t ctx;
  void operator()(GEOSGeometry* g) const { GEOSGeom_destroy_r(ctx, g); }
};
using GeosGeometry = std::unique_ptr<GEOSGeometry, GeosFree>;

}  // namespace exacity::bench
