#include "generate/export/cityjson_export.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "generate/cancel.h"
#include "generate/cancellable_invoke.h"
#include "generate/city/format_number.h"
#include "generate/city/random.h"
#include "generate/export/cancellable_file.h"
#include "generate/errors.h"
#include "generate/mesh/bridges.h"
#include "generate/export/ground_layers.h"
#include "generate/export/json_text.h"
#include "generate/export/scratch_file.h"
#include "generate/export/vector_layers.h"
#include "generate/gis/projection.h"
#include "geom/ring_cleanup.h"
#include "geom/triangulate.h"
#include "geom/untangle.h"

namespace exacity {
namespace {

using nlohmann::json;

constexpr double kScale = 0.001;  // millimetres

// The byte before a vertex index in a piece's text (below, ObjectPiece): JSON text holds
// none (a string escapes it as \u0001), so the indices can be found and renumbered.
constexpr char kIndexMark = '\x01';

// Quantised vertices, each stored once. The index is open addressing over positions in
// the list (4 bytes a slot, at most half full) rather than a node-based map: the 10 km
// city has 2.5 million vertices, looked up once for every corner of every surface.
// `marked`: a piece's vertices, numbered from 0 in it and renumbered when it is written,
// so its text marks each index (kIndexMark).
class Vertices {
 public:
  using Quantised = std::array<long long, 3>;
  explicit Vertices(geom::Vec2 origin, bool marked = false)
      : origin_(origin), marked_(marked), slots_(1 << 10, kEmpty) {}
  int operator()(double x, double y, double z) { return at(grid({x, y}), z); }
  // A point's place on the millimetre grid, whole numbers from the origin.
  geom::Vec2 grid(geom::Vec2 p) const { return {std::round((p.x - origin_.x) / kScale), std::round((p.y - origin_.y) / kScale)}; }
  // The vertex at that place of the grid, at height z.
  int at(geom::Vec2 grid, double z) { return find_or_add({std::llround(grid.x), std::llround(grid.y), std::llround(z / kScale)}); }
  // The vertex straight below vertex i, at height z.
  int below(int i, double z) {
    Quantised q = list_[i];
    q[2] = std::llround(z / kScale);
    return find_or_add(q);
  }
  // Vertex i's index in a geometry's text.
  void append_index(std::string& out, int i) const {
    if (marked_) out += kIndexMark;
    append_number(out, i);
  }
  // Each of `piece`'s vertices here, added where new: its index here by its index there. Added
  // in the piece's order, so the vertices are numbered as if the piece's objects had been
  // made here.
  void merge(const Vertices& piece, std::vector<int>& index) {
    const std::size_t n = piece.list_.size();
    index.resize(n);
    // The slots grown once for them all, so that each vertex's slot can be fetched a few
    // vertices ahead: the city's index is far larger than the cache, and this serial step
    // waited on one slot after another.
    while (2 * (list_.size() + n) > slots_.size()) grow();
    constexpr std::size_t kAhead = 8;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = 0; i < n; ++i) {
      if (i + kAhead < n) __builtin_prefetch(&slots_[hash(piece.list_[i + kAhead]) & mask]);
      index[i] = find_or_add(piece.list_[i]);
    }
  }
  // As JSON's array of [x, y, z] integers, appended to `text` (written to `out` as it grows, if given).
  void append_json(std::string& text, std::ostream* out = nullptr) const {
    text += '[';
    for (std::size_t i = 0; i < list_.size(); ++i) {
      text += i ? ",[" : "[";
      append_number(text, list_[i][0]), text += ',', append_number(text, list_[i][1]), text += ',';
      append_number(text, list_[i][2]), text += ']';
      if (out && text.size() > (1 << 16)) *out << text, text.clear();
    }
    text += ']';
  }

 private:
  static constexpr int kEmpty = -1;
  static std::size_t hash(const Quantised& q) {
    return mix(mix(static_cast<std::uint64_t>(q[0]), static_cast<std::uint64_t>(q[1])), static_cast<std::uint64_t>(q[2]));
  }
  // The slot holding q's index, or the empty slot where it belongs.
  std::size_t slot(const Quantised& q) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t s = hash(q) & mask;
    while (slots_[s] != kEmpty && !same(list_[slots_[s]], q)) s = (s + 1) & mask;
    return s;
  }
  static bool same(const Quantised& a, const Quantised& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }
  int find_or_add(const Quantised& q) {
    std::size_t s = slot(q);
    if (slots_[s] != kEmpty) return slots_[s];
    const int i = static_cast<int>(list_.size());
    list_.push_back(q);
    slots_[s] = i;
    if (2 * list_.size() > slots_.size()) grow();
    return i;
  }
  void grow() {
    slots_.assign(2 * slots_.size(), kEmpty);
    for (std::size_t i = 0; i < list_.size(); ++i) slots_[slot(list_[i])] = static_cast<int>(i);
  }

  geom::Vec2 origin_;
  bool marked_;
  std::vector<int> slots_;  // a power of two in size
  std::vector<Quantised> list_;
};

