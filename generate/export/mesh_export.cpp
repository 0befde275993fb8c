#include "generate/export/mesh_export.h"

#include <algorithm>
#include <fstream>

#include "generate/cancellable_invoke.h"
#include "generate/city/format_number.h"
#include "generate/city/number_texts.h"
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
// vertex(x, y, z) and face(indices, PLY surface class). The city is walked in pieces (a run
// of structures, or a ground layer), each from `first`, the number of vertices before it.
template <typename Out>
void walk_structures(const std::vector<Mesh>& meshes, const std::vector<ZoneType>& zone_of,
                     const std::vector<int>& id_of, std::size_t begin, std::size_t end, std::size_t first, Out& out) {
  std::vector<std::size_t> face;
  for (std::size_t i = begin; i < end; ++i) {
    const Mesh& mesh = meshes[i];
    out.object(id_of[i]);
    for (const Vec3& p : mesh.points) out.vertex(p[0], p[1], p[2]);
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
}

// A piece of the walk: structures [begin, end), or of ground layer `layer` its vertices or
// (`triangles`) its triangles [begin, end); `first` the number of the vertices before the
// structures, or before the layer.
struct WalkPiece {
  std::size_t begin = 0, end = 0;
  int layer = -1;
  bool triangles = false;
  std::size_t first = 0;
  std::size_t vertices = 0, faces = 0;  // the piece's, for its text's room
};

template <typename Out>
void walk_layer(const GroundLayer& layer, const WalkPiece& piece, Out& out) {
  if (!piece.triangles) {
    if (piece.begin == 0) out.object(layer);
    for (std::size_t i = piece.begin; i < piece.end; ++i) {
      const Vec3& v = layer.mesh.vertices[i];
      out.vertex(v[0], v[1], v[2]);
    }
    return;
  }
  const std::size_t first = piece.first;
  for (std::size_t i = piece.begin; i < piece.end; ++i) {
    const auto& t = layer.mesh.triangles[i];
    out.face(std::array<std::size_t, 3>{first + t[0], first + t[1], first + t[2]}, ply_surface(layer.kind));
  }
}

void append_material_name(std::string& out, ZoneType zone, Surface s) {
  out += name(zone), out += '_', out += kSurfaceNames[static_cast<int>(s)];
}

std::string material_name(ZoneType zone, Surface s) {
  std::string text;
  append_material_name(text, zone, s);
  return text;
}

// The OBJ file's text (its indices from 1) and PLY's vertices, as the walk gives them.
struct ObjAndPlyVertices {
  std::string obj, ply;
  NumberTexts numbers;
  void object(int building) { obj += "o building_", append_number(obj, building), obj += '\n'; }
  void object(const GroundLayer& layer) { obj += "o " + layer.name + "\nusemtl " + layer.name + '\n'; }
  void use(ZoneType zone, Surface s) { obj += "usemtl ", append_material_name(obj, zone, s), obj += '\n'; }
  void vertex(double x, double y, double z) {
    const std::size_t start = obj.size();
    obj += "v ";
    numbers.append(obj, x), obj += ' ', numbers.append(obj, y), obj += ' ', numbers.append(obj, z), obj += '\n';
    ply.append(obj, start + 2);
  }
  template <typename Indices>
  void face(const Indices& vertices, int) {
    obj += 'f';
    for (std::size_t v : vertices) obj += ' ', append_number(obj, v + 1);
    obj += '\n';
  }
};

// PLY's faces (indices from 0, then the surface class), as the walk gives them.
struct PlyFaces {
  std::string ply;
  void object(int) {}
  void object(const GroundLayer&) {}
  void use(ZoneType, Surface) {}
  void vertex(double, double, double) {}
  template <typename Indices>
  void face(const Indices& vertices, int surface) {
    append_number(ply, vertices.size());
    for (std::size_t v : vertices) ply += ' ', append_number(ply, v);
    ply += ' ', append_number(ply, surface), ply += '\n';
  }
};

// Structures (or a layer's vertices or triangles) a piece: enough that a piece is worth
// handing to a thread, few enough that the pieces waiting to be written stay small.
constexpr std::size_t kStructuresAPiece = 2048, kLayerPiece = 1 << 16;

void write_text(std::ostream& out, const std::string& text) {
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

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
  // The pieces, each with the number of vertices before it, and the city's counts.
  std::vector<WalkPiece> pieces;
  MeshCounts counts;
  for (std::size_t begin = 0; begin < meshes.size(); begin += kStructuresAPiece) {
    WalkPiece piece{begin, std::min(begin + kStructuresAPiece, meshes.size()), -1, false, counts.vertices};
    for (std::size_t i = piece.begin; i < piece.end; ++i)
      piece.vertices += meshes[i].points.size(), piece.faces += meshes[i].face_count();
    counts.vertices += piece.vertices, counts.faces += piece.faces;
    pieces.push_back(piece);
  }
  for (std::size_t k = 0; k < ground.size(); ++k) {
    const GroundMesh& mesh = ground[k].mesh;
    for (bool triangles : {false, true}) {
      const std::size_t n = triangles ? mesh.triangles.size() : mesh.vertices.size();
      for (std::size_t begin = 0; begin == 0 || begin < n; begin += kLayerPiece) {
        const std::size_t end = std::min(begin + kLayerPiece, n);
        pieces.push_back({begin, end, static_cast<int>(k), triangles, counts.vertices, triangles ? 0 : end - begin,
                          triangles ? end - begin : 0});
      }
    }
    counts.vertices += mesh.vertices.size(), counts.faces += mesh.triangles.size();
  }
  auto walk = [&](const WalkPiece& piece, auto& out) {
    if (piece.layer >= 0) walk_layer(ground[static_cast<std::size_t>(piece.layer)], piece, out);
    else walk_structures(meshes, zone_of, id_of, piece.begin, piece.end, piece.first, out);
  };
  ply << "ply\nformat ascii 1.0\ncomment Exacity city: x east, y north, z up, metres; surface " << kPlySurfaces
      << "\nelement vertex " << counts.vertices
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << counts.faces
      << "\nproperty list uchar int vertex_indices\nproperty uchar surface\nend_header\n";
  // The pieces' text made at once and written in order: OBJ with PLY's vertices, then PLY's faces.
  make_in_order<ObjAndPlyVertices>(
      pieces.size(),
      [&](std::size_t i, ObjAndPlyVertices& text) {
        // Room for the text at once (about a vertex's and a face's line each), not grown by doubling.
        text.obj.reserve(48 * pieces[i].vertices + 40 * pieces[i].faces), text.ply.reserve(40 * pieces[i].vertices);
        walk(pieces[i], text);
      },
      [&](const ObjAndPlyVertices& text) { write_text(obj, text.obj), write_text(ply, text.ply); });
  make_in_order<PlyFaces>(
      pieces.size(),
      [&](std::size_t i, PlyFaces& text) {
        text.ply.reserve(40 * pieces[i].faces);
        walk(pieces[i], text);
      },
      [&](const PlyFaces& text) { write_text(ply, text.ply); });
  if (!obj || !mtl || !ply) throw UserError(obj_file.string() + ": write failed (disk full?)");
  return counts;
}

}  // namespace exacity
