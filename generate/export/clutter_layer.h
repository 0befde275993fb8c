// vector/clutter.geojson: street clutter as points (docs/design.md, Outputs).
#pragma once

#include <vector>

#include "generate/city/ground.h"
#include "generate/export/geojson.h"
#include "generate/placement/clutter.h"

namespace exacity {

// A Point per piece of clutter where it stands, with id, kind, model, road (the id of the
// centre line it dresses) and heading (degrees counter-clockwise from east, where its front
// faces); ids are stable ones (generate/city/stable_ids.h).
Layer clutter_layer(const std::vector<Clutter>& clutter, const Ground& ground, const ModelLibrary* library);

}  // namespace exacity