// A polygon on the millimetre grid, as the simple polygons it bounds there. Quantising drops
// repeated vertices and the spikes they leave, and can make a ring touch itself or another
// (a neck or a gap under a millimetre wide): such rings are cut into simple ones, since
// CityJSON's rings must be simple (val3dity's 104, ring self-intersection).
std::vector<geom::Polygon> quantised(const geom::Polygon& p, const Vertices& v) {
  auto ring = [&](const geom::Ring& r) {
    geom::Ring q;
    q.reserve(r.size());
    for (geom::Vec2 point : r) q.push_back(v.grid(point));
    geom::drop_repeats_and_spikes(q);
    return q;
  };
  std::vector<geom::Ring> rings{ring(p.outer)};
  if (rings[0].empty()) return {};
  for (const geom::Ring& h : p.holes)
    if (geom::Ring q = ring(h); !q.empty()) rings.push_back(std::move(q));
  if (geom::vertex_repeats(rings)) return geom::untangle(rings);
  geom::Polygon out{std::move(rings[0]), {}};
  out.holes.assign(std::make_move_iterator(rings.begin() + 1), std::make_move_iterator(rings.end()));
  return {std::move(out)};
}

// Surfaces as CityJSON's boundaries list them (each surface its rings, each ring its vertex
// indices), kept flat and written straight to text: a JSON value for every index was most
// of the writer's time.
class SurfaceList {
 public:
  void begin_surface() { surface_ends_.push_back(static_cast<int>(ring_ends_.size())); }
  // A ring of the surface begun last.
  void add_ring(std::span<const int> ring) {
    indices_.insert(indices_.end(), ring.begin(), ring.end());
    ring_ends_.push_back(static_cast<int>(indices_.size()));
    surface_ends_.back() = static_cast<int>(ring_ends_.size());
  }
  // A surface of one ring.
  void add(std::span<const int> ring) { begin_surface(), add_ring(ring); }
  void append(const SurfaceList& other) {
    const int rings = static_cast<int>(ring_ends_.size()), indices = static_cast<int>(indices_.size());
    indices_.insert(indices_.end(), other.indices_.begin(), other.indices_.end());
    for (int e : other.ring_ends_) ring_ends_.push_back(indices + e);
    for (int e : other.surface_ends_) surface_ends_.push_back(rings + e);
  }
  std::size_t size() const { return surface_ends_.size(); }
  bool empty() const { return surface_ends_.empty(); }
  // Ring r's vertex indices (rings counted across the surfaces).
  std::span<const int> ring(std::size_t r) const {
    const int first = r == 0 ? 0 : ring_ends_[r - 1];
    return {indices_.data() + first, static_cast<std::size_t>(ring_ends_[r] - first)};
  }
  // As JSON: [[[i,...],...],...], indices of `v`.
  void write(std::string& out, const Vertices& v) const {
    out += '[';
    std::size_t r = 0;
    for (std::size_t s = 0; s < surface_ends_.size(); ++s) {
      out += s ? ",[" : "[";
      for (const std::size_t first = r; r < static_cast<std::size_t>(surface_ends_[s]); ++r) {
        out += r > first ? ",[" : "[";
        const std::span<const int> ring = this->ring(r);
        for (std::size_t k = 0; k < ring.size(); ++k) {
          if (k) out += ',';
          v.append_index(out, ring[k]);
        }
        out += ']';
      }
      out += ']';
    }
    out += ']';
  }
  // Surface s's rings: the first and one past the last.
  std::pair<std::size_t, std::size_t> ring_range(std::size_t s) const {
    return {s == 0 ? 0 : static_cast<std::size_t>(surface_ends_[s - 1]), static_cast<std::size_t>(surface_ends_[s])};
  }

 private:
  std::vector<int> indices_;
  std::vector<int> ring_ends_;     // where each ring ends in indices_
  std::vector<int> surface_ends_;  // where each surface ends in ring_ends_
};

void append_ints(std::string& out, const std::vector<int>& list) {
  out += '[';
  for (std::size_t k = 0; k < list.size(); ++k) {
    if (k) out += ',';
    append_number(out, list[k]);
  }
  out += ']';
}

// Flat surfaces from a polygon at height z: each an outer ring then holes, each
// counter-clockwise seen from the side the surface faces. None when the polygon collapses.
// `simple_polygons`: a polygon as quantised() gives it.
void surfaces(const std::vector<geom::Polygon>& simple_polygons, double z, bool facing_down, Vertices& v,
              SurfaceList& out) {
  std::vector<int> q;
  for (const geom::Polygon& simple : simple_polygons) {
    out.begin_surface();
    auto add = [&](const geom::Ring& r) {
      q.clear();
      for (geom::Vec2 g : r) q.push_back(v.at(g, z));
      if (facing_down) std::reverse(q.begin(), q.end());
      out.add_ring(q);
    };
    add(simple.outer);
    for (const geom::Ring& h : simple.holes) add(h);
  }
}
void surfaces(const geom::Polygon& p, double z, bool facing_down, Vertices& v, SurfaceList& out) {
  surfaces(quantised(p, v), z, facing_down, v, out);
}

