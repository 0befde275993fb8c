#include "generate/export/gltf_export.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>

#include <nlohmann/json.hpp>

#include "generate/cancel.h"
#include "generate/cancellable_invoke.h"
#include "generate/export/cancellable_file.h"
#include "generate/errors.h"
#include "generate/city/format_number.h"
#include "generate/export/ground_layers.h"
#include "generate/export/json_text.h"
#include "generate/export/scratch_file.h"
#include "generate/city/palette.h"
#include "generate/city/structure_albedos.h"
#include "generate/version.h"

namespace exacity {
namespace {

using nlohmann::json;
using Float3 = std::array<float, 3>;
using Float2 = std::array<float, 2>;

// Triangles in glTF's frame, ready to become one primitive.
struct Triangles {
  std::vector<Float3> positions;
  std::vector<std::uint32_t> indices;
  std::vector<Float2> uvs;  // TEXCOORD_0 per position, or none
};

// A primitive's accessors; position -1 when it has no triangles, uv -1 without TEXCOORD_0.
struct Accessors {
  int position = -1, index = -1, uv = -1;
  std::size_t triangles = 0;
};

// glTF's numbers for what it names.
enum : int {
  kFloat = 5126,
  kUnsignedInt = 5125,
  kArrayBuffer = 34962,
  kElementArrayBuffer = 34963,
  kTriangles = 4,
  kLinear = 9729,
  kLinearMipmapLinear = 9987,
  kClampToEdge = 33071,
  kRepeat = 10497,
};

// A node: a mesh placed (translation, rotation, scale: none when empty) or a group of
// children.
struct Node {
  std::string name;
  int mesh = -1;
  std::vector<double> translation, rotation, scale;
  std::vector<int> children;
};

// One of the JSON document's arrays, its elements' texts in a scratch file as they are made.
class JsonArray {
 public:
  explicit JsonArray(const std::filesystem::path& beside) : text_(beside) {}
  int add(const json& element) { return add_text(element.dump()); }
  // An element given as its text.
  int add_text(std::string_view element) {
    if (count_) text_.append(",");
    text_.append(element);
    return count_++;
  }
  int size() const { return count_; }
  ScratchFile& text() { return text_; }

 private:
  ScratchFile text_;
  int count_ = 0;
};

// A binary glTF written as it is made: each element of the JSON's arrays as text into a
// scratch file when it is added, the binary buffer into another, and the file put
// together from them at the end (the JSON chunk first, so its length must be known
// first). The JSON is what tinygltf's writer (which held the whole document, about
// 550 MiB for the 10 km city's 336,518 nodes, and the buffer) made of the same model, to
// the byte: each element's members sorted by name, as nlohmann's object holds them,
// members at their default value left out, numbers as nlohmann prints them; each chunk
// padded to 4 bytes, the JSON with spaces, the buffer with zeros.
class Glb {
 public:
  explicit Glb(const std::filesystem::path& file)
      : file_(file), bin_(file), accessors_(file), buffer_views_(file), images_(file), materials_(file),
        meshes_(file), nodes_(file), samplers_(file), textures_(file) {}

  int material(const std::string& name, const Colour& c, double roughness = 0.9, int texture = -1) {
    json pbr{{"metallicFactor", 0.0}};
    // tinygltf's defaults, which it leaves out: a white base colour, roughness 1.
    auto same = [](double a, double b) { return std::fabs(a - b) < 1e-12; };
    if (!(same(c[0], 1) && same(c[1], 1) && same(c[2], 1))) pbr["baseColorFactor"] = {c[0], c[1], c[2], 1.0};
    if (!same(roughness, 1)) pbr["roughnessFactor"] = roughness;
    if (texture >= 0) pbr["baseColorTexture"] = {{"index", texture}};
    json m{{"pbrMetallicRoughness", std::move(pbr)}};
    if (!name.empty()) m["name"] = name;
    return materials_.add(m);
  }

  // A material whose base colour is the image times the colour.
  int textured_material(const std::string& name, const Colour& c, const TextureImage& image, bool clamp) {
    return material(name, c, 0.9, texture(image, clamp));
  }

