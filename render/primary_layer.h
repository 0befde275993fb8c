// More first hits for the denoiser (render/README.md, Denoising): camera rays beyond the
// path samples, each with its albedo and the sun's next event there (a shadow ray),
// through the pixel points that follow the path samples' own in their sequence
// (render/sampling.h's pixel_jitter), so that together they cover the pixel as one longer
// sequence. Roofs, walls, trees and window grids finer than a pixel, in sun or shade, are
// most of a city's error at a few samples (benchmarks/cycles/); these rays cost a fraction
// of a path sample each (no bounce), and give those parts nearer their true mean.
#pragma once

#include "render/camera.h"
#include "render/path_tracer.h"
#include "render/scene.h"
#include "render/sky.h"

namespace render {

// Samples first .. first + count - 1 of each pixel, summed; `camera` in scene coordinates.
// Clear air only: in haze a camera ray's first event need not be a surface; `air`'s
// aerial perspective (Haze::air_density) as the path samples saw it.
Image::Primaries primary_layer(const RenderScene& scene, const Sky& sky, const Camera& camera, int width, int height,
                               int first, int count, const Haze& air = {});

}  // namespace render
