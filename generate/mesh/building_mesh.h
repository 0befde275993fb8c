// Building meshes (OpenMesh, double precision): a footprint extruded to its height, with
// walls, a flat roof and a ground face kept as separate surface classes.
#pragma once

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "generate/city/surface.h"
#include "generate/placement/buildings.h"

namespace exacity {

struct MeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;  // city coordinates need doubles
  using Normal = OpenMesh::Vec3d;
};
using Mesh = OpenMesh::PolyMesh_ArrayKernelT<MeshTraits>;


// Meshes are z up, each face carrying a Surface in the mesh's "surface" face property.
// An extruded building's is closed and outward-facing, its walls reaching down to the
// terrain's lowest point under it.
// One with building:parts is their prisms, each closed on its own, and not its outline's.
Mesh building_mesh(const Building& b);
// A building:part's alone (CityJSON's BuildingPart).
Mesh building_part_mesh(const Building& b, const BuildingPart& part);
// A placed model's: its library mesh moved into place (faces classed by their slope) on a
// foundation where the ground slopes; without a library, only the foundation.
Mesh model_mesh(const ModelInstance& m, const ModelLibrary* library);

// The mesh of every building and model, by id, in parallel; the exporters share them.
std::vector<Mesh> structure_meshes(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                                   const ModelLibrary* library);

// The mesh as triangles (faces triangulated in their plane): one per entry of `surface`.
struct MeshTriangles {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<Surface> surface;
};
MeshTriangles mesh_triangles(const Mesh& mesh);

// The face property that says which surface a face belongs to.
OpenMesh::FPropHandleT<int> surface_property(const Mesh& mesh);

}  // namespace exacity