  // POSITION, index and (with uvs) TEXCOORD_0 accessors for the triangles; position -1
  // when there are none.
  Accessors accessors(const Triangles& t) {
    if (t.indices.empty()) return {};
    Float3 lo = t.positions[0], hi = t.positions[0];
    for (const Float3& p : t.positions)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    json position = accessor(t.positions.data(), t.positions.size() * sizeof(Float3), kArrayBuffer, kFloat, "VEC3",
                             t.positions.size());
    position["min"] = {double{lo[0]}, double{lo[1]}, double{lo[2]}};
    position["max"] = {double{hi[0]}, double{hi[1]}, double{hi[2]}};
    Accessors out;
    out.position = accessors_.add(position);
    out.index = accessors_.add(accessor(t.indices.data(), t.indices.size() * sizeof(std::uint32_t),
                                        kElementArrayBuffer, kUnsignedInt, "SCALAR", t.indices.size()));
    if (!t.uvs.empty())
      out.uv = accessors_.add(
          accessor(t.uvs.data(), t.uvs.size() * sizeof(Float2), kArrayBuffer, kFloat, "VEC2", t.uvs.size()));
    out.triangles = t.indices.size() / 3;
    return out;
  }

  // A mesh of primitives (accessors, material); -1 when every primitive is empty.
  int mesh(const std::string& name, const std::vector<std::pair<Accessors, int>>& parts) {
    json primitives = json::array();
    for (const auto& [acc, mat] : parts) {
      if (acc.position < 0) continue;
      json attributes{{"POSITION", acc.position}};
      if (acc.uv >= 0) attributes["TEXCOORD_0"] = acc.uv;
      primitives.push_back(
          {{"attributes", std::move(attributes)}, {"indices", acc.index}, {"material", mat}, {"mode", kTriangles}});
      triangles_ += acc.triangles;
    }
    if (primitives.empty()) return -1;
    json m{{"primitives", std::move(primitives)}};
    if (!name.empty()) m["name"] = name;
    return meshes_.add(m);
  }

  // A node's text as its JSON value's dump() gives it (members in name order, numbers as
  // nlohmann writes them), made directly: the 10 km city has 336,518 nodes.
  int node(const Node& n) {
    node_text_.assign("{");
    auto member = [&](const char* key) {
      node_text_ += node_text_.size() > 1 ? ",\"" : "\"";
      node_text_ += key;
      node_text_ += "\":";
    };
    auto numbers = [&](const char* key, const std::vector<double>& list) {
      if (list.empty()) return;
      member(key);
      node_text_ += '[';
      for (std::size_t i = 0; i < list.size(); ++i) {
        if (i) node_text_ += ',';
        append_json_number(node_text_, list[i]);
      }
      node_text_ += ']';
    };
    if (!n.children.empty()) {
      member("children");
      node_text_ += '[';
      for (std::size_t i = 0; i < n.children.size(); ++i) {
        if (i) node_text_ += ',';
        append_number(node_text_, n.children[i]);
      }
      node_text_ += ']';
    }
    if (n.mesh != -1) member("mesh"), append_number(node_text_, n.mesh);
    if (!n.name.empty()) member("name"), append_json_string(node_text_, n.name);
    numbers("rotation", n.rotation);
    numbers("scale", n.scale);
    numbers("translation", n.translation);
    node_text_ += '}';
    return nodes_.add_text(node_text_);
  }

  std::size_t triangles() const { return triangles_; }
  std::size_t meshes() const { return static_cast<std::size_t>(meshes_.size()); }

