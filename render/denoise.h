// The edge-aware denoiser (render/README.md, Denoising): an à-trous wavelet filter
// (Dammertz et al. 2010) over the demodulated irradiance, its edges stopped by the data
// layers the path tracer already keeps (normal, depth, albedo) and by the luminance
// relative to each pixel's own noise (the variance of its mean, as in SVGF, Schied et
// al. 2017). Deterministic: each pixel of each level is a fixed sum, whatever the threads.
#pragma once

#include "render/path_tracer.h"

namespace render {

struct DenoiseSettings {
  int levels = 5;               // the filter's reach: 2^levels pixels each way
  float normal_power = 128;     // cos^p between the normals
  float depth_sigma = 1;        // in the local depth gradient times the distance in pixels
  float albedo_sigma = 0.2f;    // summed albedo difference, per channel
  // In the standard deviation of the pixel's mean; 2 measured best on
  // tests/render_quality_test.cpp's blocks (4 spp against 256), where 4 and 8 blur the
  // shadows' edges and 1 leaves noise.
  float luminance_sigma = 2;
};

// The image with its beauty filtered; the data layers are kept as they are, and the
// variance becomes the filtered estimate's.
Image denoise(const Image& image, const DenoiseSettings& settings = {});

// What exacity render does: denoise() with the albedo layer of kAlbedoGrid^2 camera rays a
// pixel (render/albedo_layer.h) in place of the path samples' own; `camera` in scene
// coordinates, the one `image` was traced with.
Image denoise_render(Image image, const RenderScene& scene, const Camera& camera, const DenoiseSettings& settings = {});

}  // namespace render