// The closed shell of a footprint's prism from `base` to `top`: ground, a wall per edge,
// roof; with each surface's class. Walls follow the same quantised rings as ground and
// roof, so the shell stays closed. (A footprint with a neck under a millimetre wide becomes
// prisms that share an edge there: never seen on a generated footprint.)
bool prism(const geom::Polygon& footprint, double base, double top, Vertices& v, SurfaceList& shell,
           std::vector<int>& classes) {
  SurfaceList grounds, roofs;
  const std::vector<geom::Polygon> simple = quantised(footprint, v);  // once for both
  surfaces(simple, base, true, v, grounds);
  surfaces(simple, top, false, v, roofs);
  if (grounds.empty()) return false;
  shell.append(grounds), classes.insert(classes.end(), grounds.size(), 0);
  for (std::size_t s = 0; s < roofs.size(); ++s)
    for (auto [r, end] = roofs.ring_range(s); r < end; ++r) {
      const std::span<const int> ring = roofs.ring(r);
      for (std::size_t i = 0; i < ring.size(); ++i) {
        // Roof and ground vertices differ only in z: quantised the same way, so look them up.
        const int a = ring[i], c = ring[(i + 1) % ring.size()];
        const int wall[4] = {v.below(a, base), v.below(c, base), c, a};
        shell.add(wall);
        classes.push_back(1);
      }
    }
  shell.append(roofs), classes.insert(classes.end(), roofs.size(), 2);
  return true;
}

// The shell of the building's mesh, each face with its surface class; false when a face
// collapses under quantisation, unless `skip_collapsed` (for surfaces that need not close).
bool mesh_shell(const Mesh& mesh, Vertices& v, SurfaceList& shell, std::vector<int>& classes,
                bool skip_collapsed = false) {
  std::vector<int> ring, distinct;
  for (const Mesh::Face f : mesh.faces()) {
    ring.clear();
    for (std::uint32_t corner : f.corners) {
      const Vec3& p = mesh.points[corner];
      ring.push_back(v(p[0], p[1], p[2]));
    }
    distinct = ring;
    std::sort(distinct.begin(), distinct.end());
    if (std::unique(distinct.begin(), distinct.end()) != distinct.end()) {
      if (skip_collapsed) continue;
      return false;
    }
    shell.add(ring);
    classes.push_back(static_cast<int>(f.surface));
  }
  return true;
}

// Each triangle as a surface, those that quantisation collapses left out.
void append_triangles(const GroundMesh& m, Vertices& v, SurfaceList& out) {
  for (const auto& t : m.triangles) {
    std::array<int, 3> q;
    for (int k = 0; k < 3; ++k) q[k] = v(m.vertices[t[k]][0], m.vertices[t[k]][1], m.vertices[t[k]][2]);
    if (q[0] != q[1] && q[1] != q[2] && q[0] != q[2]) out.add(q);
  }
}

// A geometry of surfaces: {"boundaries":...,"lod":"LOD","type":"TYPE"}.
void append_surface_geometry(std::string& out, const char* type, const char* lod, const SurfaceList& boundaries,
                             const Vertices& v) {
  out += "{\"boundaries\":";
  boundaries.write(out, v);
  out += ",\"lod\":\"", out += lod, out += "\",\"type\":\"", out += type, out += "\"}";
}

// A polygon, and the height it lies level at (water, bridge decks) or NaN to drape it.
using LevelPolygon = std::pair<const geom::Polygon*, double>;

// Polygons smaller than the quantum vanish; false when all do. On terrain each polygon
// becomes the triangles that drape it over the heightmap, or lay it level.
bool multisurface(const std::vector<LevelPolygon>& polygons, const Terrain* terrain, Vertices& v, std::string& out) {
  SurfaceList boundaries;
  for (const auto& [p, level] : polygons) {
    if (terrain && std::isfinite(level)) {
      GroundMesh m;
      drape_flat(*p, level, m);
      append_triangles(m, v, boundaries);
      continue;
    }
    if (!terrain) {
      surfaces(*p, 0, false, v, boundaries);
      continue;
    }
    GroundMesh m;
    drape(*p, terrain, 0, m);
    append_triangles(m, v, boundaries);
  }
  if (boundaries.empty()) return false;
  append_surface_geometry(out, "MultiSurface", "1", boundaries, v);
  return true;
}

// Model textures as CityJSON's appearance (docs/design.md, Textured models): CityJSON names
// images by path, so each image is written once into `folder`; a texture per image and wrap
// mode; each textured triangle's corners as texture vertices, u and v as the OBJ gives them
// (both count from the image's bottom left).
class Appearance {
 public:
  explicit Appearance(std::filesystem::path folder) : folder_(std::move(folder)) {}

  // The triangle's texture value: [texture, three texture vertices], or [null].
  json ring(const MeshMaterial& material, const std::array<Uv, 3>& uv) {
    if (!material.texture) return json::array({nullptr});
    json value = json::array({texture(*material.texture, material.clamp)});
    for (const Uv& c : uv) {
      value.push_back(vertices_.size());
      vertices_.push_back({c[0], c[1]});
    }
    return value;
  }

  bool empty() const { return textures_.empty(); }
  json to_json() const {
    return {{"default-theme-texture", "exacity"}, {"textures", textures_}, {"vertices-texture", vertices_}};
  }

 private:
  int texture(const TextureImage& image, bool clamp) {
    auto [it, added] = index_.emplace(std::make_pair(&image, clamp), static_cast<int>(textures_.size()));
    if (added)
      textures_.push_back({{"type", image.mime_type == "image/png" ? "PNG" : "JPG"},
                           {"image", "textures/" + image_name(image)},
                           {"wrapMode", clamp ? "clamp" : "wrap"}});
    return it->second;
  }

