// Exacity's polygons as OGR's, for the measures and repairs made with GEOS through OGR (in
// doubles: never a decision the exact map makes).
#pragma once

#include <memory>

#include <ogr_geometry.h>

#include "geom/plain.h"

namespace exacity {

// The polygon's rings as they are, each closed.
inline std::unique_ptr<OGRPolygon> ogr_polygon(const geom::Polygon& p) {
  auto out = std::make_unique<OGRPolygon>();
  auto ring = [](const geom::Ring& r) {
    auto o = new OGRLinearRing;
    for (geom::Vec2 v : r) o->addPoint(v.x, v.y);
    o->closeRings();
    return o;
  };
  out->addRingDirectly(ring(p.outer));
  for (const geom::Ring& h : p.holes) out->addRingDirectly(ring(h));
  return out;
}

// The box `margin` round an envelope.
inline OGRPolygon box_around(const OGREnvelope& e, double margin) {
  auto* ring = new OGRLinearRing;
  for (auto [x, y] : {std::pair{e.MinX - margin, e.MinY - margin}, {e.MaxX + margin, e.MinY - margin},
                      {e.MaxX + margin, e.MaxY + margin}, {e.MinX - margin, e.MaxY + margin}})
    ring->addPoint(x, y);
  ring->closeRings();
  OGRPolygon box;
  box.addRingDirectly(ring);
  return box;
}

}  // namespace exacity
