// Buildings and placed models in the scene: building meshes merged per tile at the tile's
// level, each library model as its own scene placed by instances.
#include <cmath>

#include "generate/cancel.h"
#include "generate/city/structure_albedos.h"
#include "generate/mesh/building_mesh.h"
#include "render/scene_build.h"

namespace render {

namespace {

// Triangles gathered per tile before they become one Embree geometry each.
struct TileMeshes {
  std::vector<std::vector<V3>> vertices;
  std::vector<std::vector<std::array<int, 3>>> triangles;
};

}  // namespace

// Buildings by tile, culled and given their level.
void RenderScene::add_buildings(const exacity::City& city, const geom::Box& world, V3 sun, const SceneOptions& options,
                                const Palette& palette) {
  StructureTiles tiles = tile_structures(city, world, options.tile_size);
  grow_towards_sun(tiles.boxes, sun);
  const TileView view = view_tiles(tiles.boxes, options);
  const ModelMaterials model_materials = add_model_materials(city.model_library(), options.lamp_head_radiance);
  if (options.lamp_intensity > 0) lamps = city_lamps(city, options.lamp_intensity, origin_x, origin_y);

  TileMeshes meshes{std::vector<std::vector<V3>>(tiles.boxes.size()),
                    std::vector<std::vector<std::array<int, 3>>>(tiles.boxes.size())};
  std::vector<Geometry> tile_info(tiles.boxes.size());
  facades_.assign(city.buildings.size() + city.models.size(), FacadeStyle{});
  // `eaves`: where the walls end, from the ground (their windows end below).
  // `mapped`: read from the sketch, not generated.
  // `stable_id`: its id in the outputs, which draws its facade and colours as city.glb's
  // and the page's tiles do.
  auto add_mesh = [&](int id, int stable_id, exacity::ZoneType zone, const exacity::Mesh& mesh, double floor,
                      double eaves, bool mapped) {
    facades_[id] =
        facade_style(zone, city.settings.seed, stable_id, static_cast<float>(floor), static_cast<float>(eaves));
    facades_[id].lit = options.lit_windows, facades_[id].light = options.window_light;
    const int k = tiles.tile_of[id];
    const exacity::StructureAlbedos albedos = exacity::structure_albedos(zone, city.settings.seed, stable_id);
    int f = palette.facade.at({zone, albedos.facade}), r = palette.roof.at({zone, albedos.roof});
    if (options.mark_mapped) f = r = mapped ? palette.mapped : palette.generated;
    const exacity::MeshTriangles tris = exacity::mesh_triangles(mesh);
    const int first = static_cast<int>(meshes.vertices[k].size());
    for (const auto& p : tris.vertices) meshes.vertices[k].push_back(to_scene(p[0], p[1], p[2]));
    for (std::size_t j = 0; j < tris.triangles.size(); ++j) {
      const auto& t = tris.triangles[j];
      meshes.triangles[k].push_back({first + t[0], first + t[1], first + t[2]});
      tile_info[k].material.push_back(tris.surface[j] == exacity::Surface::Roof   ? r
                                      : tris.surface[j] == exacity::Surface::Wall ? f
                                                                                  : palette.sidewalk);
      tile_info[k].entity.push_back(entity_id(Entity::Building, static_cast<std::size_t>(id)));
    }
  };
  const exacity::CancelCheck cancel;
  exacity::for_each_by_id(
      city.buildings, city.models,
      [&](const exacity::Building& b) {
        cancel.check();
        const int k = tiles.tile_of[b.id];
        if (!view.seen[k]) return;
        const bool mapped = b.mapped >= 0;
        if (view.detailed[k])
          return add_mesh(b.id, b.stable_id, b.zone, exacity::building_mesh(b), b.floor, b.floor + b.eaves, mapped);
        exacity::Building box = b;  // the simple level: the footprint extruded, no roof
        box.roof_faces.clear();
        box.eaves = box.height;
        add_mesh(b.id, b.stable_id, b.zone, exacity::building_mesh(box), b.floor, b.floor + b.height, mapped);
      },
      [&](const exacity::ModelInstance& m) {
        cancel.check();
        const int k = tiles.tile_of[m.id];
        if (!view.seen[k]) return;
        if (!view.detailed[k] && m.kind != exacity::ModelKind::Building) return;
        const unsigned id = add_instance(m, *city.model_library(), model_materials);
        if (options.mark_mapped && m.kind == exacity::ModelKind::Building)
          geometries_[id].instance_override = palette.generated;
        // Its foundation, below its floor: no windows.
        if (m.floor > m.base) add_mesh(m.id, m.stable_id, m.zone, exacity::model_mesh(m, nullptr), m.floor, m.floor, false);
      });
  // Street clutter, like lot furniture: an instance each in the detailed tiles seen.
  for (std::size_t i = 0; i < city.clutter.items.size(); ++i) {
    const int k = tiles.clutter_tile[i];
    if (view.seen[k] && view.detailed[k])
      add_instance(city.clutter.items[i].instance, *city.model_library(), model_materials, Entity::Clutter);
  }
  for (std::size_t k = 0; k < tiles.boxes.size(); ++k)
    if (!meshes.triangles[k].empty()) add_triangles(meshes.vertices[k], meshes.triangles[k], std::move(tile_info[k]));
}

// The model's own scene, made the first time it is placed.
RTCScene RenderScene::model_scene(const exacity::ModelLibrary& library, int model) {
  if (model_scenes_[model]) return model_scenes_[model];
  model_scenes_[model] = rtcNewScene(device_.get());  // released with the others if this throws
  fill_mesh_scene(model_scenes_[model], library.models[model].mesh);
  return model_scenes_[model];
}

// A mesh's triangles as the one geometry of its own scene, committed.
void RenderScene::fill_mesh_scene(RTCScene ms, const exacity::TriangleMesh& mesh) {
  RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      device_.new_buffer(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
  for (std::size_t j = 0; j < mesh.vertices.size(); ++j)
    for (int c = 0; c < 3; ++c) v[3 * j + c] = static_cast<float>(mesh.vertices[j][c]);
  auto* t = static_cast<unsigned*>(
      device_.new_buffer(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
  for (std::size_t j = 0; j < mesh.triangles.size(); ++j)
    for (int c = 0; c < 3; ++c) t[3 * j + c] = static_cast<unsigned>(mesh.triangles[j][c]);
  rtcCommitGeometry(g);
  rtcAttachGeometry(ms, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(ms);
  device_.check("a model's scene");
}

// An instance of the model's scene in the top scene, turned, scaled and moved into place.
unsigned RenderScene::add_instance(const exacity::ModelInstance& m, const exacity::ModelLibrary& library,
                               const ModelMaterials& materials, Entity entity) {
  const exacity::Model& model = library.models[m.placed.model];
  RTCGeometry inst = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst, model_scene(library, m.placed.model));
  const float c = std::cos(static_cast<float>(m.placed.angle)) * static_cast<float>(m.placed.scale);
  const float s = std::sin(static_cast<float>(m.placed.angle)) * static_cast<float>(m.placed.scale);
  const V3 at = to_scene(m.placed.position.x, m.placed.position.y, m.floor);
  const float sc = static_cast<float>(m.placed.scale);
  // Column-major 3x4: the turn and scale, then the translation.
  const float xfm[12] = {c, s, 0, -s, c, 0, 0, 0, sc, at.x, at.y, at.z};
  rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
  rtcCommitGeometry(inst);
  unsigned id = rtcAttachGeometry(scene_, inst);
  rtcReleaseGeometry(inst);
  device_.check("a model's instance");
  Geometry info;
  info.instance = true;
  info.instance_entity = entity_id(entity, static_cast<std::size_t>(m.id));
  info.material_base = materials.base[m.placed.model] + m.placed.tint * static_cast<int>(model.mesh.materials.size());
  info.material = materials.local[m.placed.model];
  info.cos_turn = std::cos(static_cast<float>(m.placed.angle)), info.sin_turn = std::sin(static_cast<float>(m.placed.angle));
  if (model.mesh.textured()) info.uv = &model.mesh.uv;
  if (geometries_.size() <= id) geometries_.resize(id + 1);
  geometries_[id] = std::move(info);
  ++instances;
  return id;
}

}  // namespace render

namespace render {

namespace {

// Where a lamp model's point light sits, in its own frame: 5 cm under the middle of its
// light's triangles (under its head, so that shadow rays towards it leave the head out),
// or 0.5 m under the middle of its top where no material is named as its light.
V3 lamp_light_point(const exacity::Model& model) {
  const exacity::TriangleMesh& mesh = model.mesh;
  V3 sum{0, 0, 0};
  float lowest = INFINITY;
  int corners = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!exacity::is_lamp_light_material(mesh.materials[static_cast<std::size_t>(mesh.material[t])].name)) continue;
    for (int c : mesh.triangles[t]) {
      const auto& v = mesh.vertices[static_cast<std::size_t>(c)];
      sum += V3{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
      lowest = std::min(lowest, static_cast<float>(v[2]));
      ++corners;
    }
  }
  if (corners > 0) return {sum.x / static_cast<float>(corners), sum.y / static_cast<float>(corners), lowest - 0.05f};
  V3 low{INFINITY, INFINITY, INFINITY}, high{-INFINITY, -INFINITY, -INFINITY};
  for (const auto& v : mesh.vertices) {
    const V3 p{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
    low = {std::min(low.x, p.x), std::min(low.y, p.y), std::min(low.z, p.z)};
    high = {std::max(high.x, p.x), std::max(high.y, p.y), std::max(high.z, p.z)};
  }
  return {(low.x + high.x) / 2, (low.y + high.y) / 2, high.z - 0.5f};
}

}  // namespace

std::vector<Lamp> city_lamps(const exacity::City& city, float intensity, double origin_x, double origin_y) {
  std::vector<Lamp> lamps;
  const exacity::ModelLibrary* library = city.model_library();
  if (!library) return lamps;
  std::vector<V3> points(library->models.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    if (library->models[i].kind == exacity::ModelKind::Lamp) points[i] = lamp_light_point(library->models[i]);
  auto add = [&](const exacity::ModelInstance& m) {
    if (library->models[static_cast<std::size_t>(m.placed.model)].kind != exacity::ModelKind::Lamp) return;
    const V3 local = points[static_cast<std::size_t>(m.placed.model)];
    const float c = std::cos(static_cast<float>(m.placed.angle)), s = std::sin(static_cast<float>(m.placed.angle));
    const float scale = static_cast<float>(m.placed.scale);
    const V3 at{static_cast<float>(m.placed.position.x - origin_x), static_cast<float>(m.placed.position.y - origin_y),
                static_cast<float>(m.floor)};
    lamps.push_back({at + V3{c * local.x - s * local.y, s * local.x + c * local.y, local.z} * scale,
                     intensity * scale * scale});
  };
  for (const auto& m : city.models) add(m);
  for (const auto& item : city.clutter.items) add(item.instance);
  return lamps;
}

}  // namespace render
