#include "generate/placement/obj_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "generate/errors.h"
#include "geom/triangulate.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Diffuse colours by material name; a missing or unreadable library leaves the defaults.
void read_mtl(const fs::path& file, std::map<std::string, Vec3>& colours) {
  std::ifstream in(file);
  std::string line, current;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "newmtl") {
      std::getline(words >> std::ws, current);
      while (!current.empty() && std::isspace(static_cast<unsigned char>(current.back()))) current.pop_back();
    } else if (key == "Kd" && !current.empty()) {
      Vec3 c;
      if (words >> c[0] >> c[1] >> c[2]) colours[current] = {std::clamp(c[0], 0.0, 1.0), std::clamp(c[1], 0.0, 1.0), std::clamp(c[2], 0.0, 1.0)};
    }
  }
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_planar(const std::vector<Vec3>& v) {
  const int n = static_cast<int>(v.size());
  if (n == 3) return {{0, 1, 2}};
  Vec3 normal{0, 0, 0};  // Newell's normal
  for (int i = 0; i < n; ++i) {
    const Vec3 &a = v[i], &b = v[(i + 1) % n];
    normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
    normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
    normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  int drop = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(normal[k]) > std::abs(normal[drop])) drop = k;
  const int ax = (drop + 1) % 3, ay = (drop + 2) % 3;
  const bool flip = normal[drop] < 0;
  geom::Polygon projected;
  for (int i = 0; i < n; ++i) {
    int k = flip ? n - 1 - i : i;
    projected.outer.push_back({v[k][ax], v[k][ay]});
  }
  std::vector<std::array<int, 3>> out;
  auto tris = geom::triangulate(projected);
  if (static_cast<int>(tris.size()) + 2 != n) {  // not a simple polygon: a fan is the best guess
    for (int i = 1; i + 1 < n; ++i) out.push_back({0, i, i + 1});
    return out;
  }
  for (const auto& t : tris) {
    std::array<int, 3> tri;
    for (int j = 0; j < 3; ++j) tri[j] = flip ? n - 1 - t[j] : t[j];
    if (flip) std::swap(tri[1], tri[2]);
    out.push_back(tri);
  }
  return out;
}

TriangleMesh read_obj(const fs::path& file) {
  if (fs::is_directory(file))
    throw UserError(file.string() + ": is a folder, not a model file; name an .obj file in the model library");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw UserError(file.string() + ": cannot read this model file; check the path in the model library");
  return read_obj(in, file);
}

