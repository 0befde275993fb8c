#include "geom/triangulate.h"

#include <map>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

namespace geom {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, CGAL::Triangulation_face_base_with_info_2<int, K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// The rings of a valid polygon never cross, so no constraint intersection is constructed;
// a vertex shared by a hole and the outer ring is inserted once.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

}  // namespace

std::vector<std::array<int, 3>> triangulate(const Polygon& polygon) { return triangulate(polygon, {}); }

std::vector<std::array<int, 3>> triangulate(const Polygon& polygon, const std::vector<Vec2>& inside) {
  Cdt cdt;
  std::map<std::pair<double, double>, Cdt::Vertex_handle> placed;
  int index = 0;
  auto ring = [&](const Ring& r) {
    std::vector<Cdt::Vertex_handle> vs;
    for (Vec2 p : r) {
      auto [it, added] = placed.emplace(std::make_pair(p.x, p.y), Cdt::Vertex_handle());
      if (added) {
        it->second = cdt.insert(K::Point_2(p.x, p.y));
        it->second->info() = index;
      }
      vs.push_back(it->second);
      ++index;
    }
    for (std::size_t i = 0; i < vs.size(); ++i)
      if (vs[i] != vs[(i + 1) % vs.size()]) cdt.insert_constraint(vs[i], vs[(i + 1) % vs.size()]);
  };
  try {
    ring(polygon.outer);
    for (const Ring& h : polygon.holes) ring(h);
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    return {};  // the rings cross: not a polygon this can cover
  }
  for (Vec2 p : inside) {
    auto [it, added] = placed.emplace(std::make_pair(p.x, p.y), Cdt::Vertex_handle());
    if (added) {
      it->second = cdt.insert(K::Point_2(p.x, p.y));
      it->second->info() = index;
    }
    ++index;
  }

  if (cdt.dimension() < 2) return {};  // every vertex on one line: nothing to cover

  // Faces inside: an odd number of constrained edges away from the infinite face.
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::vector<Cdt::Face_handle> queue{cdt.infinite_face()};
  cdt.infinite_face()->info() = 0;
  std::vector<Cdt::Face_handle> next;
  for (int depth = 0; !queue.empty(); ++depth) {
    while (!queue.empty()) {
      Cdt::Face_handle f = queue.back();
      queue.pop_back();
      for (int i = 0; i < 3; ++i) {
        Cdt::Face_handle g = f->neighbor(i);
        if (g->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          next.push_back(g);
        } else {
          g->info() = depth;
          queue.push_back(g);
        }
      }
    }
    for (auto g : next)
      if (g->info() == -1) g->info() = depth + 1, queue.push_back(g);
    next.clear();
  }
  std::vector<std::array<int, 3>> triangles;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info() % 2 == 1)
      triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return triangles;
}

}  // namespace geom