  // The image's name in the folder, written the first time: its own, or numbered when
  // another image took it.
  std::string image_name(const TextureImage& image) {
    auto [it, added] = names_.emplace(&image, image.file.filename().string());
    if (!added) return it->second;
    for (const auto& [other, name] : names_)
      if (other != &image && name == it->second) it->second = std::to_string(names_.size()) + "_" + it->second;
    std::filesystem::create_directories(folder_);
    std::ofstream out(folder_ / it->second, std::ios::binary);
    out.write(reinterpret_cast<const char*>(image.bytes.data()), static_cast<std::streamsize>(image.bytes.size()));
    if (!out) throw UserError((folder_ / it->second).string() + ": write failed (disk full?)");
    return it->second;
  }

  std::filesystem::path folder_;
  json textures_ = json::array(), vertices_ = json::array();
  std::map<std::pair<const TextureImage*, bool>, int> index_;
  std::map<const TextureImage*, std::string> names_;
};

// Each model of the library once, as a MultiSurface in its own frame (a geometry template), its
// textured triangles with their texture coordinates.
json templates(const ModelLibrary& library, Appearance& appearance) {
  json list = json::array(), vertices = json::array();
  for (const Model& m : library.models) {
    const int first = static_cast<int>(vertices.size());
    for (const Vec3& p : m.mesh.vertices) vertices.push_back({p[0], p[1], p[2]});
    json faces = json::array(), texture = json::array();
    for (std::size_t k = 0; k < m.mesh.triangles.size(); ++k) {
      const auto& t = m.mesh.triangles[k];
      faces.push_back(json::array({json::array({first + t[0], first + t[1], first + t[2]})}));
      if (m.mesh.textured())
        texture.push_back(json::array({appearance.ring(m.mesh.materials[m.mesh.material[k]], m.mesh.uv[k])}));
    }
    json geometry{{"type", "MultiSurface"}, {"lod", "2"}, {"boundaries", faces}};
    if (m.mesh.textured()) geometry["texture"] = {{"exacity", {{"values", texture}}}};
    list.push_back(geometry);
  }
  return {{"templates", list}, {"vertices-templates", vertices}};
}

// A model's template placed by a transform about its reference point, standing on `floor`.
void geometry_instance(const Placement& p, double floor, Vertices& v, std::string& out) {
  const double c = std::cos(p.angle) * p.scale, s = std::sin(p.angle) * p.scale;
  out += "{\"boundaries\":[";
  v.append_index(out, v(p.position.x, p.position.y, floor));
  out += "],\"template\":";
  append_number(out, p.model);
  out += ",\"transformationMatrix\":[";
  append_json_number(out, c), out += ',', append_json_number(out, -s), out += ",0,0,";
  append_json_number(out, s), out += ',', append_json_number(out, c), out += ",0,0,0,0,";
  append_json_number(out, p.scale), out += ",0,0,0,0,1],\"type\":\"GeometryInstance\"}";
}

constexpr const char* kSemanticSurfaces =
    "[{\"type\":\"GroundSurface\"},{\"type\":\"WallSurface\"},{\"type\":\"RoofSurface\"}]";

// {"boundaries":[SHELL],"lod":"2","semantics":{...},"type":"Solid"} with each surface's
// class; a MultiSurface of the surfaces when not `solid`.
void append_classed_geometry(std::string& out, bool solid, const SurfaceList& surfaces, const std::vector<int>& classes,
                             const Vertices& v) {
  out += solid ? "{\"boundaries\":[" : "{\"boundaries\":";
  surfaces.write(out, v);
  out += solid ? "],\"lod\":\"2\",\"semantics\":{\"surfaces\":" : ",\"lod\":\"2\",\"semantics\":{\"surfaces\":";
  out += kSemanticSurfaces;
  out += solid ? ",\"values\":[" : ",\"values\":";
  append_ints(out, classes);
  out += solid ? "]},\"type\":\"Solid\"}" : "},\"type\":\"MultiSurface\"}";
}

// LOD1 the prism (a closed shell) and LOD2 the mesh's shell, or the prism where quantisation
// collapses a face of the mesh: "geometry":[LOD1,LOD2]. False, writing nothing, when the
// prism collapses.
bool append_solids(std::string& out, const geom::Polygon& footprint, double base, double top, const Mesh& mesh,
                   Vertices& v) {
  SurfaceList shell;
  std::vector<int> classes;
  if (!prism(footprint, base, top, v, shell, classes)) return false;
  SurfaceList lod2;
  std::vector<int> lod2_classes;
  const bool built = mesh_shell(mesh, v, lod2, lod2_classes);
  out += "\"geometry\":[{\"boundaries\":[";
  shell.write(out, v);
  out += "],\"lod\":\"1\",\"type\":\"Solid\"},";
  built ? append_classed_geometry(out, true, lod2, lod2_classes, v) : append_classed_geometry(out, true, shell, classes, v);
  out += ']';
  return true;
}

// A lot by its id in the outputs; null for none.
json lot_id(const Ground& ground, int lot) { return lot >= 0 ? json(ground.lots[lot].stable_id) : json(nullptr); }
void append_lot(std::string& out, const Ground& ground, int lot) {
  lot >= 0 ? append_number(out, ground.lots[lot].stable_id) : void(out += "null");
}

