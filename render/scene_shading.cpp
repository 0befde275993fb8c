// The surface a ray met: its entity, its normal facing the ray, and its material with the
// texture and pattern at the hit.
#include <algorithm>
#include <cmath>

#include "render/noise.h"
#include "render/paving.h"
#include "render/scene_build.h"

namespace render {

namespace {

const Noise& noise() {
  static const Noise n;
  return n;
}

}  // namespace

// The surface a ray met, from Embree's hit, or the ground plane past the city.
bool RenderScene::surface(V3 o, V3 d, float tmax, const Hit& hit, Surface& s) const {
  int m;
  const std::array<exacity::Uv, 3>* textured = nullptr;  // the hit triangle's texture coordinates
  float hit_u = 0, hit_v = 0;                            // and its barycentric place in it
  if (hit.geom == RTC_INVALID_GEOMETRY_ID) {
    // The ground plane beyond the city.
    if (!ground_plane_ || d.z >= 0 || o.z <= ground) return false;
    const float t = (ground - o.z) / d.z;
    if (t > tmax) return false;
    s.distance = t;
    s.position = o + d * t;
    s.normal = {0, 0, 1};
    s.entity = entity_id(Entity::Terrain, 0);
    m = grass_material_;
  } else {
    s.distance = hit.t;
    s.position = o + d * hit.t;
    V3 n = hit.ng;
    if (hit.inst != RTC_INVALID_GEOMETRY_ID) {
      const Geometry& g = geometries_[hit.inst];
      n = {g.cos_turn * n.x - g.sin_turn * n.y, g.sin_turn * n.x + g.cos_turn * n.y, n.z};
      m = g.instance_override >= 0 ? g.instance_override : g.material_base + g.material_of(hit.prim);
      s.entity = g.instance_entity;
      if (g.uv) textured = &(*g.uv)[hit.prim], hit_u = hit.u, hit_v = hit.v;
    } else {
      const Geometry& g = geometries_[hit.geom];
      m = g.material[hit.prim];
      s.entity = g.entity[hit.prim];
    }
    s.normal = normalize(n);
    if (dot(s.normal, d) > 0) s.normal = s.normal * -1;
  }
  s.material = materials_[m];
  if (textured && static_cast<std::size_t>(m) < material_textures_.size() && material_textures_[m].texture) {
    // Embree's u and v weigh the triangle's second and third corners.
    const exacity::Uv& a = (*textured)[0];
    const exacity::Uv& b = (*textured)[1];
    const exacity::Uv& c = (*textured)[2];
    const float w = 1 - hit_u - hit_v;
    const float u = static_cast<float>(w * a[0] + hit_u * b[0] + hit_v * c[0]);
    const float v = static_cast<float>(w * a[1] + hit_u * b[1] + hit_v * c[1]);
    s.material.albedo = s.material.albedo * material_textures_[m].texture->sample(u, v, material_textures_[m].clamp);
  }
  switch (patterns_[m]) {
    case Pattern::Windows: {
      // The building's own rows and bays (render/facade.h); a soup's walls keep the default.
      const std::size_t id = s.entity & 0xffffff;
      const FacadeStyle style = id < facades_.size() ? facades_[id] : FacadeStyle{};
      s.material = facade_material(style, s.material, s.position, s.normal);
      s.spread_emission = spread_window_light(style, s.position, s.normal);
      break;
    }
    case Pattern::Roof:
      s.material = roof_material(s.material, s.position, s.normal);
      break;
    case Pattern::Paving:
      s.material = paving_material(s.material, s.position);
      break;
    case Pattern::Grass: {
      const float beyond = landscape_ && s.entity >> 24 == static_cast<std::uint32_t>(Entity::Terrain)
                               ? landscape_->beyond(s.position.x, s.position.y)
                               : 0.0f;
      if (beyond >= 1) {
        s.material.albedo = landscape_->albedo(s.position.x, s.position.y);
        break;
      }
      const float coarse = noise().fractal(s.position.x * 0.02f, s.position.y * 0.02f, 2);
      const float fine = noise()(s.position.x * 0.9f, s.position.y * 0.9f);
      const V3 lush = colour(exacity::kLushGrassAlbedo), dry = colour(exacity::kDryGrassAlbedo);
      const float t = std::clamp(0.5f + coarse * 1.2f, 0.0f, 1.0f);
      // Tufts and blades a few centimetres across, which at eye level make grass of what
      // were metre-wide blurred blobs; from the air a pixel's rays average them out.
      const float tufts = noise()(s.position.x * 7.3f, s.position.y * 7.3f), blades = noise()(s.position.x * 31, s.position.y * 29);
      s.material.albedo = (lush * (1 - t) + dry * t) * (0.85f + 0.3f * fine) * (1 + 0.35f * tufts + 0.3f * blades);
      if (beyond > 0) s.material.albedo = s.material.albedo * (1 - beyond) + landscape_->albedo(s.position.x, s.position.y) * beyond;
      break;
    }
    case Pattern::None:
      break;
  }
  if (patterns_[m] != Pattern::Windows) s.spread_emission = s.material.emission;
  return true;
}

}  // namespace render
