#include "render/albedo_layer.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace render {

std::vector<V3> albedo_layer(const RenderScene& scene, const Camera& camera, int width, int height, int grid) {
  std::vector<V3> albedo(static_cast<std::size_t>(width) * height);
  const Lens lens(camera, width, height);
  const float cell = 1.0f / static_cast<float>(grid);
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      V3 sum{0, 0, 0};
      for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
          V3 o, d;
          // A thin lens's points from the R2 sequence (Roberts), so that they do not line
          // up with the grid's: the albedo blurs as the beauty does out of focus.
          const float k = static_cast<float>(j * grid + i) + 0.5f;
          const float lu = k * 0.7548776662f - std::floor(k * 0.7548776662f),
                      lv = k * 0.5698402910f - std::floor(k * 0.5698402910f);
          lens.ray(static_cast<float>(x) + (static_cast<float>(i) + 0.5f) * cell,
                   static_cast<float>(y) + (static_cast<float>(j) + 0.5f) * cell, lu, lv, o, d);
          Surface hit;
          sum += scene.intersect(o, d, INFINITY, hit) ? hit.material.albedo : V3{1, 1, 1};
        }
      albedo[static_cast<std::size_t>(y) * width + x] = sum / static_cast<float>(grid * grid);
    }
  });
  return albedo;
}

}  // namespace render
