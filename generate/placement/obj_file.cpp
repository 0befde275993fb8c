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

// The file's lines, continued lines ("\" at the end) joined, and failing with the file
// and line named.
class ObjLines {
 public:
  ObjLines(std::istream& in, const fs::path& file) : in_(in), file_(file) {}

  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++number_;
    while (!line.empty() && line.back() == '\\') {
      std::string next;
      if (!std::getline(in_, next)) break;
      ++number_;
      line.pop_back();
      line += " " + next;
    }
    return true;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw UserError(file_.string() + " line " + std::to_string(number_) + ": " + what);
  }

 private:
  std::istream& in_;
  const fs::path& file_;
  int number_ = 0;
};

// What an OBJ file declares, as it declares it: indices are still per position, and
// faces may repeat or have no area.
struct ObjContents {
  std::vector<Vec3> positions;
  long texture_coordinates = 0, normals = 0;  // only counted: face corners may point at them
  std::vector<std::vector<int>> faces;        // into positions
  std::vector<int> face_material;             // per face, into material_names
  std::vector<std::string> material_names{"default"};
  std::map<std::string, int> material_index{{"default", 0}};
  std::map<std::string, Vec3> colours;  // from the .mtl libraries, by material name
  int current_material = 0;             // of the faces that follow
};

