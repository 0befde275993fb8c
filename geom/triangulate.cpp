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

using Placed = std::map<std::pair<double, double>, Cdt::Vertex_handle>;

// A point met again (a vertex a hole shares with the outer ring) keeps its first vertex;
// `index` still counts it, so indices follow the input's order.
Cdt::Vertex_handle place(Cdt& cdt, Placed& placed, Vec2 p, int index) {
  auto [it, added] = placed.emplace(std::make_pair(p.x, p.y), Cdt::Vertex_handle());
  if (added) {
    it->second = cdt.insert(K::Point_2(p.x, p.y));
    it->second->info() = index;
  }
  return it->second;
}

void insert_ring(Cdt& cdt, Placed& placed, const Ring& r, int& index) {
  std::vector<Cdt::Vertex_handle> vs;
  for (Vec2 p : r) {
    vs.push_back(place(cdt, placed, p, index));
    ++index;
  }
  for (std::size_t i = 0; i < vs.size(); ++i)
    if (vs[i] != vs[(i + 1) % vs.size()]) cdt.insert_constraint(vs[i], vs[(i + 1) % vs.size()]);
}

// Sets each face's info to how many constrained edges lie between it and the infinite face.
void mark_depths(Cdt& cdt) {
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
}

// Faces inside: an odd number of constrained edges away from the infinite face.
std::vector<std::array<int, 3>> inside_faces(const Cdt& cdt) {
  std::vector<std::array<int, 3>> triangles;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info() % 2 == 1)
      triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return triangles;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate(const Polygon& polygon) { return triangulate(polygon, {}); }

std::vector<std::array<int, 3>> triangulate(const Polygon& polygon, const std::vector<Vec2>& inside) {
  Cdt cdt;
  Placed placed;
  int index = 0;
  try {
    insert_ring(cdt, placed, polygon.outer, index);
    for (const Ring& h : polygon.holes) insert_ring(cdt, placed, h, index);
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    return {};  // the rings cross: not a polygon this can cover
  }
  for (Vec2 p : inside) {
    place(cdt, placed, p, index);
    ++index;
  }
  if (cdt.dimension() < 2) return {};  // every vertex on one line: nothing to cover
  mark_depths(cdt);
  return inside_faces(cdt);
}

}  // namespace geom
