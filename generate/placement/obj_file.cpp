#include "generate/placement/obj_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "generate/errors.h"
#include "generate/input_file.h"
#include "geom/triangulate.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

// An .mtl's map_Kd line after the keyword: options, then the file name, which is the rest of
// the line (names may hold spaces; "\\" between parts is read as "/").
struct TextureMap {
  std::string file;
  Uv scale{1, 1}, offset{0, 0};
  bool clamp = false;
};

// Throws the reason when an option is not one Exacity reads: -s, -o and -clamp change where
// the image lies; the others (blending, colour correction, channels) would change its look
// and are refused rather than ignored.
TextureMap parse_texture_map(const std::string& rest) {
  TextureMap map;
  std::size_t at = 0;
  auto word = [&]() {
    while (at < rest.size() && std::isspace(static_cast<unsigned char>(rest[at]))) ++at;
    const std::size_t start = at;
    while (at < rest.size() && !std::isspace(static_cast<unsigned char>(rest[at]))) ++at;
    return rest.substr(start, at - start);
  };
  auto number = [&](double& out) {
    const std::size_t before = at;
    const std::string w = word();
    char* end = nullptr;
    const double v = w.empty() ? 0 : std::strtod(w.c_str(), &end);
    if (w.empty() || *end != '\0' || !std::isfinite(v)) return at = before, false;
    out = v;
    return true;
  };
  for (;;) {
    const std::size_t before = at;
    const std::string option = word();
    if (option.size() < 2 || option[0] != '-' || std::isdigit(static_cast<unsigned char>(option[1]))) {
      at = before;
      break;
    }
    if (option == "-s" || option == "-o") {
      Uv& uv = option == "-s" ? map.scale : map.offset;
      double w = 0;
      if (!number(uv[0])) throw std::invalid_argument("map_Kd " + option + " needs numbers (u [v [w]])");
      if (!number(uv[1])) uv[1] = option == "-s" ? uv[0] : 0;
      number(w);
    } else if (option == "-clamp") {
      const std::string v = word();
      if (v != "on" && v != "off") throw std::invalid_argument("map_Kd -clamp takes on or off");
      map.clamp = v == "on";
    } else {
      throw std::invalid_argument("map_Kd option " + option +
                                  " is not read by Exacity (only -s, -o and -clamp); remove it");
    }
  }
  while (at < rest.size() && std::isspace(static_cast<unsigned char>(rest[at]))) ++at;
  map.file = rest.substr(at);
  while (!map.file.empty() && std::isspace(static_cast<unsigned char>(map.file.back()))) map.file.pop_back();
  std::replace(map.file.begin(), map.file.end(), '\\', '/');
  if (map.file.empty()) throw std::invalid_argument("map_Kd names no file; give the image's name after map_Kd");
  return map;
}

// What an .mtl says of one material.
struct MtlEntry {
  std::optional<Vec3> colour;
  std::shared_ptr<const TextureImage> texture;
  TextureMap map;
};

constexpr const char* kOutsideFix =
    "; keep an OBJ's MTL and texture files in its library's folder (an OBJ outside it: its own folder) or below";

// Diffuse colours and textures by material name; a missing library leaves the defaults, one
// that is not a regular file or is too large, and a texture that is missing or unreadable,
// are refused. Textures must lie in `within` unless it is empty.
void read_mtl(const fs::path& file, const std::string& named_by, TextureImages& textures,
              std::map<std::string, MtlEntry>& entries, const fs::path& within) {
  std::error_code ec;
  if (!fs::exists(file, ec)) return;
  std::istringstream in(read_input(file, kMaxSettingsFileBytes, "the material library " + named_by + " names",
                                   "name an .mtl file in the mtllib line"));
  std::string line, current;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "newmtl") {
      std::getline(words >> std::ws, current);
      while (!current.empty() && std::isspace(static_cast<unsigned char>(current.back()))) current.pop_back();
    } else if (key == "Kd" && !current.empty()) {
      Vec3 c;
      if (words >> c[0] >> c[1] >> c[2])
        entries[current].colour =
            Vec3{std::clamp(c[0], 0.0, 1.0), std::clamp(c[1], 0.0, 1.0), std::clamp(c[2], 0.0, 1.0)};
    } else if (key == "map_Kd" && !current.empty()) {
      const std::string where = file.string() + " line " + std::to_string(number);
      std::string rest;
      std::getline(words, rest);
      MtlEntry& e = entries[current];
      try {
        e.map = parse_texture_map(rest);
      } catch (const std::invalid_argument& why) {
        throw UserError(where + ": " + why.what());
      }
      const fs::path image = file.parent_path() / e.map.file;
      if (!within.empty() && !lies_within(image, within))
        throw UserError(where + ": map_Kd " + e.map.file + " lies outside " + within.string() + kOutsideFix);
      e.texture = textures.read(image, where);
    }
  }
}