void parse_vertex(std::istringstream& words, ObjContents& obj, const ObjLines& lines) {
  Vec3 p;
  if (!(words >> p[0] >> p[1] >> p[2]) || !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    lines.fail("a vertex needs three finite coordinates; fix or remove the line");
  obj.positions.push_back(p);
}

[[noreturn]] void not_a_corner(const std::string& corner, const ObjLines& lines) {
  lines.fail("\"" + corner + "\" is not a face corner (v, v/vt, v//vn or v/vt/vn, whole numbers); fix the face");
}

// One index of a face corner, 0-based: 1-based in the file, or negative, counted back from
// the last one read so far (`count` of them).
long resolve_index(const std::string& text, long count, const char* what, const std::string& corner,
                   const ObjLines& lines) {
  std::size_t used = 0;
  long index = 0;
  try {
    index = std::stol(text, &used);
  } catch (const std::exception&) {
  }
  if (used == 0 || used != text.size()) not_a_corner(corner, lines);
  long resolved = index > 0 ? index - 1 : count + index;
  if (index == 0 || resolved < 0 || resolved >= count)
    lines.fail(std::string(what) + " index " + std::to_string(index) + " points to none of the " +
               std::to_string(count) + " read so far; fix the face");
  return resolved;
}

// "v", "v/vt", "v//vn" or "v/vt/vn"; an empty vt or vn ("2//", as some exporters write)
// is none. Returns the position; vt and vn are only checked, Exacity keeps neither.
int parse_corner(const std::string& corner, const ObjContents& obj, const ObjLines& lines) {
  std::vector<std::string> parts{""};
  for (char c : corner) c == '/' ? parts.push_back("") : void(parts.back() += c);
  if (parts.size() > 3) not_a_corner(corner, lines);
  const int position =
      static_cast<int>(resolve_index(parts[0], static_cast<long>(obj.positions.size()), "vertex", corner, lines));
  if (parts.size() >= 2 && !parts[1].empty())
    resolve_index(parts[1], obj.texture_coordinates, "texture coordinate", corner, lines);
  if (parts.size() == 3 && !parts[2].empty()) resolve_index(parts[2], obj.normals, "normal", corner, lines);
  return position;
}

void parse_face(std::istringstream& words, ObjContents& obj, const ObjLines& lines) {
  std::vector<int> face;
  std::string corner;
  while (words >> corner) face.push_back(parse_corner(corner, obj, lines));
  if (face.size() < 3) lines.fail("a face needs at least 3 corners; use \"l\" for a line or remove it");
  obj.faces.push_back(std::move(face));
  obj.face_material.push_back(obj.current_material);
}

void parse_usemtl(std::istringstream& words, ObjContents& obj) {
  std::string name;
  std::getline(words >> std::ws, name);
  while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
  auto [it, added] = obj.material_index.emplace(name, static_cast<int>(obj.material_names.size()));
  if (added) obj.material_names.push_back(name);
  obj.current_material = it->second;
}

ObjContents parse_obj(std::istream& in, const fs::path& file) {
  ObjContents obj;
  ObjLines lines(in, file);
  std::string line;
  while (lines.next(line)) {
    std::istringstream words(line);
    std::string key;
    if (!(words >> key) || key[0] == '#') continue;
    if (key == "v") {
      parse_vertex(words, obj, lines);
    } else if (key == "vt" || key == "vn") {
      ++(key == "vt" ? obj.texture_coordinates : obj.normals);
    } else if (key == "f") {
      parse_face(words, obj, lines);
    } else if (key == "usemtl") {
      parse_usemtl(words, obj);
    } else if (key == "mtllib") {
      std::string name;
      while (words >> name) read_mtl(file.parent_path() / name, obj.colours);
    }
    // o, g, s, l, p and the rest carry nothing Exacity uses.
  }
  return obj;
}

// One vertex per position, so faces doubled over copied vertices are found; returns each
// position's vertex.
std::vector<int> weld_positions(const std::vector<Vec3>& positions, std::vector<Vec3>& vertices) {
  std::map<Vec3, int> welded;
  std::vector<int> vertex_of(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    auto [it, added] = welded.emplace(positions[i], static_cast<int>(vertices.size()));
    if (added) vertices.push_back(positions[i]);
    vertex_of[i] = it->second;
  }
  return vertex_of;
}

// A face over welded vertices, without the corners welding made repeat.
std::vector<int> welded_face(const std::vector<int>& positions, const std::vector<int>& vertex_of) {
  std::vector<int> face;
  for (int i : positions)
    if (face.empty() || vertex_of[i] != face.back()) face.push_back(vertex_of[i]);
  while (face.size() > 1 && face.front() == face.back()) face.pop_back();
  return face;
}

bool has_no_area(const std::vector<Vec3>& vertices, const std::array<int, 3>& t) {
  Vec3 n = cross(sub(vertices[t[1]], vertices[t[0]]), sub(vertices[t[2]], vertices[t[0]]));
  return n[0] == 0 && n[1] == 0 && n[2] == 0;
}

// Whether no triangle over the same three vertices, in either winding, came before.
bool first_of_its_vertices(std::set<std::array<int, 3>>& seen, const std::array<int, 3>& t) {
  std::array<int, 3> key = t;
  std::sort(key.begin(), key.end());
  return seen.insert(key).second;
}

// The mesh's material for one of the file's, added when a triangle first uses it: the
// mesh keeps only materials it uses, in the order they are first used.
int mesh_material(const ObjContents& obj, int material, std::vector<int>& used_material, TriangleMesh& mesh) {
  int& m = used_material[material];
  if (m < 0) {
    m = static_cast<int>(mesh.materials.size());
    MeshMaterial mat{obj.material_names[material], {}};
    if (auto c = obj.colours.find(mat.name); c != obj.colours.end()) mat.colour = c->second;
    mesh.materials.push_back(mat);
  }
  return m;
}

// The faces' triangles over the welded vertices, leaving out those with no area and those
// that repeat another.
void add_triangles(const ObjContents& obj, const std::vector<int>& vertex_of, TriangleMesh& mesh) {
  std::set<std::array<int, 3>> seen;
  std::vector<int> used_material(obj.material_names.size(), -1);
  for (std::size_t f = 0; f < obj.faces.size(); ++f) {
    const std::vector<int> face = welded_face(obj.faces[f], vertex_of);
    if (face.size() < 3) continue;
    std::vector<Vec3> corners;
    for (int i : face) corners.push_back(mesh.vertices[i]);
    for (auto t : triangulate_planar(corners)) {
      for (int& i : t) i = face[i];
      if (has_no_area(mesh.vertices, t) || !first_of_its_vertices(seen, t)) continue;
      const int m = mesh_material(obj, obj.face_material[f], used_material, mesh);
      mesh.triangles.push_back(t);
      mesh.material.push_back(m);
    }
  }
}

// Keeps only the vertices faces use: stray ones would stretch the model's bounds.
void drop_unused_vertices(TriangleMesh& mesh) {
  std::vector<int> renumber(mesh.vertices.size(), -1);
  std::vector<Vec3> used;
  for (auto& t : mesh.triangles)
    for (int& i : t) {
      if (renumber[i] < 0) renumber[i] = static_cast<int>(used.size()), used.push_back(mesh.vertices[i]);
      i = renumber[i];
    }
  mesh.vertices = std::move(used);
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
  const ObjContents obj = parse_obj(in, file);
  TriangleMesh mesh;
  const std::vector<int> vertex_of = weld_positions(obj.positions, mesh.vertices);
  add_triangles(obj, vertex_of, mesh);
  if (mesh.triangles.empty())
    throw UserError(file.string() + ": no faces with area; a model needs at least one polygon face (\"f\" lines)");
  drop_unused_vertices(mesh);
  return mesh;
}

}  // namespace exacity
