#include "render/primary_layer.h"

#include <tbb/parallel_for.h>

#include <tuple>

#include "render/sampling.h"

namespace render {

Image::Primaries primary_layer(const RenderScene& scene, const Sky& sky, const Camera& camera, int width, int height,
                               int first, int count) {
  const std::size_t n = static_cast<std::size_t>(width) * height;
  Image::Primaries sums{std::vector<V3>(n), std::vector<V3>(n), count};
  const Lens lens(camera, width, height);
  tbb::parallel_for(0, height, [&](int y) {
    RayCounts counts;
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      V3 albedo{0, 0, 0}, sun{0, 0, 0};
      for (int k = first; k < first + count; ++k) {
        // Sample k's pixel point and lens point, as the path tracer would draw them.
        Sampler rng(i, static_cast<std::uint64_t>(k));
        float jx, jy;
        pixel_jitter(static_cast<std::uint64_t>(k), jx, jy);
        float lu = 0.5f, lv = 0.5f;
        if (lens.thin_lens()) std::tie(lu, lv) = rng.next2();
        V3 o, d;
        lens.ray(static_cast<float>(x) + jx, static_cast<float>(y) + jy, lu, lv, o, d);
        Surface hit;
        if (!scene.intersect(o, d, INFINITY, hit)) {
          albedo += V3{1, 1, 1};
          continue;
        }
        albedo += hit.material.albedo;
        sun += first_hit_sun(scene, sky, d, hit, rng, counts);
      }
      sums.albedo[i] = albedo, sums.sun[i] = sun;
    }
  });
  return sums;
}

}  // namespace render
