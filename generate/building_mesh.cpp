#include "generate/building_mesh.h"

#include <cmath>
#include <map>

#include <tbb/parallel_for.h>

#include "geom/triangulate.h"

namespace exacity {

namespace {

// A gable: an upright triangle, all its points on one vertical plane (its footprint is a line).
bool is_gable(const geom::Face3& f) {
  if (f.size() != 3) return false;
  double cross = (f[1][0] - f[0][0]) * (f[2][1] - f[0][1]) - (f[1][1] - f[0][1]) * (f[2][0] - f[0][0]);
  double scale = std::hypot(f[1][0] - f[0][0], f[1][1] - f[0][1]) * std::hypot(f[2][0] - f[0][0], f[2][1] - f[0][1]);
  return std::abs(cross) <= 1e-9 * scale;
}

}  // namespace

OpenMesh::FPropHandleT<int> surface_property(const Mesh& mesh) {
  OpenMesh::FPropHandleT<int> surface;
  if (!mesh.get_property_handle(surface, "surface")) throw std::logic_error("mesh has no surface property");
  return surface;
}

std::vector<Mesh> building_meshes(const std::vector<Building>& buildings) {
  std::vector<Mesh> meshes(buildings.size());
  tbb::parallel_for(std::size_t(0), buildings.size(), [&](std::size_t i) { meshes[i] = building_mesh(buildings[i]); });
  return meshes;
}

Mesh building_mesh(const Building& b) {
  Mesh mesh;
  OpenMesh::FPropHandleT<int> surface;
  mesh.add_property(surface, "surface");
  // One vertex per distinct point, so faces share their edges and the mesh closes.
  std::map<std::array<double, 3>, Mesh::VertexHandle> vertices;
  auto vertex = [&](double x, double y, double z) {
    auto [it, added] = vertices.emplace(std::array<double, 3>{x, y, z}, Mesh::VertexHandle());
    if (added) it->second = mesh.add_vertex({x, y, z});
    return it->second;
  };
  auto add = [&](const std::vector<Mesh::VertexHandle>& face, Surface s) {
    Mesh::FaceHandle f = mesh.add_face(face);
    if (f.is_valid()) mesh.property(surface, f) = static_cast<int>(s);
  };
  // Walls up to the eaves: a quad per ring edge, outward (rings run with the inside on
  // their left).
  auto walls = [&](const geom::Ring& r) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      geom::Vec2 a = r[i], c = r[(i + 1) % r.size()];
      add({vertex(a.x, a.y, 0), vertex(c.x, c.y, 0), vertex(c.x, c.y, b.eaves), vertex(a.x, a.y, b.eaves)}, Surface::Wall);
    }
  };
  walls(b.polygon.outer);
  for (const auto& h : b.polygon.holes) walls(h);
  std::vector<geom::Vec2> points(b.polygon.outer);
  for (const auto& h : b.polygon.holes) points.insert(points.end(), h.begin(), h.end());
  for (const auto& t : geom::triangulate(b.polygon)) {
    const geom::Vec2 &p = points[t[0]], &q = points[t[1]], &r = points[t[2]];
    add({vertex(p.x, p.y, 0), vertex(r.x, r.y, 0), vertex(q.x, q.y, 0)}, Surface::Ground);
    if (b.roof_faces.empty()) add({vertex(p.x, p.y, b.eaves), vertex(q.x, q.y, b.eaves), vertex(r.x, r.y, b.eaves)}, Surface::Roof);
  }
  // Pitched roofs: faces rising from the eaves (a gable's upright triangle counts as wall).
  for (const geom::Face3& f : b.roof_faces) {
    std::vector<Mesh::VertexHandle> face;
    for (const geom::Vec3& v : f) face.push_back(vertex(v[0], v[1], v[2]));
    add(face, is_gable(f) ? Surface::Wall : Surface::Roof);
  }
  return mesh;
}

}  // namespace exacity
