#include "generate/mesh/building_mesh.h"

#include <cmath>
#include <map>

#include <mutex>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <tbb/parallel_for.h>

#include "generate/cancel.h"
#include "geom/triangulate.h"

namespace exacity {

namespace {

struct MeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;  // city coordinates need doubles
  using Normal = OpenMesh::Vec3d;
};
// The mesh while it is built: OpenMesh joins each face to those sharing its edges.
using JoinedMesh = OpenMesh::PolyMesh_ArrayKernelT<MeshTraits>;

// A gable: an upright triangle, all its points on one vertical plane (its footprint is a line).
bool is_gable(const geom::Face3& f) {
  if (f.size() != 3) return false;
  double cross = (f[1][0] - f[0][0]) * (f[2][1] - f[0][1]) - (f[1][1] - f[0][1]) * (f[2][0] - f[0][0]);
  double scale = std::hypot(f[1][0] - f[0][0], f[1][1] - f[0][1]) * std::hypot(f[2][0] - f[0][0], f[2][1] - f[0][1]);
  return std::abs(cross) <= 1e-9 * scale;
}

// OpenMesh reports every face of a non-manifold model it cannot join on stderr; such faces
// are handled here (they stand alone), so the reports are noise.
void quiet_openmesh() {
  static std::once_flag once;
  std::call_once(once, [] { omerr().disable(); });
}

}  // namespace

void Mesh::add_face(Surface s, std::span<const std::uint32_t> corners) {
  faces_.push_back(static_cast<std::uint32_t>(corners.size()));
  faces_.push_back(static_cast<std::uint32_t>(s));
  faces_.insert(faces_.end(), corners.begin(), corners.end());
}

void Mesh::shrink() {
  points.shrink_to_fit();
  faces_.shrink_to_fit();
}

std::size_t Mesh::face_count() const {
  std::size_t n = 0;
  for (FaceIterator f = faces().begin(); !(f == faces().end()); ++f) ++n;
  return n;
}

std::vector<Mesh> structure_meshes(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                                   const ModelLibrary* library) {
  quiet_openmesh();
  std::vector<Mesh> meshes(buildings.size() + models.size());
  const CancelCheck cancel;
  tbb::parallel_for(std::size_t(0), buildings.size(), [&](std::size_t i) {
    cancel.check();
    meshes[buildings[i].id] = building_mesh(buildings[i]);
  });
  const ModelMeshes model_meshes(library);
  tbb::parallel_for(std::size_t(0), models.size(), [&](std::size_t i) {
    cancel.check();
    meshes[models[i].id] = model_meshes(models[i]);
  });
  return meshes;
}

MeshTriangles mesh_triangles(const Mesh& mesh) {
  MeshTriangles out;
  out.vertices = mesh.points;
  std::vector<Vec3> corners;
  for (const Mesh::Face f : mesh.faces()) {
    corners.clear();
    for (std::uint32_t v : f.corners) corners.push_back(out.vertices[v]);
    for (const auto& t : triangulate_planar(corners)) {
      out.triangles.push_back({static_cast<int>(f.corners[t[0]]), static_cast<int>(f.corners[t[1]]),
                               static_cast<int>(f.corners[t[2]])});
      out.surface.push_back(f.surface);
    }
  }
  return out;
}

