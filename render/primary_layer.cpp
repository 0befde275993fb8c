#include "render/primary_layer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <tuple>
#include <vector>

#include "generate/cancel.h"
#include "render/sampling.h"

namespace render {

Image::Primaries primary_layer(const RenderScene& scene, const Sky& sky, const Camera& camera, int width, int height,
                               int first, int count, const Haze& air) {
  const std::size_t n = static_cast<std::size_t>(width) * height;
  Image::Primaries sums{std::vector<V3>(n), std::vector<V3>(n), count};
  const Lens lens(camera, width, height);
  const exacity::CancelCheck cancel;  // row by row (generate/cancel.h)
  tbb::parallel_for(0, height, [&](int y) {
    cancel.check();
    std::vector<Sampler> rngs;
    rngs.reserve(CameraPacket::kSize);
    CameraPacket packet;
    RayCounts uncounted;
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      V3 albedo{0, 0, 0}, sun{0, 0, 0};
      for (int k0 = first, rays = 0; k0 < first + count; k0 += rays) {
        rays = CameraPacket::size_from(k0, first + count);
        trace_camera_packet(scene, sky, lens, x, y, i, k0, rays, true, rngs, packet, uncounted, air);
        for (int j = 0; j < rays; ++j) {
          V3 a = packet.found[j] ? packet.hits[j].material.albedo : V3{1, 1, 1}, s = packet.sun[j], unused{0, 0, 0};
          packet.through_air(j, unused, a, s);
          albedo += a, sun += s;
        }
      }
      sums.albedo[i] = albedo, sums.sun[i] = sun;
    }
  });
  return sums;
}

}  // namespace render
