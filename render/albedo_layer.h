// The albedo the denoiser divides out and multiplies back (render/README.md, Denoising):
// the first hits' albedo averaged over a stratified grid of camera rays in each pixel,
// the sky's as white. Texture finer than a pixel (window grids, grass) is then the
// mean the many-sample image converges to, not the few path samples' guess of it, whose
// error the filter could not remove (it keeps the albedo's detail by design).
#pragma once

#include <vector>

#include "render/camera.h"
#include "render/scene.h"
#include "render/vec.h"

namespace render {

// The grid exacity render uses: on tests/render_quality_test.cpp's city, 6x6 gave nearly
// all that 8x8 did (2x2 little), at a fraction of a 16-sample render's time.
inline constexpr int kAlbedoGrid = 6;

// grid x grid camera rays a pixel through the centres of its cells; `camera` in scene
// coordinates. Camera rays alone: a fraction of a path's cost each.
std::vector<V3> albedo_layer(const RenderScene& scene, const Camera& camera, int width, int height, int grid);

}  // namespace render
