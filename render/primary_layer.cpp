#include "render/primary_layer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <tuple>
#include <vector>

#include "render/sampling.h"

namespace render {

Image::Primaries primary_layer(const RenderScene& scene, const Sky& sky, const Camera& camera, int width, int height,
                               int first, int count) {
  const std::size_t n = static_cast<std::size_t>(width) * height;
  Image::Primaries sums{std::vector<V3>(n), std::vector<V3>(n), count};
  const Lens lens(camera, width, height);
  tbb::parallel_for(0, height, [&](int y) {
    constexpr int kPacket = RenderScene::kPacket;
    std::vector<Sampler> rngs;
    rngs.reserve(kPacket);
    RayCounts uncounted;
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      V3 albedo{0, 0, 0}, sun{0, 0, 0};
      // A pixel's rays in packets: their camera rays, then their shadow rays to the sun.
      for (int k0 = first; k0 < first + count; k0 += kPacket) {
        const int rays = std::min(kPacket, first + count - k0);
        V3 o[kPacket], d[kPacket];
        camera_rays(lens, x, y, i, k0, rays, rngs, o, d);
        Surface hits[kPacket];
        bool found[kPacket];
        scene.intersect_packet(o, d, rays, hits, found);
        V3 light[kPacket];
        first_surfaces_sun(scene, sky, d, hits, found, rays, rngs, light, uncounted);
        for (int j = 0; j < rays; ++j) albedo += found[j] ? hits[j].material.albedo : V3{1, 1, 1}, sun += light[j];
      }
      sums.albedo[i] = albedo, sums.sun[i] = sun;
    }
  });
  return sums;
}

}  // namespace render
