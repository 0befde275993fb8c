#include "generate/export/mesh_export.h"

#include <fstream>

#include "generate/cancel.h"
#include "generate/city/format_number.h"
#include "generate/city/palette.h"
#include "generate/errors.h"
#include "generate/export/geojson.h"

namespace exacity {
namespace {

// PLY's surface classes: a building's, then one per kind of ground layer.
constexpr const char* kPlySurfaces = "0 ground, 1 wall, 2 roof, 3 terrain, 4 zone, 5 water, 6 road, 7 bridge";
int ply_surface(GroundKind kind) { return 3 + static_cast<int>(kind); }

// The city's vertices and faces in the order both files list them: each building's
// vertices, then its faces by surface (ground, wall, roof; the material named before each
// surface's faces), then each ground layer's. Faces index vertices counted across the city
// from 0. `out` takes object(building id or ground layer), use(zone, surface),
// vertex(x, y, z) and face(indices, PLY surface class). Walked once per pass (PLY's counts,
// OBJ with PLY's vertices, PLY's faces), so no file is held in memory to be written later.
template <typename Out>
void walk_city(const std::vector<Mesh>& meshes, const std::vector<ZoneType>& zone_of, const std::vector<int>& id_of,
               const std::vector<GroundLayer>& ground, Out& out) {
  const CancelCheck cancel;
  std::size_t first = 0;  // the object's first vertex
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    cancel.check();
    const Mesh& mesh = meshes[i];
    out.object(id_of[i]);
    for (const Vec3& p : mesh.points) out.vertex(p[0], p[1], p[2]);
    std::vector<std::size_t> face;
    for (Surface s : {Surface::Ground, Surface::Wall, Surface::Roof}) {
      out.use(zone_of[i], s);
      for (const Mesh::Face f : mesh.faces()) {
        if (f.surface != s) continue;
        face.clear();
        for (std::uint32_t v : f.corners) face.push_back(first + v);
        out.face(face, static_cast<int>(s));
      }
    }
    first += mesh.points.size();
  }
  for (const GroundLayer& layer : ground) {
    cancel.check();
    out.object(layer);
    for (const Vec3& v : layer.mesh.vertices) out.vertex(v[0], v[1], v[2]);
    for (const auto& t : layer.mesh.triangles)
      out.face(std::array<std::size_t, 3>{first + t[0], first + t[1], first + t[2]}, ply_surface(layer.kind));
    first += layer.mesh.vertices.size();
  }
}

std::string material_name(ZoneType zone, Surface s) {
  return std::string(name(zone)) + '_' + kSurfaceNames[static_cast<int>(s)];
}

// Counts what walk_city gives, for PLY's header.
struct Counter {
  MeshCounts counts;
  void object(int) {}
  void object(const GroundLayer&) {}
  void use(ZoneType, Surface) {}
  void vertex(double, double, double) { ++counts.vertices; }
  template <typename Indices>
  void face(const Indices&, int) { ++counts.faces; }
};

// The OBJ file (its indices from 1) and PLY's vertices, written as walk_city gives them;
// each line made in a reused buffer and written whole.
struct ObjAndPlyVertices {
  std::ostream &obj, &ply;
  std::string line{};
  void object(int building) { obj << "o building_" << building << '\n'; }
  void object(const GroundLayer& layer) { obj << "o " << layer.name << "\nusemtl " << layer.name << '\n'; }
  void use(ZoneType zone, Surface s) { obj << "usemtl " << material_name(zone, s) << '\n'; }
  void vertex(double x, double y, double z) {
    line.assign("v ");
    append_number(line, x), line += ' ', append_number(line, y), line += ' ', append_number(line, z), line += '\n';
    obj.write(line.data(), static_cast<std::streamsize>(line.size()));
    ply.write(line.data() + 2, static_cast<std::streamsize>(line.size() - 2));
  }
  template <typename Indices>
  void face(const Indices& vertices, int) {
    line.clear(), line += 'f';
    for (std::size_t v : vertices) line += ' ', append_number(line, v + 1);
    line += '\n';
    obj.write(line.data(), static_cast<std::streamsize>(line.size()));
  }
};

// PLY's faces (indices from 0, then the surface class), written as walk_city gives them.
struct PlyFaces {
  std::ostream& ply;
  std::string line{};
  void object(int) {}
  void object(const GroundLayer&) {}
  void use(ZoneType, Surface) {}
  void vertex(double, double, double) {}
  template <typename Indices>
  void face(const Indices& vertices, int surface) {
    line.clear();
    append_number(line, vertices.size());
    for (std::size_t v : vertices) line += ' ', append_number(line, v);
    line += ' ', append_number(line, surface), line += '\n';
    ply.write(line.data(), static_cast<std::streamsize>(line.size()));
  }
};

}  // namespace

MeshCounts write_meshes(const MeshedCity& city, const std::filesystem::path& obj_file,
                        const std::filesystem::path& ply_file) {
  const std::vector<Building>& buildings = city.buildings;
  const std::vector<ModelInstance>& models = city.models;
  const std::vector<Mesh>& meshes = city.meshes;
  const std::vector<GroundLayer>& ground = city.ground_layers;
  std::filesystem::path mtl_file = obj_file;
  mtl_file.replace_extension(".mtl");
  std::ofstream obj(obj_file, std::ios::binary), mtl(mtl_file, std::ios::binary), ply(ply_file, std::ios::binary);
  if (!obj || !mtl || !ply)
    throw UserError(obj_file.string() + ": cannot write this file; check the output folder's permissions");
  obj << "# Exacity city: x east, y north, z up, metres\nmtllib " << mtl_file.filename().string() << '\n';

  auto material = [&](const std::string& name, const Colour& c) {
    mtl << "newmtl " << name << "\nKd " << format_number(c[0]) << ' ' << format_number(c[1]) << ' '
        << format_number(c[2]) << "\n\n";
  };
  for (ZoneType zone : {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial})
    for (Surface s : {Surface::Ground, Surface::Wall, Surface::Roof}) material(material_name(zone, s), surface_colour(zone, s));
  for (const GroundLayer& layer : ground) material(layer.name, layer.colour);

  std::vector<ZoneType> zone_of;
  std::vector<int> id_of;  // ids in the outputs
  for_each_by_id(
      buildings, models, [&](const Building& b) { zone_of.push_back(b.zone), id_of.push_back(b.stable_id); },
      [&](const ModelInstance& m) { zone_of.push_back(m.zone), id_of.push_back(m.stable_id); });
  Counter counter;
  walk_city(meshes, zone_of, id_of, ground, counter);
  const MeshCounts& counts = counter.counts;
  ply << "ply\nformat ascii 1.0\ncomment Exacity city: x east, y north, z up, metres; surface " << kPlySurfaces
      << "\nelement vertex " << counts.vertices
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << counts.faces
      << "\nproperty list uchar int vertex_indices\nproperty uchar surface\nend_header\n";
  ObjAndPlyVertices obj_and_vertices{obj, ply};
  walk_city(meshes, zone_of, id_of, ground, obj_and_vertices);
  PlyFaces faces{ply};
  walk_city(meshes, zone_of, id_of, ground, faces);
  if (!obj || !mtl || !ply) throw UserError(obj_file.string() + ": write failed (disk full?)");
  return counts;
}

}  // namespace exacity
