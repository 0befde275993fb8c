#include "generate/export/gltf_export.h"

#include <cmath>
#include <fstream>
#include <cstdint>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <tiny_gltf.h>

#include "generate/cancel.h"
#include "generate/export/cancellable_file.h"
#include "generate/errors.h"
#include "generate/export/ground_layers.h"
#include "generate/city/palette.h"
#include "generate/city/structure_albedos.h"
#include "generate/version.h"

namespace exacity {
namespace {

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
};

// A binary glTF of a JSON text and a binary buffer, as tinygltf's WriteBinaryGltfStream
// writes it: each chunk padded to 4 bytes, the JSON with spaces, the buffer with zeros.
void write_glb(std::ostream& out, const std::string& json_text, const std::vector<unsigned char>& bin) {
  auto word = [&](std::uint32_t w) {
    const char bytes[4] = {static_cast<char>(w), static_cast<char>(w >> 8), static_cast<char>(w >> 16),
                           static_cast<char>(w >> 24)};
    out.write(bytes, 4);
  };
  const auto json_size = static_cast<std::uint32_t>(json_text.size()), bin_size = static_cast<std::uint32_t>(bin.size());
  const std::uint32_t json_padding = (4 - json_size % 4) % 4, bin_padding = (4 - bin_size % 4) % 4;
  out.write("glTF", 4);
  word(2);
  word(12 + 8 + json_size + json_padding + (bin_size ? 8 + bin_size + bin_padding : 0));
  word(json_size + json_padding);
  word(0x4E4F534A);  // "JSON"
  out.write(json_text.data(), json_size);
  out.write("   ", json_padding);
  if (bin_size == 0) return;
  word(bin_size + bin_padding);
  word(0x004E4942);  // "BIN"
  out.write(reinterpret_cast<const char*>(bin.data()), bin_size);
  out.write("\0\0\0", bin_padding);
}

class Glb {
 public:
  Glb() {
    model_.asset.generator = std::string("exacity ") + kVersion;
    model_.buffers.emplace_back();
  }

  int material(const std::string& name, const Colour& c, double roughness = 0.9) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {c[0], c[1], c[2], 1.0};
    m.pbrMetallicRoughness.metallicFactor = 0;
    m.pbrMetallicRoughness.roughnessFactor = roughness;
    model_.materials.push_back(m);
    return static_cast<int>(model_.materials.size()) - 1;
  }

  // A material whose base colour is the image times the colour.
  int textured_material(const std::string& name, const Colour& c, const TextureImage& image, bool clamp) {
    const int m = material(name, c);
    model_.materials[m].pbrMetallicRoughness.baseColorTexture.index = texture(image, clamp);
    return m;
  }

  // POSITION, index and (with uvs) TEXCOORD_0 accessors for the triangles; position -1
  // when there are none.
  Accessors accessors(const Triangles& t) {
    if (t.indices.empty()) return {};
    Float3 lo = t.positions[0], hi = t.positions[0];
    for (const Float3& p : t.positions)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    int position = accessor(t.positions.data(), t.positions.size() * sizeof(Float3), TINYGLTF_TARGET_ARRAY_BUFFER,
                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, t.positions.size());
    model_.accessors[position].minValues = {lo[0], lo[1], lo[2]};
    model_.accessors[position].maxValues = {hi[0], hi[1], hi[2]};
    int index = accessor(t.indices.data(), t.indices.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER,
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, t.indices.size());
    int uv = -1;
    if (!t.uvs.empty())
      uv = accessor(t.uvs.data(), t.uvs.size() * sizeof(Float2), TINYGLTF_TARGET_ARRAY_BUFFER,
                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, t.uvs.size());
    return {position, index, uv};
  }