// The names an mtllib line gives: its rest as one name when a file has it (names may hold
// spaces), else each word.
std::vector<std::string> mtllib_names(const std::string& rest, const fs::path& folder) {
  std::string whole = rest;
  while (!whole.empty() && std::isspace(static_cast<unsigned char>(whole.front()))) whole.erase(whole.begin());
  while (!whole.empty() && std::isspace(static_cast<unsigned char>(whole.back()))) whole.pop_back();
  if (whole.find(' ') != std::string::npos && fs::is_regular_file(folder / whole)) return {whole};
  std::istringstream words(rest);
  std::vector<std::string> names;
  for (std::string name; words >> name;) names.push_back(name);
  return names;
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

  std::string where() const { return file_.string() + " line " + std::to_string(number_); }
  [[noreturn]] void fail(const std::string& what) const { throw UserError(where() + ": " + what); }

 private:
  std::istream& in_;
  const fs::path& file_;
  int number_ = 0;
};

// What an OBJ file declares, as it declares it: indices are still per position, and
// faces may repeat or have no area.
struct ObjContents {
  std::vector<Vec3> positions;
  std::vector<Uv> texture_coordinates;
  long normals = 0;                       // only counted: face corners may point at them
  std::vector<std::vector<int>> faces;    // into positions
  std::vector<std::vector<int>> face_uv;  // per face corner, into texture_coordinates; -1 for none
  std::vector<int> face_material;         // per face, into material_names
  std::vector<std::string> material_names{"default"};
  std::map<std::string, int> material_index{{"default", 0}};
  std::map<std::string, MtlEntry> mtl;  // from the .mtl libraries, by material name
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

void parse_texture_coordinate(std::istringstream& words, ObjContents& obj, const ObjLines& lines) {
  Uv uv{0, 0};
  if (!(words >> uv[0]) || !std::isfinite(uv[0]))
    lines.fail("a texture coordinate needs a finite u; fix or remove the line");
  if (!(words >> uv[1])) uv[1] = 0;  // "vt u" alone: v is 0
  if (!std::isfinite(uv[1])) lines.fail("a texture coordinate needs a finite v; fix or remove the line");
  obj.texture_coordinates.push_back(uv);
}

// "v", "v/vt", "v//vn" or "v/vt/vn"; an empty vt or vn ("2//", as some exporters write)
// is none. Returns the position and the texture coordinate (-1 for none); vn is only
// checked, Exacity keeps no normals.
std::pair<int, int> parse_corner(const std::string& corner, const ObjContents& obj, const ObjLines& lines) {
  std::vector<std::string> parts{""};
  for (char c : corner) c == '/' ? parts.push_back("") : void(parts.back() += c);
  if (parts.size() > 3) not_a_corner(corner, lines);
  const int position =
      static_cast<int>(resolve_index(parts[0], static_cast<long>(obj.positions.size()), "vertex", corner, lines));
  int uv = -1;
  if (parts.size() >= 2 && !parts[1].empty())
    uv = static_cast<int>(resolve_index(parts[1], static_cast<long>(obj.texture_coordinates.size()),
                                        "texture coordinate", corner, lines));
  if (parts.size() == 3 && !parts[2].empty()) resolve_index(parts[2], obj.normals, "normal", corner, lines);
  return {position, uv};
}

void parse_face(std::istringstream& words, ObjContents& obj, const ObjLines& lines) {
  std::vector<int> face, uv;
  std::string corner;
  while (words >> corner) {
    const auto [p, t] = parse_corner(corner, obj, lines);
    face.push_back(p), uv.push_back(t);
  }
  if (face.size() < 3) lines.fail("a face needs at least 3 corners; use \"l\" for a line or remove it");
  obj.faces.push_back(std::move(face));
  obj.face_uv.push_back(std::move(uv));
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

ObjContents parse_obj(std::istream& in, const fs::path& file, TextureImages& textures, const fs::path& within) {
  ObjContents obj;
  ObjLines lines(in, file);
  std::string line;
  while (lines.next(line)) {
    std::istringstream words(line);
    std::string key;
    if (!(words >> key) || key[0] == '#') continue;
    if (key == "v") {
      parse_vertex(words, obj, lines);
    } else if (key == "vt") {
      parse_texture_coordinate(words, obj, lines);
    } else if (key == "vn") {
      ++obj.normals;
    } else if (key == "f") {
      parse_face(words, obj, lines);
    } else if (key == "usemtl") {
      parse_usemtl(words, obj);
    } else if (key == "mtllib") {
      std::string rest;
      std::getline(words, rest);
      for (const std::string& name : mtllib_names(rest, file.parent_path())) {
        const fs::path mtl = file.parent_path() / name;
        if (!within.empty() && !lies_within(mtl, within))
          lines.fail("mtllib " + name + " lies outside " + within.string() + kOutsideFix);
        read_mtl(mtl, lines.where(), textures, obj.mtl, within);
      }
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

// A face over welded vertices, without the corners welding made repeat: the vertices and
// which of the file's corners each is.
std::pair<std::vector<int>, std::vector<int>> welded_face(const std::vector<int>& positions,
                                                          const std::vector<int>& vertex_of) {
  std::vector<int> face, corner;
  for (std::size_t k = 0; k < positions.size(); ++k)
    if (face.empty() || vertex_of[positions[k]] != face.back())
      face.push_back(vertex_of[positions[k]]), corner.push_back(static_cast<int>(k));
  while (face.size() > 1 && face.front() == face.back()) face.pop_back(), corner.pop_back();
  return {face, corner};
}

bool has_no_area(const std::vector<Vec3>& vertices, const std::array<int, 3>& t) {
  const Vec3 n = geom::triangle_normal(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  return n[0] == 0 && n[1] == 0 && n[2] == 0;
}

// Whether no triangle over the same three vertices, in either winding, came before.
bool first_of_its_vertices(std::set<std::array<int, 3>>& seen, const std::array<int, 3>& t) {
  std::array<int, 3> key = t;
  std::sort(key.begin(), key.end());
  return seen.insert(key).second;
}

// The mesh's material for one of the file's, added when a triangle first uses it: the
// mesh keeps only materials it uses, in the order they are first used. A textured
// material's faces without texture coordinates get an untextured copy of it.
int mesh_material(const ObjContents& obj, int material, bool has_uv, std::vector<int>& used_material,
                  TriangleMesh& mesh) {
  int& m = used_material[2 * material + (has_uv ? 1 : 0)];
  if (m < 0) {
    m = static_cast<int>(mesh.materials.size());
    MeshMaterial mat{obj.material_names[material], {}, nullptr, false};
    if (auto e = obj.mtl.find(mat.name); e != obj.mtl.end()) {
      // Without Kd a texture shows as it is; an untextured material keeps the grey default.
      if (e->second.colour)
        mat.colour = *e->second.colour;
      else if (e->second.texture)
        mat.colour = {1, 1, 1};
      if (e->second.texture && has_uv)
        mat.texture = e->second.texture, mat.clamp = e->second.map.clamp;
      else if (e->second.texture)
        mat.name += "_untextured";
    }
    mesh.materials.push_back(mat);
  }
  return m;
}

// The faces' triangles over the welded vertices, leaving out those with no area and those
// that repeat another; with their corners' texture coordinates where the material has a
// texture (map_Kd's -s and -o applied).
void add_triangles(const ObjContents& obj, const std::vector<int>& vertex_of, TriangleMesh& mesh) {
  std::set<std::array<int, 3>> seen;
  std::vector<int> used_material(2 * obj.material_names.size(), -1);
  for (std::size_t f = 0; f < obj.faces.size(); ++f) {
    const auto [face, corner] = welded_face(obj.faces[f], vertex_of);
    if (face.size() < 3) continue;
    const std::string& material_name = obj.material_names[obj.face_material[f]];
    const auto entry = obj.mtl.find(material_name);
    const MtlEntry* mtl = entry == obj.mtl.end() || !entry->second.texture ? nullptr : &entry->second;
    const bool has_uv = std::none_of(corner.begin(), corner.end(), [&](int k) { return obj.face_uv[f][k] < 0; });
    std::vector<Vec3> corners;
    for (int i : face) corners.push_back(mesh.vertices[i]);
    for (auto t : triangulate_planar(corners)) {
      std::array<int, 3> vertex;
      for (int k = 0; k < 3; ++k) vertex[k] = face[t[k]];
      if (has_no_area(mesh.vertices, vertex) || !first_of_its_vertices(seen, vertex)) continue;
      const int m = mesh_material(obj, obj.face_material[f], has_uv, used_material, mesh);
      mesh.triangles.push_back(vertex);
      mesh.material.push_back(m);
      std::array<Uv, 3> uv{};
      if (mtl && has_uv)
        for (int k = 0; k < 3; ++k) {
          const Uv& c = obj.texture_coordinates[obj.face_uv[f][corner[t[k]]]];
          uv[k] = {c[0] * mtl->map.scale[0] + mtl->map.offset[0], c[1] * mtl->map.scale[1] + mtl->map.offset[1]};
        }
      mesh.uv.push_back(uv);
    }
  }
  const bool textured = std::any_of(mesh.materials.begin(), mesh.materials.end(),
                                    [](const MeshMaterial& m) { return m.texture != nullptr; });
  if (!textured) mesh.uv.clear();
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

// What follows `key` on each line of `file` that starts with it; none when the file cannot
// be read (its reader says why).
std::vector<std::string> rests_after(const fs::path& file, const std::string& key) {
  std::vector<std::string> rests;
  std::string text, why;
  if (!read_input(file, kMaxDataFileBytes, text, why)) return rests;
  std::istringstream in(std::move(text));
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string first, rest;
    if (!(words >> first) || first != key) continue;
    std::getline(words, rest);
    rests.push_back(std::move(rest));
  }
  return rests;
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

std::vector<std::string> texture_files(const fs::path& mtl) {
  std::vector<std::string> names;
  for (const std::string& rest : rests_after(mtl, "map_Kd")) try {
      names.push_back(parse_texture_map(rest).file);
    } catch (const std::invalid_argument&) {
    }
  return names;
}

std::vector<std::string> material_files(const fs::path& obj) {
  std::vector<std::string> names;
  for (const std::string& rest : rests_after(obj, "mtllib"))
    for (std::string& name : mtllib_names(rest, obj.parent_path())) names.push_back(std::move(name));
  return names;
}

TriangleMesh read_obj(const fs::path& file, TextureImages* textures, const fs::path& within) {
  std::istringstream in(read_input(file, kMaxDataFileBytes, "the model file",
                                   "name an .obj file in the model library"));
  return read_obj(in, file, textures, within);
}

TriangleMesh read_obj(std::istream& in, const fs::path& file, TextureImages* textures, const fs::path& within) {
  TextureImages own;
  const ObjContents obj = parse_obj(in, file, textures ? *textures : own, within);
  TriangleMesh mesh;
  const std::vector<int> vertex_of = weld_positions(obj.positions, mesh.vertices);
  add_triangles(obj, vertex_of, mesh);
  if (mesh.triangles.empty())
    throw UserError(file.string() + ": no faces with area; a model needs at least one polygon face (\"f\" lines)");
  drop_unused_vertices(mesh);
  return mesh;
}

}  // namespace exacity