json building_attributes(const Building& b, const Ground& ground) {
  json attributes{{"lot", lot_id(ground, b.lot)}, {"zone", name(b.zone)}, {"measuredHeight", b.height},
                  {"roofType", b.roof}};
  if (b.mapped >= 0) {
    const nlohmann::ordered_json mapped = mapped_attributes(b);
    for (auto it = mapped.begin(); it != mapped.end(); ++it) attributes[it.key()] = *it;
  }
  return attributes;
}

// A city object's text is its members in name order, as a JSON object's dump() gives them.
void append_attributes(std::string& out, const json& attributes) {
  out += "{\"attributes\":";
  out += attributes.dump();
  out += ',';
}

// An extruded building: LOD1 its prism, LOD2 its roof as built (where quantisation
// collapses a face of it, the prism). False when the prism collapses.
bool building_object(const Building& b, const Ground& ground, const Mesh& mesh, Vertices& v, std::string& out) {
  std::string geometry;
  if (!append_solids(geometry, b.polygon, b.base, b.floor + b.height, mesh, v)) return false;
  if (b.mapped >= 0) {
    append_attributes(out, building_attributes(b, ground));
  } else {
    // building_attributes' members, written directly (the buildings are most objects).
    out += "{\"attributes\":{\"lot\":";
    append_lot(out, ground, b.lot);
    out += ",\"measuredHeight\":";
    append_json_number(out, b.height);
    out += ",\"roofType\":";
    append_json_string(out, b.roof);
    out += ",\"zone\":";
    append_json_string(out, name(b.zone));
    out += "},";
  }
  out += geometry;
  out += ",\"type\":\"Building\"}";
  return true;
}

// A mapped building with building:parts: its attributes, its geometry theirs (its children),
// since OSM's outline of such a building is 2D only.
void building_with_parts(const Building& b, const Ground& ground, const std::vector<std::string>& children,
                         std::string& out) {
  append_attributes(out, building_attributes(b, ground));
  out += "\"children\":";
  out += json(children).dump();
  out += ",\"geometry\":[],\"type\":\"Building\"}";
}

// A building:part (OSM's Simple 3D Buildings) of a mapped building: LOD1 its prism from
// its bottom to its height, LOD2 as built, as an extruded building's; its parent named.
// False when the prism collapses.
bool building_part_object(const Building& b, const BuildingPart& part, const std::string& parent, Vertices& v,
                          std::string& out) {
  const double bottom = part.bottom > 0 ? b.floor + part.bottom : b.base;
  std::string geometry;
  if (!append_solids(geometry, part.polygon, bottom, b.floor + part.height, building_part_mesh(b, part), v))
    return false;
  append_attributes(out, {{"osm_id", part.osm_id.empty() ? json(nullptr) : json(part.osm_id)},
                          {"building:part", part.tag},
                          {"measuredHeight", part.height},
                          {"min_height", part.bottom},
                          {"roofType", part.roof}});
  out += geometry;
  out += ",\"parents\":";
  out += json::array({parent}).dump();
  out += ",\"type\":\"BuildingPart\"}";
  return true;
}

// A placed model: LOD1 the prism of its outline; then a library building's surfaces as
// placed (CityJSON lets no Building hold a GeometryInstance), or for furniture and trees
// the template stored once, placed by a transform about its reference point. False when
// the prism collapses.
bool model_object(const ModelInstance& m, const Ground& ground, const Mesh& mesh, const ModelLibrary& library,
                  Vertices& v, std::string& out) {
  SurfaceList shell;
  std::vector<int> classes;
  if (!prism(m.polygon, m.base, m.floor + m.height, v, shell, classes)) return false;
  out += "{\"attributes\":{\"lot\":";
  append_lot(out, ground, m.lot);
  out += ",\"measuredHeight\":";
  append_json_number(out, m.height);
  out += ",\"model\":";
  append_json_string(out, library.models[m.placed.model].name);
  out += ",\"zone\":";
  append_json_string(out, name(m.zone));
  out += "},\"geometry\":[{\"boundaries\":[";
  shell.write(out, v);
  out += "],\"lod\":\"1\",\"type\":\"Solid\"},";
  if (m.kind == ModelKind::Building) {
    SurfaceList faces;
    std::vector<int> face_classes;
    mesh_shell(mesh, v, faces, face_classes, true);
    append_classed_geometry(out, false, faces, face_classes, v);
  } else {
    geometry_instance(m.placed, m.floor, v, out);
  }
  out += "],\"type\":";
  out += m.kind == ModelKind::Tree       ? "\"SolitaryVegetationObject\"}"
         : m.kind == ModelKind::Building ? "\"Building\"}"
                                         : "\"CityFurniture\"}";
  return true;
}

// Street clutter: CityFurniture, or SolitaryVegetationObject for a tree, whose one
// geometry is its model's template placed; its attributes name the road it dresses (null for
// a park's tree).
void clutter_object(const Clutter& c, const Ground& ground, const ModelLibrary& library, Vertices& v, std::string& out) {
  const ModelInstance& m = c.instance;
  out += "{\"attributes\":{\"heading\":";
  append_json_number(out, c.heading);
  out += ",\"kind\":";
  append_json_string(out, name(m.kind));
  if (m.lot >= 0) out += ",\"lot\":", append_number(out, ground.lots[m.lot].stable_id);
  out += ",\"measuredHeight\":";
  append_json_number(out, m.height);
  out += ",\"model\":";
  append_json_string(out, library.models[m.placed.model].name);
  out += ",\"road\":";
  c.road >= 0 ? append_number(out, ground.roads[c.road].stable_id) : void(out += "null");
  out += "},";
  out += "\"geometry\":[";
  geometry_instance(m.placed, m.floor, v, out);
  out += m.kind == ModelKind::Tree ? "],\"type\":\"SolitaryVegetationObject\"}" : "],\"type\":\"CityFurniture\"}";
}

