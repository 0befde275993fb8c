// Building meshes (OpenMesh, double precision): a footprint extruded to its height, with
// walls, a flat roof and a ground face kept as separate surface classes.
#pragma once

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "generate/buildings.h"

namespace exacity {

struct MeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;  // city coordinates need doubles
  using Normal = OpenMesh::Vec3d;
};
using Mesh = OpenMesh::PolyMesh_ArrayKernelT<MeshTraits>;

enum class Surface : int { Ground = 0, Wall = 1, Roof = 2 };
inline constexpr const char* kSurfaceNames[] = {"ground", "wall", "roof"};

// The mesh of one building: closed, outward-facing, z up. Each face carries a Surface in
// the mesh's "surface" face property.
Mesh building_mesh(const Building& b);

// building_mesh of every building, in parallel; the exporters share them.
std::vector<Mesh> building_meshes(const std::vector<Building>& buildings);

// The face property that says which surface a face belongs to.
OpenMesh::FPropHandleT<int> surface_property(const Mesh& mesh);

}  // namespace exacity
