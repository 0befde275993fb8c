// Wavefront OBJ as real model files write it: polygons of any size (triangulated here),
// negative (relative) indices, v/vt/vn index forms with or without texture coordinates and
// normals, several objects and groups, materials from the .mtl (diffuse colour and
// texture: Kd and map_Kd), doubled faces. Geometry, colours, textures and the corners'
// texture coordinates are kept.
#pragma once

#include <array>
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "generate/placement/texture_image.h"
#include "geom/vec3.h"

namespace exacity {

using geom::Vec3;

using Uv = std::array<double, 2>;

struct MeshMaterial {
  std::string name;
  Vec3 colour{0.7, 0.7, 0.7};  // linear RGB in [0, 1]; multiplies the texture where there is one
  // map_Kd's image, shared by every material naming the same file; null without one.
  std::shared_ptr<const TextureImage> texture{};
  bool clamp = false;  // map_Kd -clamp on: coordinates outside 0..1 take the edge's texel, else the image repeats
};

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
  std::vector<int> material;                  // per triangle, into materials
  std::vector<MeshMaterial> materials;        // at least one
  // Per triangle, its corners' texture coordinates (OBJ's vt: u to the right, v up, the
  // image spanning 0..1), map_Kd's -s and -o applied: empty when no material has a texture,
  // else one entry a triangle ({0, 0} each for untextured ones). A face without vt keeps
  // its colour but not the texture: its material is an untextured copy.
  std::vector<std::array<Uv, 3>> uv;
  bool textured() const { return !uv.empty(); }
};

// Triangles of a planar polygon in 3D, as indices into `corners`, wound as the polygon is:
// triangulated in the plane it mostly lies in (a fan would cross a concave notch), or a
// fan when the polygon is not simple there.
std::vector<std::array<int, 3>> triangulate_planar(const std::vector<Vec3>& corners);

// The files an .mtl's map_Kd lines name, as written (relative to the .mtl's folder, "/"
// between parts); a line that does not parse is left out (read_obj reports it).
std::vector<std::string> texture_files(const std::filesystem::path& mtl);
// The .mtl files an OBJ file's mtllib lines name, as read_obj reads them (a name with spaces
// whole when a file has it), relative to the OBJ's folder.
std::vector<std::string> material_files(const std::filesystem::path& obj);

// Reads the file, merging vertices at the same position and dropping triangles that
// repeat another (either winding) or have no area. Throws UserError naming the file and
// line when the file cannot be read, an index points nowhere or nothing is left, and
// naming the .mtl file and line when a texture is missing or unreadable. `textures` shares
// images between models (a library's); null: the file's own. Unless `within` is empty, the
// .mtl and texture files must lie in that folder or below (a library's folder, or the OBJ's own
// where the manifest names one outside it).
TriangleMesh read_obj(const std::filesystem::path& file, TextureImages* textures = nullptr,
                      const std::filesystem::path& within = {});
// The same from a stream: `file` names it in messages, and .mtl files are found beside it.
TriangleMesh read_obj(std::istream& in, const std::filesystem::path& file, TextureImages* textures = nullptr,
                      const std::filesystem::path& within = {});

}  // namespace exacity