  // A mesh of primitives (accessors, material); -1 when every primitive is empty.
  int mesh(const std::string& name, const std::vector<std::pair<Accessors, int>>& parts) {
    tinygltf::Mesh m;
    m.name = name;
    for (const auto& [acc, mat] : parts) {
      if (acc.position < 0) continue;
      tinygltf::Primitive p;
      p.attributes["POSITION"] = acc.position;
      if (acc.uv >= 0) p.attributes["TEXCOORD_0"] = acc.uv;
      p.indices = acc.index;
      p.material = mat;
      p.mode = TINYGLTF_MODE_TRIANGLES;
      m.primitives.push_back(p);
      triangles_ += model_.accessors[acc.index].count / 3;
    }
    if (m.primitives.empty()) return -1;
    model_.meshes.push_back(m);
    return static_cast<int>(model_.meshes.size()) - 1;
  }

  int node(tinygltf::Node n) {
    model_.nodes.push_back(std::move(n));
    return static_cast<int>(model_.nodes.size()) - 1;
  }

  std::size_t triangles() const { return triangles_; }
  std::size_t meshes() const { return model_.meshes.size(); }

  void write(int root, const std::filesystem::path& file) {
    tinygltf::Scene scene;
    scene.nodes = {root};
    model_.scenes.push_back(scene);
    model_.defaultScene = 0;
    CancellableFile out(file);
    tinygltf::TinyGLTF writer;
    // tinygltf copies the binary buffer before it writes it (about 150 MB of the 10 km
    // city's, at the 3D export's peak). So its JSON is made with the buffer set aside, the
    // buffer's length is put back into it, and the two chunks are written as tinygltf's
    // WriteBinaryGltfStream writes them: the same bytes.
    std::vector<unsigned char> bin = std::move(model_.buffers[0].data);
    model_.buffers[0].data.clear();
    std::ostringstream without_bin;
    if (!writer.WriteGltfSceneToStream(&model_, without_bin, false, true)) throw UserError(file.string() + ": write failed");
    model_.buffers[0].data = std::move(bin);
    std::string content = std::move(without_bin).str();
    content.erase(0, 20);  // the header (12 bytes) and the JSON chunk's (8)
    while (!content.empty() && content.back() == ' ') content.pop_back();  // its padding
    const std::string empty = R"("buffers":[{"byteLength":0}])";
    const std::size_t at = content.find(empty);
    if (at == std::string::npos || content.find(empty, at + 1) != std::string::npos)
      throw std::logic_error("glTF: the buffer's length is not where it was looked for");
    content.replace(at, empty.size(), R"("buffers":[{"byteLength":)" + std::to_string(model_.buffers[0].data.size()) + "}]");
    write_glb(out, content, model_.buffers[0].data);
    out.close();
  }

