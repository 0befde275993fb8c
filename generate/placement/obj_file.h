// Wavefront OBJ as real model files write it: polygons of any size (triangulated here),
// negative (relative) indices, v/vt/vn index forms with or without texture coordinates and
// normals, several objects and groups, materials from the .mtl (diffuse colour only),
// doubled faces. Only geometry and colours are kept.
#pragma once

#include <array>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace exacity {

using Vec3 = std::array<double, 3>;

struct MeshMaterial {
  std::string name;
  Vec3 colour{0.7, 0.7, 0.7};  // linear RGB in [0, 1]
};

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
  std::vector<int> material;                  // per triangle, into materials
  std::vector<MeshMaterial> materials;        // at least one
};

// Triangles of a planar polygon in 3D, as indices into `corners`, wound as the polygon is:
// triangulated in the plane it mostly lies in (a fan would cross a concave notch), or a
// fan when the polygon is not simple there.
std::vector<std::array<int, 3>> triangulate_planar(const std::vector<Vec3>& corners);

// Reads the file, merging vertices at the same position and dropping triangles that
// repeat another (either winding) or have no area. Throws UserError naming the file and
// line when the file cannot be read, an index points nowhere or nothing is left.
TriangleMesh read_obj(const std::filesystem::path& file);
// The same from a stream: `file` names it in messages, and .mtl files are found beside it.
TriangleMesh read_obj(std::istream& in, const std::filesystem::path& file);

}  // namespace exacity
