// A library of placed models (seeds 001, 002, 004): a JSON manifest naming OBJ files, the
// zone types each suits, its axes and units, and how often to pick it. Each model is
// loaded once, brought to Exacity's frame, and placed many times by transforms.
//
//   {"models": [{"file": "house.obj", "zones": ["residential"], "kind": "building",
//                "up": "y", "unit": "m", "front": "+z", "weight": 2, "scale": [0.9, 1.1]}]}
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "generate/placement/obj_file.h"
#include "generate/city/zone_type.h"
#include "geom/plain.h"

namespace exacity {

// Buildings stand in rows along a lot's road frontage; street furniture stands along the
// frontage inside the setback; trees fill space left in lots.
enum class ModelKind { Building, Street, Tree };
inline const char* name(ModelKind k) {
  return k == ModelKind::Tree ? "tree" : k == ModelKind::Street ? "street" : "building";
}

struct Model {
  std::string name;
  ModelKind kind = ModelKind::Building;
  std::vector<ZoneType> zones;
  double weight = 1;
  double min_scale = 0.9, max_scale = 1.1;  // random size variation (seed 001)
  double spacing = 30;                      // m between street furniture along a frontage
  // In metres, z up, its front facing -y, standing on z = 0, its outline's bounding box
  // centred on the origin.
  TriangleMesh mesh;
  // The footprint: the mesh's outline on the ground, counter-clockwise, on the grid. A
  // model whose outline falls apart in pieces, or has courtyards, or whose mesh has more
  // than kExactOutlineTriangles triangles, gets the convex hull; an outline of more than
  // kOutlineCorners corners, a polygon of that many sides around it.
  geom::Ring outline;
  double width = 0, depth = 0, height = 0;  // along x, y and z
};

inline constexpr std::size_t kExactOutlineTriangles = 20000;
inline constexpr std::size_t kOutlineCorners = 64;

struct ModelLibrary {
  std::filesystem::path file;
  std::vector<Model> models;
  // The models for a zone type and kind, as indices.
  std::vector<int> choices(ZoneType zone, ModelKind kind) const;
};

// Throws UserError naming the manifest, the entry and the fix.
ModelLibrary load_model_library(const std::filesystem::path& manifest);

// A raw mesh brought to the library's frame: up axis "y" or "z"; front one of "+x",
// "-x", "+y", "-y", "+z", "-z" in the file's axes, horizontal; `unit` metres per file
// unit. Throws UserError (with `where`) when the front is not horizontal.
Model normalise_model(TriangleMesh mesh, const std::string& up, const std::string& front, double unit,
                      const std::string& where);

}  // namespace exacity