 private:
  int buffer_view(const void* data, std::size_t bytes, int target) {
    auto& buffer = model_.buffers[0].data;
    while (buffer.size() % 4) buffer.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  // The image's file embedded in the buffer the first time a material uses it (its bytes
  // as read: glTF takes PNG and JPEG as they are), with a sampler that repeats it or
  // clamps it to its edge.
  int texture(const TextureImage& image, bool clamp) {
    auto [stored, added] = images_.emplace(&image, static_cast<int>(model_.images.size()));
    if (added) {
      tinygltf::Image i;
      i.name = image.file.filename().string();
      i.mimeType = image.mime_type;
      i.bufferView = buffer_view(image.bytes.data(), image.bytes.size(), 0);
      model_.images.push_back(i);
    }
    auto [sampler, new_sampler] = samplers_.emplace(clamp, static_cast<int>(model_.samplers.size()));
    if (new_sampler) {
      tinygltf::Sampler s;
      s.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
      s.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
      s.wrapS = s.wrapT = clamp ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE : TINYGLTF_TEXTURE_WRAP_REPEAT;
      model_.samplers.push_back(s);
    }
    auto [texture, new_texture] =
        textures_.emplace(std::make_pair(stored->second, sampler->second), static_cast<int>(model_.textures.size()));
    if (new_texture) {
      tinygltf::Texture t;
      t.source = stored->second;
      t.sampler = sampler->second;
      model_.textures.push_back(t);
    }
    return texture->second;
  }

  int accessor(const void* data, std::size_t bytes, int target, int component, int type, std::size_t count) {
    tinygltf::Accessor a;
    a.bufferView = buffer_view(data, bytes, target);
    a.byteOffset = 0;
    a.componentType = component;
    a.type = type;
    a.count = count;
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  tinygltf::Model model_;
  std::size_t triangles_ = 0;
  std::map<const TextureImage*, int> images_;
  std::map<bool, int> samplers_;                 // by clamp
  std::map<std::pair<int, int>, int> textures_;  // by (image, sampler)
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

// Extruded buildings and the foundations of placed models, merged by look.
Primitives building_primitives(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                               const std::vector<Mesh>& meshes, std::uint64_t seed, const Frame& local, Glb& glb) {
  std::map<Look, Triangles> merged;
  const CancelCheck cancel;
  auto merge = [&](int id, ZoneType zone, const Mesh& mesh) {
    cancel.check();
    const StructureAlbedos albedos = structure_albedos(zone, seed, id);
    const MeshTriangles tris = mesh_triangles(mesh);
    for (std::size_t k = 0; k < tris.triangles.size(); ++k) {
      Triangles& t = merged[look_of(zone, tris.surface[k], albedos)];
      for (int v : tris.triangles[k]) {
        const Vec3& p = tris.vertices[v];
        t.indices.push_back(static_cast<std::uint32_t>(t.positions.size()));
        t.positions.push_back(local(p[0], p[1], p[2]));
      }
    }
  };
  for_each_by_id(
      buildings, models, [&](const Building& b) { merge(b.stable_id, b.zone, meshes[b.id]); },
      [&](const ModelInstance& m) {
        if (m.floor > m.base) merge(m.stable_id, m.zone, model_mesh(m, nullptr));
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
                            Glb& glb, tinygltf::Node& root, StoredModels& stored) {
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
    tinygltf::Node n;
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
void add_mesh_node(const std::string& name, const Primitives& primitives, Glb& glb, tinygltf::Node& root) {
  tinygltf::Node node;
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
  Glb glb;
  tinygltf::Node root;
  root.name = "city";
  root.translation = {local.origin.x, 0, -local.origin.y};
  if (ground_layers) add_mesh_node("ground", ground_primitives(*ground_layers, local, glb), glb, root);
  add_mesh_node("buildings", building_primitives(buildings, models, meshes, seed, local, glb), glb, root);
  GltfCounts counts;
  StoredModels stored;
  counts.instances = add_model_nodes(models, library, local, glb, root, stored);
  if (!clutter.empty()) {
    // The street clutter under a node of its own, in clutter.geojson's order.
    tinygltf::Node group;
    group.name = "clutter";
    counts.instances += add_model_nodes(clutter, library, local, glb, group, stored);
    root.children.push_back(glb.node(group));
  }
  glb.write(glb.node(root), file);
  counts.meshes = glb.meshes();
  counts.triangles = glb.triangles();
  return counts;
}

}  // namespace

GltfCounts write_gltf(const Ground& ground, const std::vector<GroundLayer>& ground_layers,
                      const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                      const std::vector<Mesh>& meshes, std::uint64_t seed, const ModelLibrary* library,
                      const std::filesystem::path& file, const std::vector<ModelInstance>& clutter) {
  return write_city_part(&ground_layers, city_box(ground), buildings, models, meshes, seed, library, file, clutter);
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
  Glb glb;
  tinygltf::Node root;
  root.name = "city";
  root.translation = {local.origin.x, 0, -local.origin.y};
  Primitives prims;
  for (const auto& [look, t] : merged) prims.push_back({glb.accessors(t), look_material(look, glb)});
  add_mesh_node("boxes", prims, glb, root);
  glb.write(glb.node(root), file);
  GltfCounts counts;
  counts.meshes = glb.meshes();
  counts.triangles = glb.triangles();
  return counts;
}

}  // namespace exacity