namespace {

// Builds a mesh face by face: one vertex per distinct point, so faces share their edges
// and the mesh closes.
class MeshBuilder {
 public:
  MeshBuilder() { quiet_openmesh(); }
  JoinedMesh::VertexHandle vertex(double x, double y, double z) {
    auto [it, added] = vertices_.emplace(std::array<double, 3>{x, y, z}, JoinedMesh::VertexHandle());
    if (added) it->second = mesh_.add_vertex({x, y, z});
    return it->second;
  }
  // A vertex of its own, joined to no other face.
  JoinedMesh::VertexHandle loose_vertex(const Vec3& p) { return mesh_.add_vertex({p[0], p[1], p[2]}); }
  void add(const std::vector<JoinedMesh::VertexHandle>& face, Surface s) {
    JoinedMesh::FaceHandle f = mesh_.add_face(face);
    if (!f.is_valid()) {
      // A model's mesh need not be manifold: a face that cannot join its neighbours
      // stands alone, so nothing of the model is lost.
      std::vector<JoinedMesh::VertexHandle> own;
      for (auto v : face) {
        const JoinedMesh::Point p = mesh_.point(v);  // a copy: adding a vertex may move the points
        own.push_back(mesh_.add_vertex(p));
      }
      f = mesh_.add_face(own);
    }
    if (f.is_valid()) surfaces_.push_back(s);  // faces are numbered as they are added
  }
  // Walls from `base` up to z: a quad per ring edge, outward (rings run with the inside on
  // their left).
  void walls(const geom::Ring& r, double base, double z) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      geom::Vec2 a = r[i], c = r[(i + 1) % r.size()];
      add({vertex(a.x, a.y, base), vertex(c.x, c.y, base), vertex(c.x, c.y, z), vertex(a.x, a.y, z)}, Surface::Wall);
    }
  }
  // Flat faces over the footprint at height z, facing up or down.
  void cap(const geom::Polygon& footprint, double z, bool down, Surface s) {
    std::vector<geom::Vec2> points(footprint.outer);
    for (const auto& h : footprint.holes) points.insert(points.end(), h.begin(), h.end());
    for (const auto& t : geom::triangulate(footprint)) {
      const geom::Vec2 &p = points[t[0]], &q = points[t[1]], &r = points[t[2]];
      if (down) add({vertex(p.x, p.y, z), vertex(r.x, r.y, z), vertex(q.x, q.y, z)}, s);
      else add({vertex(p.x, p.y, z), vertex(q.x, q.y, z), vertex(r.x, r.y, z)}, s);
    }
  }
  // The mesh, compact: its points and faces in OpenMesh's order, each face's corners as its
  // vertex circulator gives them.
  Mesh take() const {
    Mesh out;
    out.points.reserve(mesh_.n_vertices());
    for (auto v : mesh_.vertices()) {
      const JoinedMesh::Point& p = mesh_.point(v);
      out.points.push_back({p[0], p[1], p[2]});
    }
    std::vector<std::uint32_t> corners;
    for (auto f : mesh_.faces()) {
      corners.clear();
      for (auto v : mesh_.fv_range(f)) corners.push_back(static_cast<std::uint32_t>(v.idx()));
      out.add_face(surfaces_[static_cast<std::size_t>(f.idx())], corners);
    }
    out.shrink();
    return out;
  }
  // What comes next is a mesh of its own, sharing no vertex with what came before.
  void next_piece() { vertices_.clear(); }

 private:
  JoinedMesh mesh_;
  std::vector<Surface> surfaces_;  // by face
  std::map<std::array<double, 3>, JoinedMesh::VertexHandle> vertices_;
};

// A slope's surface class: facing up a roof, facing down a ground, else a wall.
Surface slope_class(const Vec3& p, const Vec3& q, const Vec3& r) {
  const auto [nx, ny, nz] = geom::triangle_normal(p, q, r);
  const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
  return nz > 0.5 * len ? Surface::Roof : nz < -0.5 * len ? Surface::Ground : Surface::Wall;
}

// A library model's triangles joined as MeshBuilder joins them, in the model's own frame.
// OpenMesh's choices (which faces join, which stand alone on vertices of their own) depend
// only on the triangles, so they are the same for every instance of the model: made once,
// then placed (joining each instance's triangles again was most of the 3D meshes' time).
Mesh joined_model(const TriangleMesh& model) {
  MeshBuilder mesh;
  std::vector<JoinedMesh::VertexHandle> handles;
  for (const Vec3& v : model.vertices) handles.push_back(mesh.loose_vertex(v));
  for (const auto& t : model.triangles)
    mesh.add({handles[t[0]], handles[t[1]], handles[t[2]]},
             slope_class(model.vertices[t[0]], model.vertices[t[1]], model.vertices[t[2]]));
  return mesh.take();
}