  // The file, with `root` the scene's one node.
  void write(int root) {
    // The JSON's members in name order, each array's elements from its scratch file.
    struct Piece {
      std::string text;
      ScratchFile* elements = nullptr;  // after the text
    };
    std::vector<Piece> pieces{{"{"}};
    bool first = true;
    auto member = [&](const std::string& key, const std::string& value) {
      pieces.back().text += (first ? "" : ",") + json(key).dump() + ":" + value;
      first = false;
    };
    auto array = [&](const std::string& key, JsonArray& a) {
      if (a.size() == 0) return;
      member(key, "[");
      pieces.push_back({"", &a.text()});
      pieces.push_back({"]"});
    };
    array("accessors", accessors_);
    member("asset", json{{"generator", std::string("exacity ") + kVersion}, {"version", "2.0"}}.dump());
    array("bufferViews", buffer_views_);
    member("buffers", json::array({{{"byteLength", bin_.size()}}}).dump());
    array("images", images_);
    array("materials", materials_);
    array("meshes", meshes_);
    array("nodes", nodes_);
    array("samplers", samplers_);
    member("scene", "0");
    member("scenes", json::array({{{"nodes", {root}}}}).dump());
    array("textures", textures_);
    pieces.back().text += "}";

    std::uint64_t json_size = 0;
    for (const Piece& p : pieces) json_size += (p.elements ? p.elements->size() : 0) + p.text.size();
    const std::uint64_t bin_size = bin_.size();
    const std::uint64_t json_padding = (4 - json_size % 4) % 4, bin_padding = (4 - bin_size % 4) % 4;
    const std::uint64_t length = 12 + 8 + json_size + json_padding + (bin_size ? 8 + bin_size + bin_padding : 0);
    if (length > 0xFFFFFFFFu) throw UserError(file_.string() + ": larger than a GLB can be (4 GiB)");
    CancellableFile out(file_);
    auto word = [&](std::uint64_t w) {
      const char bytes[4] = {static_cast<char>(w), static_cast<char>(w >> 8), static_cast<char>(w >> 16),
                             static_cast<char>(w >> 24)};
      out.write(bytes, 4);
    };
    out.write("glTF", 4);
    word(2);
    word(length);
    word(json_size + json_padding);
    word(0x4E4F534A);  // "JSON"
    for (Piece& p : pieces) {
      if (p.elements) p.elements->copy_to(out);
      out << p.text;
    }
    out.write("   ", static_cast<std::streamsize>(json_padding));
    if (bin_size) {
      word(bin_size + bin_padding);
      word(0x004E4942);  // "BIN"
      bin_.copy_to(out);
      out.write("\0\0\0", static_cast<std::streamsize>(bin_padding));
    }
    out.close();
  }

 private:
  int buffer_view(const void* data, std::size_t bytes, int target) {
    bin_.append_zeros((4 - bin_.size() % 4) % 4);
    json view{{"buffer", 0}, {"byteLength", bytes}};
    if (bin_.size() > 0) view["byteOffset"] = bin_.size();
    if (target) view["target"] = target;
    bin_.append({static_cast<const char*>(data), bytes});
    return buffer_views_.add(view);
  }

  // The image's file embedded in the buffer the first time a material uses it (its bytes
  // as read: glTF takes PNG and JPEG as they are), with a sampler that repeats it or
  // clamps it to its edge.
  int texture(const TextureImage& image, bool clamp) {
    auto [stored, added] = image_index_.emplace(&image, images_.size());
    if (added) {
      json i{{"mimeType", image.mime_type}, {"bufferView", buffer_view(image.bytes.data(), image.bytes.size(), 0)}};
      if (const std::string name = image.file.filename().string(); !name.empty()) i["name"] = name;
      images_.add(i);
    }
    auto [sampler, new_sampler] = sampler_index_.emplace(clamp, samplers_.size());
    if (new_sampler) {
      const int wrap = clamp ? kClampToEdge : kRepeat;
      samplers_.add({{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}, {"wrapS", wrap}, {"wrapT", wrap}});
    }
    auto [texture, new_texture] =
        texture_index_.emplace(std::make_pair(stored->second, sampler->second), textures_.size());
    if (new_texture) textures_.add({{"sampler", sampler->second}, {"source", stored->second}});
    return texture->second;
  }

  // An accessor of the data, put into the buffer; its bounds are the caller's to add.
  json accessor(const void* data, std::size_t bytes, int target, int component, const char* type, std::size_t count) {
    return {{"bufferView", buffer_view(data, bytes, target)}, {"componentType", component}, {"count", count}, {"type", type}};
  }