TriangleMesh read_obj(std::istream& in, const fs::path& file) {
  std::vector<Vec3> positions;
  long texture_coordinates = 0, normals = 0;
  std::vector<std::vector<int>> faces;
  std::vector<int> face_material;
  std::vector<std::string> material_names{"default"};
  std::map<std::string, int> material_index{{"default", 0}};
  std::map<std::string, Vec3> colours;
  int current = 0;
  std::string line;
  int line_number = 0;
  auto fail = [&](const std::string& what) {
    throw UserError(file.string() + " line " + std::to_string(line_number) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++line_number;
    while (!line.empty() && line.back() == '\\') {  // a continued line
      std::string next;
      if (!std::getline(in, next)) break;
      ++line_number;
      line.pop_back();
      line += " " + next;
    }
    std::istringstream words(line);
    std::string key;
    if (!(words >> key) || key[0] == '#') continue;
    if (key == "v") {
      Vec3 p;
      if (!(words >> p[0] >> p[1] >> p[2]) || !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        fail("a vertex needs three finite coordinates; fix or remove the line");
      positions.push_back(p);
    } else if (key == "vt" || key == "vn") {
      ++(key == "vt" ? texture_coordinates : normals);
    } else if (key == "f") {
      std::vector<int> face;
      std::string corner;
      while (words >> corner) {
        // "v", "v/vt", "v//vn" or "v/vt/vn", each index 1-based, or negative: counted back
        // from the last one read so far. An empty vt or vn ("2//", as some exporters write) is none.
        auto not_a_corner = [&] {
          fail("\"" + corner + "\" is not a face corner (v, v/vt, v//vn or v/vt/vn, whole numbers); fix the face");
        };
        auto resolve = [&](const std::string& text, long count, const char* what) {
          std::size_t used = 0;
          long index = 0;
          try {
            index = std::stol(text, &used);
          } catch (const std::exception&) {
          }
          if (used == 0 || used != text.size()) not_a_corner();
          long resolved = index > 0 ? index - 1 : count + index;
          if (index == 0 || resolved < 0 || resolved >= count)
            fail(std::string(what) + " index " + std::to_string(index) + " points to none of the " + std::to_string(count) +
                 " read so far; fix the face");
          return resolved;
        };
        std::vector<std::string> parts{""};
        for (char c : corner) c == '/' ? parts.push_back("") : void(parts.back() += c);
        if (parts.size() > 3) not_a_corner();
        face.push_back(static_cast<int>(resolve(parts[0], static_cast<long>(positions.size()), "vertex")));
        if (parts.size() >= 2 && !parts[1].empty()) resolve(parts[1], texture_coordinates, "texture coordinate");
        if (parts.size() == 3 && !parts[2].empty()) resolve(parts[2], normals, "normal");
      }
      if (face.size() < 3) fail("a face needs at least 3 corners; use \"l\" for a line or remove it");
      faces.push_back(std::move(face));
      face_material.push_back(current);
    } else if (key == "usemtl") {
      std::string name;
      std::getline(words >> std::ws, name);
      while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
      auto [it, added] = material_index.emplace(name, static_cast<int>(material_names.size()));
      if (added) material_names.push_back(name);
      current = it->second;
    } else if (key == "mtllib") {
      std::string name;
      while (words >> name) read_mtl(file.parent_path() / name, colours);
    }
    // o, g, s, l, p and the rest carry nothing Exacity uses.
  }

  TriangleMesh mesh;
  // One vertex per position, so faces doubled over copied vertices are found below.
  std::map<Vec3, int> welded;
  std::vector<int> vertex_of(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    auto [it, added] = welded.emplace(positions[i], static_cast<int>(mesh.vertices.size()));
    if (added) mesh.vertices.push_back(positions[i]);
    vertex_of[i] = it->second;
  }
  std::set<std::array<int, 3>> seen;
  std::vector<int> used_material(material_names.size(), -1);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::vector<int> face;
    for (int i : faces[f])
      if (face.empty() || vertex_of[i] != face.back()) face.push_back(vertex_of[i]);
    while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    if (face.size() < 3) continue;
    std::vector<Vec3> corners;
    for (int i : face) corners.push_back(mesh.vertices[i]);
    for (auto t : triangulate_planar(corners)) {
      for (int& i : t) i = face[i];
      Vec3 n = cross(sub(mesh.vertices[t[1]], mesh.vertices[t[0]]), sub(mesh.vertices[t[2]], mesh.vertices[t[0]]));
      if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
      std::array<int, 3> key = t;
      std::sort(key.begin(), key.end());
      if (!seen.insert(key).second) continue;
      int& m = used_material[face_material[f]];
      if (m < 0) {
        m = static_cast<int>(mesh.materials.size());
        MeshMaterial mat{material_names[face_material[f]], {}};
        if (auto c = colours.find(mat.name); c != colours.end()) mat.colour = c->second;
        mesh.materials.push_back(mat);
      }
      mesh.triangles.push_back(t);
      mesh.material.push_back(m);
    }
  }
  if (mesh.triangles.empty())
    throw UserError(file.string() + ": no faces with area; a model needs at least one polygon face (\"f\" lines)");
  // Keep only the vertices faces use: stray ones would stretch the model's bounds.
  std::vector<int> renumber(mesh.vertices.size(), -1);
  std::vector<Vec3> used;
  for (auto& t : mesh.triangles)
    for (int& i : t) {
      if (renumber[i] < 0) renumber[i] = static_cast<int>(used.size()), used.push_back(mesh.vertices[i]);
      i = renumber[i];
    }
  mesh.vertices = std::move(used);
  return mesh;
}

}  // namespace exacity