// The instance's mesh: its foundation, then its model's joined mesh placed (none without one).
Mesh placed_model(const ModelInstance& m, const Mesh* joined) {
  Mesh out;
  // A foundation from the lowest terrain under the model up to where it stands.
  if (m.floor > m.base) {
    MeshBuilder mesh;
    mesh.walls(m.polygon.outer, m.base, m.floor);
    mesh.cap(m.polygon, m.base, true, Surface::Ground);
    mesh.cap(m.polygon, m.floor, false, Surface::Roof);
    out = mesh.take();
  }
  if (!joined) return out;
  // The model's vertices after the foundation's, as they were added to one builder; its
  // faces after the foundation's.
  const auto first = static_cast<std::uint32_t>(out.points.size());
  out.points.reserve(out.points.size() + joined->points.size());
  for (const Vec3& p : joined->points) out.points.push_back(m.placed.apply(p, m.floor));
  std::vector<std::uint32_t> corners;
  for (const Mesh::Face f : joined->faces()) {
    corners.assign(f.corners.begin(), f.corners.end());
    for (std::uint32_t& c : corners) c += first;
    out.add_face(f.surface, corners);
  }
  out.shrink();
  return out;
}

}  // namespace

Mesh model_mesh(const ModelInstance& m, const ModelLibrary* library) {
  if (!library) return placed_model(m, nullptr);
  const Mesh joined = joined_model(library->models[m.placed.model].mesh);
  return placed_model(m, &joined);
}

ModelMeshes::ModelMeshes(const ModelLibrary* library) : library_(library) {
  if (!library) return;
  joined_.resize(library->models.size());
  tbb::parallel_for(std::size_t(0), joined_.size(),
                    [&](std::size_t i) { joined_[i] = joined_model(library->models[i].mesh); });
}

Mesh ModelMeshes::operator()(const ModelInstance& m) const {
  return placed_model(m, library_ ? &joined_[static_cast<std::size_t>(m.placed.model)] : nullptr);
}

namespace {

// A footprint's prism from `base` up to `eaves` (heights in the city) under its roof's faces
// (standing on `floor`), or a flat roof where it has none.
void add_prism(MeshBuilder& mesh, const geom::Polygon& footprint, double base, double eaves,
               const std::vector<geom::Face3>& roof_faces, double floor) {
  mesh.walls(footprint.outer, base, eaves);
  for (const auto& h : footprint.holes) mesh.walls(h, base, eaves);
  mesh.cap(footprint, base, true, Surface::Ground);
  if (roof_faces.empty()) mesh.cap(footprint, eaves, false, Surface::Roof);
  // Pitched roofs: faces rising from the eaves (a gable's upright triangle counts as wall).
  for (const geom::Face3& f : roof_faces) {
    std::vector<JoinedMesh::VertexHandle> face;
    for (const geom::Vec3& v : f) face.push_back(mesh.vertex(v[0], v[1], v[2] + floor));
    mesh.add(face, is_gable(f) ? Surface::Wall : Surface::Roof);
  }
}

// A building:part's prism: from the ground under the building where it stands on it.
void add_part(MeshBuilder& mesh, const Building& b, const BuildingPart& part) {
  add_prism(mesh, part.polygon, part.bottom > 0 ? b.floor + part.bottom : b.base, b.floor + part.eaves, part.roof_faces,
            b.floor);
}

}  // namespace

Mesh building_part_mesh(const Building& b, const BuildingPart& part) {
  MeshBuilder mesh;
  add_part(mesh, b, part);
  return mesh.take();
}

Mesh building_mesh(const Building& b) {
  MeshBuilder mesh;
  if (b.parts.empty()) add_prism(mesh, b.polygon, b.base, b.floor + b.eaves, b.roof_faces, b.floor);
  // Where it maps parts, they are its 3D (OSM's Simple 3D Buildings), each closed on its own.
  for (const BuildingPart& part : b.parts) {
    mesh.next_piece();
    add_part(mesh, b, part);
  }
  return mesh.take();
}

}  // namespace exacity