// The city objects' texts by key, kept in a scratch file until they are written in the
// document's (key) order, which is not the order they are made in. Held in memory they
// were most of the file (about 300 MB of the 10 km city's) at the 3D export's peak.
class ObjectTexts {
 public:
  explicit ObjectTexts(const std::filesystem::path& beside) : file_(beside) {}

  // A key given again keeps its last text.
  void set(const std::string& key, std::string_view text) {
    at_.push_back({prefix(key), key, file_.size(), text.size()});
    file_.append(text);
  }

  // Each object as `"key":text`, comma-separated, in key order.
  void write(std::ostream& out) {
    // Sorted once (a map of 450,000 keys compared them with memcmp at every insertion),
    // first by the keys' first 16 bytes as numbers, which mostly decides.
    std::stable_sort(at_.begin(), at_.end(), [](const Entry& a, const Entry& b) {
      return a.prefix != b.prefix ? a.prefix < b.prefix : a.key < b.key;
    });
    std::string text;
    bool first = true;
    for (std::size_t i = 0; i < at_.size(); ++i) {
      const Entry& e = at_[i];
      if (i + 1 < at_.size() && at_[i + 1].key == e.key) continue;  // given again later
      text.assign(first ? "" : ",");
      append_json_string(text, e.key);
      text += ':';
      const std::size_t start = text.size();
      text.resize(start + e.length);
      file_.read(e.offset, text.data() + start, e.length);
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      first = false;
    }
  }

 private:
  // A key's first 16 bytes, big-endian (unsigned, as strings compare), zeros past its end.
  static std::pair<std::uint64_t, std::uint64_t> prefix(const std::string& key) {
    auto word = [&](std::size_t from) {
      std::uint64_t w = 0;
      for (std::size_t i = from; i < from + 8; ++i) w = w << 8 | (i < key.size() ? static_cast<unsigned char>(key[i]) : 0u);
      return w;
    };
    return {word(0), word(8)};
  }
  struct Entry {
    std::pair<std::uint64_t, std::uint64_t> prefix;
    std::string key;
    std::uint64_t offset;
    std::size_t length;
  };
  ScratchFile file_;
  std::vector<Entry> at_;  // in the order set
};

// A city object's key and its text.
struct CityObjectText {
  std::string key, text;
};

enum class Form { Document, Sequence };

// A piece of the city's objects, made on any thread: a document's objects with the vertices
// they share, numbered in the piece (their indices marked) until the writer renumbers them;
// a sequence's features as their lines, each with its own vertices.
class ObjectPiece {
 public:
  ObjectPiece() = default;
  ObjectPiece(Form form, geom::Vec2 origin) : form_(form), origin_(origin), vertices_(origin, form == Form::Document) {}

  // The vertices the next feature's geometry indexes.
  Vertices& next_vertices() {
    if (form_ == Form::Sequence) vertices_ = Vertices(origin_);
    return vertices_;
  }

  // A feature made with next_vertices(): its object's text under `key`, and its children's.
  void add(const std::string& key, std::string_view object, std::vector<CityObjectText> children = {}) {
    if (form_ == Form::Document) {
      for (CityObjectText& child : children) objects_.push_back(std::move(child));
      objects_.push_back({key, std::string(object)});
      return;
    }
    // A feature's objects in key order, as a JSON object holds them.
    lines_ += "{\"type\":\"CityJSONFeature\",\"id\":";
    lines_ += json(key).dump();
    lines_ += ",\"CityObjects\":{";
    children.push_back({key, std::string(object)});
    std::sort(children.begin(), children.end(), [](const auto& a, const auto& b) { return a.key < b.key; });
    for (std::size_t i = 0; i < children.size(); ++i) {
      if (i) lines_ += ',';
      lines_ += json(children[i].key).dump(), lines_ += ':', lines_ += children[i].text;
    }
    lines_ += "},\"vertices\":";
    vertices_.append_json(lines_);
    lines_ += "}\n";
  }

  const Vertices& vertices() const { return vertices_; }
  const std::vector<CityObjectText>& objects() const { return objects_; }
  const std::string& lines() const { return lines_; }

 private:
  Form form_ = Form::Document;
  geom::Vec2 origin_;
  Vertices vertices_{{0, 0}};
  std::vector<CityObjectText> objects_;  // a document's, in the order made
  std::string lines_;                    // a sequence's
};

// Where the pieces go, in order: a document's objects share one vertex list, each piece's
// vertices added to it as they come (so numbered as one writer making every object in turn
// numbers them), and are written in key order once all are made; a sequence's features are
// written at once.
class CityObjectWriter {
 public:
  // `shared`: the members every object refers to (transform, templates, appearance, metadata).
  CityObjectWriter(Form form, const std::filesystem::path& file, json shared, geom::Vec2 origin)
      : form_(form), vertices_(origin), shared_(std::move(shared)), out_(file) {
    if (form_ == Form::Document) {
      texts_.emplace(file);
      return;
    }
    json header = shared_;
    header["CityObjects"] = json::object();
    header["vertices"] = json::array();
    out_ << header.dump() << '\n';
  }

