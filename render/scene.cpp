#include "render/scene.h"

#include "generate/cancel.h"
#include "generate/mesh/ground_mesh.h"
#include "render/scene_build.h"

namespace render {

unsigned RenderScene::add_triangles(const std::vector<V3>& vertices, const std::vector<std::array<int, 3>>& tris,
                                    Geometry info) {
  RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      device_.new_buffer(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i)
    v[3 * i] = vertices[i].x, v[3 * i + 1] = vertices[i].y, v[3 * i + 2] = vertices[i].z;
  auto* t = static_cast<unsigned*>(
      device_.new_buffer(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) t[3 * i + k] = static_cast<unsigned>(tris[i][k]);
  rtcCommitGeometry(g);
  unsigned id = rtcAttachGeometry(scene_, g);
  rtcReleaseGeometry(g);
  device_.check("a mesh");
  if (geometries_.size() <= id) geometries_.resize(id + 1);
  geometries_[id] = std::move(info);
  triangles += tris.size();
  return id;
}

RenderScene::RenderScene(const std::vector<TriangleSoup>& soups, bool ground_plane)
    : scene_(rtcNewScene(device_.get())), ground_plane_(ground_plane) {
  bounds = geom::Box::none();
  for (const TriangleSoup& s : soups) {
    materials_.push_back(s.material);
    patterns_.push_back(Pattern::None);
    Geometry info;
    info.material.assign(s.triangles.size(), static_cast<int>(materials_.size()) - 1);
    info.entity.assign(s.triangles.size(), s.entity);
    for (V3 p : s.vertices) bounds.add(geom::Vec2{p.x, p.y}), top = std::max(top, p.z);
    add_triangles(s.vertices, s.triangles, std::move(info));
  }
  materials_.push_back({Material::Diffuse, colour(exacity::kGrassAlbedo)});
  patterns_.push_back(Pattern::Grass);
  grass_material_ = static_cast<int>(materials_.size()) - 1;
  rtcCommitScene(scene_);
  device_.check("the scene");
}

namespace {

// Embree's build of a large city's scene takes a while: its progress monitor stops it once
// the job is cancelled (generate/cancel.h), and the cancel is then thrown here.
void commit_cancellable(RTCScene scene) {
  exacity::CancelCheck cancel;
  rtcSetSceneProgressMonitorFunction(
      scene,
      [](void* check, double) {
        try {
          static_cast<const exacity::CancelCheck*>(check)->check();
          return true;
        } catch (const exacity::Cancelled&) {
          return false;
        }
      },
      &cancel);
  rtcCommitScene(scene);
  rtcSetSceneProgressMonitorFunction(scene, nullptr, nullptr);
  cancel.check();
}

}  // namespace

RenderScene::RenderScene(const exacity::City& city, V3 sun, const SceneOptions& options)
    : scene_(rtcNewScene(device_.get())), ground_plane_(options.ground_plane) {
  try {
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    build(city, sun, options);
    commit_cancellable(scene_);
    device_.check("the city's scene");
  } catch (...) {
    release();  // no destructor runs for a constructor that throws
    throw;
  }
}

RenderScene::~RenderScene() { release(); }

void RenderScene::release() {
  if (scene_) rtcReleaseScene(scene_);
  for (RTCScene s : model_scenes_)
    if (s) rtcReleaseScene(s);
  scene_ = nullptr, model_scenes_.clear();
}

void RenderScene::build(const exacity::City& city, V3 sun, const SceneOptions& options) {
  geom::Box world = city.ground.bounds();
  if (world.holds_nothing()) world = {0, 0, 1, 1};
  const geom::Vec2 origin = exacity::local_origin(world);
  origin_x = origin.x, origin_y = origin.y;
  bounds = {world.min_x - origin_x, world.min_y - origin_y, world.max_x - origin_x, world.max_y - origin_y};

  Palette palette;
  make_palette(palette);
  add_ground(city, world, palette);
  add_buildings(city, world, sun, options, palette);
  add_landscape(city, world, options);
}

int RenderScene::add_material(Material m, Pattern p) {
  materials_.push_back(m);
  patterns_.push_back(p);
  return static_cast<int>(materials_.size()) - 1;
}

}  // namespace render