  std::filesystem::path file_;
  ScratchFile bin_;
  JsonArray accessors_, buffer_views_, images_, materials_, meshes_, nodes_, samplers_, textures_;
  std::size_t triangles_ = 0;
  std::map<const TextureImage*, int> image_index_;
  std::map<bool, int> sampler_index_;                 // by clamp
  std::map<std::pair<int, int>, int> texture_index_;  // by (image, sampler)
  std::string node_text_;
};

// Exacity's x east, y north, z up to glTF's x, y up, z south, about the local origin.
struct Frame {
  geom::Vec2 origin;
  Float3 operator()(double x, double y, double z) const {
    return Float3{static_cast<float>(x - origin.x), static_cast<float>(z), static_cast<float>(origin.y - y)};
  }
};

using Primitives = std::vector<std::pair<Accessors, int>>;  // (accessors, material) each

void add_ground_mesh(const GroundMesh& g, const Frame& local, Triangles& t) {
  const auto first = static_cast<std::uint32_t>(t.positions.size());
  for (const Vec3& v : g.vertices) t.positions.push_back(local(v[0], v[1], v[2]));
  for (const auto& tri : g.triangles)
    for (int k : tri) t.indices.push_back(first + static_cast<std::uint32_t>(k));
}

// The ground's layers, a primitive each.
Primitives ground_primitives(const std::vector<GroundLayer>& layers, const Frame& local, Glb& glb) {
  Primitives out;
  for (const GroundLayer& layer : layers) {
    Triangles t;
    add_ground_mesh(layer.mesh, local, t);
    out.push_back({glb.accessors(t), glb.material(layer.name, layer.colour, layer.roughness)});
  }
  return out;
}

// A structure's surfaces are merged with those of the same look: its zone, the surface and
// the albedo the renderer gives it there (structure_albedos; -1: the ground face, or a
// box of several structures).
using Look = std::tuple<ZoneType, int, int>;

Look look_of(ZoneType zone, Surface surface, const StructureAlbedos& albedos) {
  return {zone, static_cast<int>(surface),
          surface == Surface::Wall ? albedos.facade : surface == Surface::Roof ? albedos.roof : -1};
}

// The renderer's albedo for a look (docs/design.md, Rendering: facades and roofs): walls and
// roofs their structure's, the mean of the zone's for a box of several, ground faces the
// sidewalk's.
int look_material(const Look& look, Glb& glb) {
  const auto [zone, surface_index, index] = look;
  const auto surface = static_cast<Surface>(surface_index);
  std::string name_ = std::string(name(zone)) + "_" + kSurfaceNames[surface_index];
  const std::vector<Albedo>* albedos = surface == Surface::Wall   ? &facade_albedos(zone)
                                       : surface == Surface::Roof ? &roof_albedos(zone)
                                                                  : nullptr;
  Colour colour{kSidewalkAlbedo[0], kSidewalkAlbedo[1], kSidewalkAlbedo[2]};
  if (albedos && index >= 0) {
    const Albedo& a = (*albedos)[static_cast<std::size_t>(index)];
    colour = {a[0], a[1], a[2]};
    name_ += "_" + std::to_string(index);
  } else if (albedos) {
    colour = {0, 0, 0};
    for (const Albedo& a : *albedos)
      for (int c = 0; c < 3; ++c) colour[c] += a[c] / static_cast<double>(albedos->size());
  }
  return glb.material(name_, colour);
}

// Extruded buildings and the foundations of placed models, merged by look. Structures are
// triangulated a run at a time at once on TBB's threads and merged in their order, so the
// buffer is the same whatever the thread count.
Primitives building_primitives(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                               const std::vector<Mesh>& meshes, std::uint64_t seed, const Frame& local, Glb& glb) {
  // Each structure by id: its stable id, zone, and its mesh or (a placed model) the model,
  // whose foundation is made here.
  struct Structure {
    int id;
    ZoneType zone;
    const Mesh* mesh;
    const ModelInstance* model;
  };
  std::vector<Structure> structures;
  structures.reserve(meshes.size());
  for_each_by_id(
      buildings, models, [&](const Building& b) { structures.push_back({b.stable_id, b.zone, &meshes[b.id], nullptr}); },
      [&](const ModelInstance& m) { structures.push_back({m.stable_id, m.zone, nullptr, &m}); });
  constexpr std::size_t kStructuresAPiece = 2048;
  const std::size_t n_pieces = (structures.size() + kStructuresAPiece - 1) / kStructuresAPiece;
  std::map<Look, Triangles> merged;
  make_in_order<std::map<Look, Triangles>>(
      n_pieces,
      [&](std::size_t piece, std::map<Look, Triangles>& part) {
        const std::size_t end = std::min(structures.size(), (piece + 1) * kStructuresAPiece);
        for (std::size_t i = piece * kStructuresAPiece; i < end; ++i) {
          const Structure& s = structures[i];
          Mesh foundation;
          const Mesh* mesh = s.mesh;
          if (s.model) {
            if (!(s.model->floor > s.model->base)) continue;
            foundation = model_mesh(*s.model, nullptr);
            mesh = &foundation;
          }
          const StructureAlbedos albedos = structure_albedos(s.zone, seed, s.id);
          const MeshTriangles tris = mesh_triangles(*mesh);
          for (std::size_t k = 0; k < tris.triangles.size(); ++k) {
            Triangles& t = part[look_of(s.zone, tris.surface[k], albedos)];
            for (int v : tris.triangles[k]) {
              const Vec3& p = tris.vertices[v];
              t.indices.push_back(static_cast<std::uint32_t>(t.positions.size()));
              t.positions.push_back(local(p[0], p[1], p[2]));
            }
          }
        }
      },
      [&](const std::map<Look, Triangles>& part) {
        for (const auto& [look, t] : part) {
          Triangles& all = merged[look];
          const auto first = static_cast<std::uint32_t>(all.positions.size());
          all.positions.insert(all.positions.end(), t.positions.begin(), t.positions.end());
          for (std::uint32_t i : t.indices) all.indices.push_back(first + i);
        }
      });
  Primitives out;
  for (const auto& [look, t] : merged) out.push_back({glb.accessors(t), look_material(look, glb)});
  return out;
}

// Each library model's geometry and colour variants, stored the first time one is placed.
struct StoredModels {
  std::map<int, std::vector<Accessors>> geometry;           // model -> accessors per material
  std::map<std::pair<int, int>, int> variant_mesh;          // (model, tint) -> mesh
};

// Placed models: geometry once per model, a mesh per colour variant used, a node each
// (children of `root`). Returns the nodes added.
std::size_t add_model_nodes(const std::vector<ModelInstance>& models, const ModelLibrary* library, const Frame& local,
                            Glb& glb, Node& root, StoredModels& stored) {
  auto& geometry = stored.geometry;
  auto& variant_mesh = stored.variant_mesh;
  const CancelCheck cancel;
  for (const ModelInstance& m : models) {
    cancel.check();
    const int mi = m.placed.model;
    const Model& model = library->models[mi];
    if (!geometry.count(mi)) {
      std::vector<Triangles> by_material(model.mesh.materials.size());
      for (std::size_t k = 0; k < model.mesh.triangles.size(); ++k) {
        const int material = model.mesh.material[k];
        Triangles& t = by_material[material];
        for (int c = 0; c < 3; ++c) {
          const Vec3& p = model.mesh.vertices[model.mesh.triangles[k][c]];
          t.indices.push_back(static_cast<std::uint32_t>(t.positions.size()));
          t.positions.push_back({static_cast<float>(p[0]), static_cast<float>(p[2]), static_cast<float>(-p[1])});
          // glTF's v runs down the image, OBJ's up.
          if (model.mesh.materials[material].texture) {
            const Uv& uv = model.mesh.uv[k][c];
            t.uvs.push_back({static_cast<float>(uv[0]), static_cast<float>(1 - uv[1])});
          }
        }
      }
      for (const Triangles& t : by_material) geometry[mi].push_back(glb.accessors(t));
    }
    auto [it, added] = variant_mesh.emplace(std::make_pair(mi, m.placed.tint), -1);
    if (added) {
      Primitives prims;
      for (std::size_t k = 0; k < model.mesh.materials.size(); ++k) {
        const MeshMaterial& material = model.mesh.materials[k];
        const std::string name = model.name + "_" + material.name + "_" + std::to_string(m.placed.tint);
        const Colour colour = tinted(material.colour, m.placed.tint);
        prims.push_back({geometry[mi][k], material.texture
                                              ? glb.textured_material(name, colour, *material.texture, material.clamp)
                                              : glb.material(name, colour)});
      }
      it->second = glb.mesh(model.name + "_" + std::to_string(m.placed.tint), prims);
    }
    Node n;
    n.name = model.name;
    n.mesh = it->second;
    Float3 at = local(m.placed.position.x, m.placed.position.y, m.floor);
    n.translation = {at[0], at[1], at[2]};
    n.rotation = {0, std::sin(m.placed.angle / 2), 0, std::cos(m.placed.angle / 2)};
    n.scale = {m.placed.scale, m.placed.scale, m.placed.scale};
    root.children.push_back(glb.node(n));
  }
  return models.size();
}

// A node holding one mesh of the primitives, under `root`; none when they are all empty.
void add_mesh_node(const std::string& name, const Primitives& primitives, Glb& glb, Node& root) {
  Node node;
  node.name = name;
  node.mesh = glb.mesh(name, primitives);
  if (node.mesh >= 0) root.children.push_back(glb.node(node));
}

// write_gltf's body; without the ground when `ground_layers` is null (a tile's structures).
GltfCounts write_city_part(const std::vector<GroundLayer>* ground_layers, const geom::Box& box,
                           const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                           const std::vector<Mesh>& meshes, std::uint64_t seed, const ModelLibrary* library,
                           const std::filesystem::path& file, const std::vector<ModelInstance>& clutter) {
  const Frame local{local_origin(box)};
  Glb glb(file);
  Node root;
  root.name = "city";
  root.translation = {local.origin.x, 0, -local.origin.y};
  if (ground_layers) add_mesh_node("ground", ground_primitives(*ground_layers, local, glb), glb, root);
  add_mesh_node("buildings", building_primitives(buildings, models, meshes, seed, local, glb), glb, root);
  GltfCounts counts;
  StoredModels stored;
  counts.instances = add_model_nodes(models, library, local, glb, root, stored);
  if (!clutter.empty()) {
    // The street clutter under a node of its own, in clutter.geojson's order.
    Node group;
    group.name = "clutter";
    counts.instances += add_model_nodes(clutter, library, local, glb, group, stored);
    root.children.push_back(glb.node(group));
  }
  glb.write(glb.node(root));
  counts.meshes = glb.meshes();
  counts.triangles = glb.triangles();
  return counts;
}

}  // namespace

GltfCounts write_gltf(const MeshedCity& city, const std::filesystem::path& file) {
  std::vector<ModelInstance> clutter;
  clutter.reserve(city.clutter.size());
  for (const Clutter& c : city.clutter) clutter.push_back(c.instance);
  return write_city_part(&city.ground_layers, city_box(city.ground), city.buildings, city.models, city.meshes, city.seed,
                         city.library, file, clutter);
}

GltfCounts write_gltf_structures(const geom::Box& city, const std::vector<Building>& buildings,
                                 const std::vector<ModelInstance>& models, const std::vector<Mesh>& meshes,
                                 std::uint64_t seed, const ModelLibrary* library, const std::filesystem::path& file,
                                 const std::vector<ModelInstance>& clutter) {
  return write_city_part(nullptr, city, buildings, models, meshes, seed, library, file, clutter);
}

GltfCounts write_gltf_boxes(const geom::Box& city, const std::vector<StructureBox>& boxes, std::uint64_t seed,
                            const std::filesystem::path& file) {
  const Frame local{local_origin(city)};
  std::map<Look, Triangles> merged;
  for (const StructureBox& b : boxes) {
    const double x[2] = {b.box.min_x, b.box.max_x}, y[2] = {b.box.min_y, b.box.max_y}, z[2] = {b.bottom, b.top};
    const StructureAlbedos albedos = b.id >= 0 ? structure_albedos(b.zone, seed, b.id) : StructureAlbedos{-1, -1};
    auto quad = [&](Surface surface, std::array<std::array<int, 3>, 4> corners) {
      Triangles& t = merged[look_of(b.zone, surface, albedos)];
      const auto first = static_cast<std::uint32_t>(t.positions.size());
      for (const auto& c : corners) t.positions.push_back(local(x[c[0]], y[c[1]], z[c[2]]));
      for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) t.indices.push_back(first + k);
    };
    // Counter-clockwise seen from outside (glTF's front faces).
    quad(Surface::Roof, {{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}});
    quad(Surface::Wall, {{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}});
    quad(Surface::Wall, {{{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}});
    quad(Surface::Wall, {{{1, 1, 0}, {0, 1, 0}, {0, 1, 1}, {1, 1, 1}}});
    quad(Surface::Wall, {{{0, 1, 0}, {0, 0, 0}, {0, 0, 1}, {0, 1, 1}}});
  }
  Glb glb(file);
  Node root;
  root.name = "city";
  root.translation = {local.origin.x, 0, -local.origin.y};
  Primitives prims;
  for (const auto& [look, t] : merged) prims.push_back({glb.accessors(t), look_material(look, glb)});
  add_mesh_node("boxes", prims, glb, root);
  glb.write(glb.node(root));
  GltfCounts counts;
  counts.meshes = glb.meshes();
  counts.triangles = glb.triangles();
  return counts;
}

}  // namespace exacity
