// vector/clutter.geojson: street clutter as points (docs/design.md, Outputs).
#pragma once

#include <vector>

#include "generate/export/geojson.h"
#include "generate/placement/clutter.h"

namespace exacity {

// A Point per piece of clutter where it stands, with id, kind, model, road (the centre line
// it dresses) and heading (degrees counter-clockwise from east, where its front faces).
Layer clutter_layer(const std::vector<Clutter>& clutter, const ModelLibrary* library);

}  // namespace exacity