  void write(const ObjectPiece& piece) {
    if (form_ == Form::Sequence) {
      out_ << piece.lines();
      return;
    }
    vertices_.merge(piece.vertices(), index_);
    for (const auto& [key, text] : piece.objects()) {
      // The text with each marked index renumbered.
      renumbered_.clear();
      std::size_t from = 0;
      for (std::size_t mark; (mark = text.find(kIndexMark, from)) != std::string::npos;) {
        renumbered_.append(text, from, mark - from);
        std::size_t i = 0;
        for (from = mark + 1; from < text.size() && text[from] >= '0' && text[from] <= '9'; ++from)
          i = 10 * i + static_cast<std::size_t>(text[from] - '0');
        append_number(renumbered_, index_[i]);
      }
      renumbered_.append(text, from);
      texts_->set(key, renumbered_);
    }
  }

  void close() {
    if (form_ == Form::Document) {
      // In the document's (sorted) order the objects come first and the vertices last, so
      // they are written before and after the other members.
      out_ << "{\"CityObjects\":{";
      texts_->write(out_);
      const std::string members = shared_.dump();
      out_ << "}," << members.substr(1, members.size() - 2) << ",\"vertices\":";
      std::string text;
      vertices_.append_json(text, &out_);
      out_ << text << "}\n";
    }
    out_.close();
  }

 private:
  Form form_;
  Vertices vertices_;  // a document's
  json shared_;
  std::optional<ObjectTexts> texts_;  // the document's objects, until written in key order
  CancellableFile out_;               // written as it goes, through a buffer that stops once the build is cancelled
  std::vector<int> index_;            // a piece's vertices' indices in vertices_
  std::string renumbered_;            // an object's text, renumbered
};

// Roads, land use and water as LOD1 surfaces: an object per road (its areas), per zone
// type and one for the water, in the order of their key's text (kept from when they were
// grouped by their GeoJSON property), each named prefix + n; a road's prefix + its id, so
// that an edit leaves the names of the roads it does not reach as they were.
void add_ground_objects(const Ground& ground, const std::vector<GroundLayer>& layers, const Terrain* terrain,
                        ObjectPiece& out) {
  using Groups = std::map<std::string, std::pair<json, std::vector<LevelPolygon>>>;
  std::string text;
  auto surfaces = [&](const Groups& groups, const std::string& prefix, const std::string& type, bool by_key = false) {
    int n = 0;
    for (const auto& [key, group] : groups) {
      text.assign("{");
      if (!group.first.is_null()) text += "\"attributes\":", text += group.first.dump(), text += ',';
      text += "\"geometry\":[";
      if (!multisurface(group.second, terrain, out.next_vertices(), text)) continue;
      text += "],\"type\":", text += json(type).dump(), text += '}';
      out.add(prefix + (by_key ? key : std::to_string(n++)), text);
    }
  };
  Groups roads, zones, water;
  // Water level at its shore height, bridge decks level between their ends
  // (docs/design.md, Ground meshes).
  const BridgeDecks decks = bridge_decks(ground, terrain);
  for (std::size_t i = 0; i < ground.road_areas.size(); ++i) {
    const RoadArea& a = ground.road_areas[i];
    const int road = a.road >= 0 ? ground.roads[a.road].stable_id : -1;
    auto& [attributes, polygons] = roads[road >= 0 ? std::to_string(road) : "null"];
    // The road's id and its OpenStreetMap tags, as roads.geojson has them.
    if (attributes.is_null()) {
      attributes = {{"road", road >= 0 ? json(road) : json(nullptr)}};
      if (a.road >= 0) attributes.update(json(road_attributes(ground.roads[a.road])));
    }
    polygons.push_back({&a.polygon, decks.height[i]});
  }
  for (const ZoneArea& z : ground.zones) {
    auto& [zone, polygons] = zones[std::string(name(z.type))];
    zone = {{"zone", name(z.type)}};
    polygons.push_back({&z.polygon, NAN});
  }
  for (const geom::Polygon& w : ground.water) water[""].second.push_back({&w, water_level(w, terrain)});
  surfaces(roads, "road-", "Road", true);
  surfaces(zones, "landuse-", "LandUse");
  surfaces(water, "water-", "WaterBody");
  // The decks' sides and undersides and the piers, one Bridge object for every bridge.
  if (const GroundMesh* bridges = layer_mesh(layers, GroundKind::Bridge); terrain && bridges) {
    SurfaceList boundaries;
    Vertices& v = out.next_vertices();
    append_triangles(*bridges, v, boundaries);
    if (!boundaries.empty()) {
      text.assign("{\"geometry\":[");
      append_surface_geometry(text, "MultiSurface", "1", boundaries, v);
      text += "],\"type\":\"Bridge\"}";
      out.add("bridges", text);
    }
  }
}

// Structures and clutter a piece: enough that a piece is worth handing to a thread, few
// enough that the pieces waiting to be written stay small.
constexpr std::size_t kObjectsAPiece = 1024;

