#include "generate/export/mesh_export.h"

#include <fstream>
#include <map>
#include <sstream>

#include "generate/errors.h"
#include "generate/export/geojson.h"
#include "generate/city/palette.h"

namespace exacity {
MeshCounts write_meshes(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                        const std::vector<Mesh>& meshes, const std::filesystem::path& obj_file,
                        const std::filesystem::path& ply_file) {
  std::filesystem::path mtl_file = obj_file;
  mtl_file.replace_extension(".mtl");
  std::ofstream obj(obj_file, std::ios::binary), mtl(mtl_file, std::ios::binary);
  if (!obj || !mtl) throw UserError(obj_file.string() + ": cannot write this file; check the output folder's permissions");

  for (ZoneType zone : {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial})
    for (Surface s : {Surface::Ground, Surface::Wall, Surface::Roof}) {
      Colour c = surface_colour(zone, s);
      mtl << "newmtl " << name(zone) << '_' << kSurfaceNames[static_cast<int>(s)] << "\nKd " << format_number(c[0]) << ' '
          << format_number(c[1]) << ' ' << format_number(c[2]) << "\n\n";
    }

  obj << "# Exacity city: x east, y north, z up, metres\nmtllib " << mtl_file.filename().string() << '\n';
  MeshCounts counts;
  std::ostringstream ply_vertices, ply_faces;
  std::vector<ZoneType> zone_of;
  for_each_by_id(buildings, models, [&](const Building& b) { zone_of.push_back(b.zone); },
                 [&](const ModelInstance& m) { zone_of.push_back(m.zone); });
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const Mesh& mesh = meshes[i];
    auto surface = surface_property(mesh);
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      ply_vertices << format_number(p[0]) << ' ' << format_number(p[1]) << ' ' << format_number(p[2]) << '\n';
    }
    for (auto f : mesh.faces()) {
      ply_faces << mesh.valence(f);
      for (auto v : mesh.fv_range(f)) ply_faces << ' ' << counts.vertices + v.idx();
      ply_faces << ' ' << mesh.property(surface, f) << '\n';
    }
    obj << "o building_" << i << '\n';
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      obj << "v " << format_number(p[0]) << ' ' << format_number(p[1]) << ' ' << format_number(p[2]) << '\n';
    }
    // Faces grouped by material; OBJ indices count from 1 across the file.
    for (Surface s : {Surface::Ground, Surface::Wall, Surface::Roof}) {
      obj << "usemtl " << name(zone_of[i]) << '_' << kSurfaceNames[static_cast<int>(s)] << '\n';
      for (auto f : mesh.faces()) {
        if (mesh.property(surface, f) != static_cast<int>(s)) continue;
        obj << 'f';
        for (auto v : mesh.fv_range(f)) obj << ' ' << counts.vertices + v.idx() + 1;
        obj << '\n';
        ++counts.faces;
      }
    }
    counts.vertices += mesh.n_vertices();
  }
  std::ofstream ply(ply_file, std::ios::binary);
  ply << "ply\nformat ascii 1.0\ncomment Exacity city: x east, y north, z up, metres; surface 0 ground, 1 wall, 2 roof\n"
      << "element vertex " << counts.vertices << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "element face " << counts.faces << "\nproperty list uchar int vertex_indices\nproperty uchar surface\n"
      << "end_header\n"
      << ply_vertices.str() << ply_faces.str();
  if (!obj || !mtl || !ply) throw UserError(obj_file.string() + ": write failed (disk full?)");
  return counts;
}

}  // namespace exacity
