#include "generate/export/mesh_export.h"

#include <fstream>
#include <sstream>

#include "generate/cancel.h"
#include "generate/export/cancellable_file.h"
#include "generate/city/palette.h"
#include "generate/errors.h"
#include "generate/export/geojson.h"

namespace exacity {
namespace {

// PLY's surface classes: a building's, then one per kind of ground layer.
constexpr const char* kPlySurfaces = "0 ground, 1 wall, 2 roof, 3 terrain, 4 zone, 5 water, 6 road, 7 bridge";
int ply_surface(GroundKind kind) { return 3 + static_cast<int>(kind); }

// Both files' vertices and faces, counted across the city (OBJ's indices from 1, PLY's from 0).
class MeshWriter {
 public:
  MeshWriter(std::ostream& obj, std::ostream& mtl) : obj_(obj), mtl_(mtl) {}

  void material(const std::string& name, const Colour& c) {
    mtl_ << "newmtl " << name << "\nKd " << format_number(c[0]) << ' ' << format_number(c[1]) << ' '
         << format_number(c[2]) << "\n\n";
  }
  void object(const std::string& name) { obj_ << "o " << name << '\n'; }
  void use(const std::string& material) { obj_ << "usemtl " << material << '\n'; }

  // The object's vertices go in one run; faces index them from `first()`.
  std::size_t first() const { return counts_.vertices; }
  void vertex(double x, double y, double z) {
    const std::string xyz = format_number(x) + ' ' + format_number(y) + ' ' + format_number(z);
    obj_ << "v " << xyz << '\n';
    ply_vertices_ << xyz << '\n';
    ++counts_.vertices;
  }
  // A face of vertices counted across the city from 0, with its PLY surface class.
  template <typename Indices>
  void face(const Indices& vertices, int surface) {
    obj_ << 'f';
    ply_faces_ << vertices.size();
    for (std::size_t v : vertices) {
      obj_ << ' ' << v + 1;
      ply_faces_ << ' ' << v;
    }
    obj_ << '\n';
    ply_faces_ << ' ' << surface << '\n';
    ++counts_.faces;
  }

  MeshCounts write_ply(std::ostream& ply) const {
    ply << "ply\nformat ascii 1.0\ncomment Exacity city: x east, y north, z up, metres; surface " << kPlySurfaces
        << "\nelement vertex " << counts_.vertices
        << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << counts_.faces
        << "\nproperty list uchar int vertex_indices\nproperty uchar surface\nend_header\n"
        << ply_vertices_.str() << ply_faces_.str();
    return counts_;
  }

 private:
  std::ostream &obj_, &mtl_;
  std::ostringstream ply_vertices_, ply_faces_;
  MeshCounts counts_;
};

}  // namespace

MeshCounts write_meshes(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                        const std::vector<Mesh>& meshes, const std::vector<GroundLayer>& ground,
                        const std::filesystem::path& obj_file, const std::filesystem::path& ply_file) {
  std::filesystem::path mtl_file = obj_file;
  mtl_file.replace_extension(".mtl");
  std::ofstream obj(obj_file, std::ios::binary), mtl(mtl_file, std::ios::binary);
  if (!obj || !mtl)
    throw UserError(obj_file.string() + ": cannot write this file; check the output folder's permissions");
  obj << "# Exacity city: x east, y north, z up, metres\nmtllib " << mtl_file.filename().string() << '\n';
  MeshWriter out(obj, mtl);

  auto material_name = [](ZoneType zone, Surface s) {
    return std::string(name(zone)) + '_' + kSurfaceNames[static_cast<int>(s)];
  };
  for (ZoneType zone : {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial})
    for (Surface s : {Surface::Ground, Surface::Wall, Surface::Roof})
      out.material(material_name(zone, s), surface_colour(zone, s));
  for (const GroundLayer& layer : ground) out.material(layer.name, layer.colour);

  std::vector<ZoneType> zone_of;
  for_each_by_id(
      buildings, models, [&](const Building& b) { zone_of.push_back(b.zone); },
      [&](const ModelInstance& m) { zone_of.push_back(m.zone); });
  const CancelCheck cancel;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    cancel.check();
    const Mesh& mesh = meshes[i];
    auto surface = surface_property(mesh);
    out.object("building_" + std::to_string(i));
    const std::size_t first = out.first();
    for (auto v : mesh.vertices()) out.vertex(mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2]);
    // Faces grouped by material.
    for (Surface s : {Surface::Ground, Surface::Wall, Surface::Roof}) {
      out.use(material_name(zone_of[i], s));
      for (auto f : mesh.faces()) {
        if (mesh.property(surface, f) != static_cast<int>(s)) continue;
        std::vector<std::size_t> face;
        for (auto v : mesh.fv_range(f)) face.push_back(first + v.idx());
        out.face(face, static_cast<int>(s));
      }
    }
  }
  for (const GroundLayer& layer : ground) {
    cancel.check();
    out.object(layer.name);
    out.use(layer.name);
    const std::size_t first = out.first();
    for (const Vec3& v : layer.mesh.vertices) out.vertex(v[0], v[1], v[2]);
    for (const auto& t : layer.mesh.triangles)
      out.face(std::array<std::size_t, 3>{first + t[0], first + t[1], first + t[2]}, ply_surface(layer.kind));
  }

  CancellableFile ply(ply_file);
  const MeshCounts counts = out.write_ply(ply);
  ply.close();
  if (!obj || !mtl) throw UserError(obj_file.string() + ": write failed (disk full?)");
  return counts;
}

}  // namespace exacity
