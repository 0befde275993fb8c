#include "generate/building_mesh.h"

#include "geom/triangulate.h"

namespace exacity {

OpenMesh::FPropHandleT<int> surface_property(const Mesh& mesh) {
  OpenMesh::FPropHandleT<int> surface;
  if (!mesh.get_property_handle(surface, "surface")) throw std::logic_error("mesh has no surface property");
  return surface;
}

Mesh building_mesh(const Building& b) {
  Mesh mesh;
  OpenMesh::FPropHandleT<int> surface;
  mesh.add_property(surface, "surface");
  // Vertices: every ring vertex at the ground and at the roof, outer ring first.
  std::vector<geom::Vec2> points(b.polygon.outer);
  for (const auto& h : b.polygon.holes) points.insert(points.end(), h.begin(), h.end());
  std::vector<Mesh::VertexHandle> ground, roof;
  for (geom::Vec2 p : points) ground.push_back(mesh.add_vertex({p.x, p.y, 0}));
  for (geom::Vec2 p : points) roof.push_back(mesh.add_vertex({p.x, p.y, b.height}));
  auto add = [&](std::vector<Mesh::VertexHandle> face, Surface s) {
    Mesh::FaceHandle f = mesh.add_face(face);
    if (f.is_valid()) mesh.property(surface, f) = static_cast<int>(s);
  };
  // Walls: a quad per ring edge, outward (rings run with the inside on their left).
  int first = 0;
  auto walls = [&](const geom::Ring& r) {
    for (int i = 0, n = static_cast<int>(r.size()); i < n; ++i) {
      int a = first + i, c = first + (i + 1) % n;
      add({ground[a], ground[c], roof[c], roof[a]}, Surface::Wall);
    }
    first += static_cast<int>(r.size());
  };
  walls(b.polygon.outer);
  for (const auto& h : b.polygon.holes) walls(h);
  for (const auto& t : geom::triangulate(b.polygon)) {
    add({roof[t[0]], roof[t[1]], roof[t[2]]}, Surface::Roof);
    add({ground[t[0]], ground[t[2]], ground[t[1]]}, Surface::Ground);
  }
  return mesh;
}

}  // namespace exacity
