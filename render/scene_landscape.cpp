// The land beyond the city in the scene (render/landscape.h): its fields are the terrain's
// and the ground plane's albedo (render/scene_shading.cpp); its woods' and hedgerows'
// trees are instances of the built-in broadleaf and conifer, those the view can see or
// whose shadow it can.
#include <algorithm>
#include <cmath>

#include "generate/cancel.h"
#include "generate/placement/builtin_models.h"
#include "render/scene_build.h"

namespace render {

void RenderScene::add_landscape(const exacity::City& city, const geom::Box& world, const SceneOptions& options) {
  landscape_ = std::make_unique<Landscape>(city.ground, bounds, geom::Vec2{origin_x, origin_y}, city.settings.seed,
                                           corridors_);
  // Trees as far past the city as the city is across, 1 to 1.5 km; past them woods are
  // their dark floor, and the air fades them.
  const double reach = std::clamp(std::max(world.width(), world.height()), 1000.0, 1500.0);
  const geom::Box region{bounds.min_x - reach, bounds.min_y - reach, bounds.max_x + reach, bounds.max_y + reach};
  if (!options.landscape_trees) return;
  const exacity::Terrain* terrain = city.heightmap();
  const std::vector<LandscapeTree> trees = landscape_->trees(region, [&](double x, double y) {
    return terrain ? terrain->height_at({x + origin_x, y + origin_y}) : 0.0;
  });
  std::vector<Plane> planes;
  Camera view;
  if (options.view) view = to_scene(*options.view), planes = frustum(view, options.aspect);
  landscape_trees_ = {exacity::broadleaf_mesh(), exacity::conifer_mesh()};
  RTCScene scenes[2];
  int base[2];
  for (int k = 0; k < 2; ++k) {
    const exacity::TriangleMesh& mesh = landscape_trees_[k];
    base[k] = static_cast<int>(materials_.size());
    for (int tint = 0; tint < exacity::kTints; ++tint)
      for (const auto& mat : mesh.materials)
        add_material({Material::Diffuse, colour(exacity::tinted(mat.colour, tint)) * 0.8f});
    RTCScene ms = model_scenes_.emplace_back(rtcNewScene(device_.get()));  // released with the others
    fill_mesh_scene(ms, mesh);
    scenes[k] = ms;
  }
  const exacity::CancelCheck cancel;
  // A tree is left out when a sphere about it, grown by its shadow's reach, lies wholly
  // outside the view, or when it is farther than twice the detailed tiles' distance.
  constexpr float kReach = 45;
  for (std::size_t i = 0; i < trees.size(); ++i) {
    if (i % 4096 == 0) cancel.check();
    const LandscapeTree& tree = trees[i];
    if (options.view) {
      const V3 c = tree.at + V3{0, 0, 8};
      bool outside = length(c - view.from) > 2 * options.detail_distance;
      for (const Plane& p : planes) outside = outside || dot(p.n, c) + p.d < -kReach;
      if (outside) continue;
    }
    const int k = tree.conifer ? 1 : 0;
    RTCGeometry inst = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, scenes[k]);
    const float c = std::cos(tree.angle), s = std::sin(tree.angle);
    const float xfm[12] = {c * tree.width, s * tree.width, 0, -s * tree.width, c * tree.width, 0, 0, 0, tree.height,
                           tree.at.x,      tree.at.y,      tree.at.z};
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(inst);
    const unsigned id = rtcAttachGeometry(scene_, inst);
    rtcReleaseGeometry(inst);
    Geometry info;
    info.instance = true;
    info.instance_entity = entity_id(Entity::Landscape, i);
    info.material_base = base[k] + tree.tint * static_cast<int>(landscape_trees_[k].materials.size());
    info.shared_material = &landscape_trees_[k].material;
    info.cos_turn = c, info.sin_turn = s;
    if (geometries_.size() <= id) geometries_.resize(id + 1);
    geometries_[id] = std::move(info);
    ++landscape_instances;
  }
  device_.check("the landscape's trees");
}

}  // namespace render