// Every object of the city through `out`, in the order their vertices are numbered: the
// buildings and models by id, the clutter, the ground's objects, the terrain. Made in pieces
// at once and written in order, so the bytes are those of one writer making each in turn.
void write_objects(const MeshedCity& city, Form form, CityObjectWriter& out, geom::Vec2 origin) {
  const Ground& ground = city.ground;
  // The structures by id: a building's index, or a model's as ~index.
  std::vector<int> structures;
  for_each_by_id(
      city.buildings, city.models, [&](const Building& b) { structures.push_back(static_cast<int>(&b - city.buildings.data())); },
      [&](const ModelInstance& m) { structures.push_back(~static_cast<int>(&m - city.models.data())); });
  auto add_structure = [&](int s, ObjectPiece& piece, std::string& text) {
    text.clear();
    if (s < 0) {
      const ModelInstance& m = city.models[static_cast<std::size_t>(~s)];
      if (model_object(m, ground, city.meshes[m.id], *city.library, piece.next_vertices(), text))
        piece.add("building-" + std::to_string(m.stable_id), text);
      return;
    }
    const Building& b = city.buildings[static_cast<std::size_t>(s)];
    const std::string key = "building-" + std::to_string(b.stable_id);
    Vertices& v = piece.next_vertices();
    if (b.parts.empty()) {
      if (building_object(b, ground, city.meshes[b.id], v, text)) piece.add(key, text);
      return;
    }
    // Its parts are its 3D (OSM's Simple 3D Buildings): BuildingParts, its children.
    std::vector<CityObjectText> parts;
    std::vector<std::string> children;
    for (std::size_t k = 0; k < b.parts.size(); ++k) {
      std::string part_key = key + "-part-" + std::to_string(k), part;
      if (building_part_object(b, b.parts[k], key, v, part)) {
        children.push_back(part_key);
        parts.push_back({std::move(part_key), std::move(part)});
      }
    }
    building_with_parts(b, ground, children, text);
    piece.add(key, text, std::move(parts));
  };
  // The pieces: runs of structures, runs of clutter, the ground's objects, the terrain.
  const std::size_t structure_pieces = (structures.size() + kObjectsAPiece - 1) / kObjectsAPiece;
  const std::size_t clutter_pieces = (city.clutter.size() + kObjectsAPiece - 1) / kObjectsAPiece;
  const std::size_t ground_piece = structure_pieces + clutter_pieces;
  make_in_order<ObjectPiece>(
      ground_piece + 2,
      [&](std::size_t i, ObjectPiece& piece) {
        piece = ObjectPiece(form, origin);
        std::string text;
        if (i < structure_pieces) {
          for (std::size_t k = i * kObjectsAPiece; k < std::min(structures.size(), (i + 1) * kObjectsAPiece); ++k)
            add_structure(structures[k], piece, text);
        } else if (i < ground_piece) {
          const std::size_t begin = (i - structure_pieces) * kObjectsAPiece;
          for (std::size_t k = begin; k < std::min(city.clutter.size(), begin + kObjectsAPiece); ++k) {
            const Clutter& c = city.clutter[k];
            text.clear();
            clutter_object(c, ground, *city.library, piece.next_vertices(), text);
            piece.add("clutter-" + std::to_string(c.instance.stable_id), text);
          }
        } else if (i == ground_piece) {
          add_ground_objects(ground, city.ground_layers, city.terrain, piece);
        } else {
          // The ground under the city: the heightmap over the rectangle around it.
          SurfaceList tin;
          Vertices& v = piece.next_vertices();
          append_triangles(*layer_mesh(city.ground_layers, GroundKind::Terrain), v, tin);
          text.assign("{\"geometry\":[");
          append_surface_geometry(text, "CompositeSurface", "1", tin, v);
          text += "],\"type\":\"TINRelief\"}";
          piece.add("terrain", text);
        }
      },
      [&](const ObjectPiece& piece) { out.write(piece); });
  out.close();
}

}  // namespace

void write_cityjson(const MeshedCity& city, const std::filesystem::path& document, const std::filesystem::path& sequence) {
  const geom::Box box = city_box(city.ground);
  const geom::Vec2 origin{std::floor(box.min_x), std::floor(box.min_y)};
  // What both forms share, made once: the templates, and the appearance with its image files.
  json shared{{"type", "CityJSON"},
              {"version", "2.0"},
              {"transform", {{"scale", {kScale, kScale, kScale}}, {"translate", {origin.x, origin.y, 0.0}}}}};
  Appearance appearance(document.parent_path() / "textures");
  if (city.library) shared["geometry-templates"] = templates(*city.library, appearance);
  if (!appearance.empty()) shared["appearance"] = appearance.to_json();
  // An EPSG code in the sketch's crs becomes the reference system.
  if (const std::optional<int> epsg = epsg_of(city.crs))
    shared["metadata"] = {{"referenceSystem", "https://www.opengis.net/def/crs/EPSG/0/" + std::to_string(*epsg)}};

  CityObjectWriter out(Form::Document, document, shared, origin);
  write_objects(city, Form::Document, out, origin);
  if (sequence.empty()) return;
  CityObjectWriter features(Form::Sequence, sequence, std::move(shared), origin);
  write_objects(city, Form::Sequence, features, origin);
}

}  // namespace exacity
