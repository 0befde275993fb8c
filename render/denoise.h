// The denoiser (render/README.md, Denoising): an à-trous wavelet filter (Dammertz et al.
// 2010) over the light with the first hit's albedo divided out and the sun's next event
// there split off, its edges stopped by the data layers the path tracer keeps (normal,
// depth, albedo) and by the luminance relative to each pixel's own noise (as in SVGF,
// Schied et al. 2017). It filters the even- and the odd-numbered samples apart, and each
// pixel takes the level, the unfiltered image included, whose error the two halves tell
// by cross-validation is least, so where the image has converged it stays as it is.
// Deterministic: each pixel of each level is a fixed sum, whatever the threads.
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
  // The neighbourhood, (2r+1)^2 pixels, over which the halves' cross-validation error is
  // averaged before each pixel picks its level: the Cycles comparison's view measured
  // 3 a little worse, 2 worse again (one pixel's error is too noisy to choose by).
  int selection_radius = 5;
  // The most camera rays a pixel denoise_render adds beyond the path samples
  // (render/primary_layer.h; primary_rays() below): on the Cycles comparison's view 16 cut
  // the error at 16 samples from 0.0219 to 0.0149, 32 to 0.0129, 64 to 0.0112 at nearly
  // twice 32's cost; 32 gave the most for the time.
  int primary_rays = 32;
};

// The image with its beauty filtered; the data layers are kept as they are, and the
// variance becomes the filtered estimate's. Uses the image's halves (Image::halves) and
// its primary layer (Image::extra) where it has them.
Image denoise(const Image& image, const DenoiseSettings& settings = {});

// The primary layer's rays a pixel for an image of `samples` path samples: half as many,
// 8 to settings.primary_rays. A primary ray costs about a third of a path sample, so the
// layer costs a sixth of the tracing (more under 16 samples, where 8 rays are the least
// that help): with the filter, the denoiser stays under half the tracing at 16 samples.
int primary_rays(int samples, const DenoiseSettings& settings = {});

// How long denoise() takes on `image` here, with a primary layer (Image::extra) or without:
// bands of its rows filtered, timed and scaled (the filter's work is nearly the same for
// every surface pixel); for a time budget. An image of one sample is timed as one of two
// (the filter of the samples to come), unless `as_it_is`: one estimate, a third the work.
double filter_seconds(const Image& image, bool primary_layer, bool as_it_is = false, const DenoiseSettings& settings = {});

// What exacity render does: the primary layer's rays (none in haze), then denoise();
// the scene, sky, camera (in scene coordinates) and haze `image` was traced with. The
// primary layer's wall time goes to `primary_layer_s` if given.
Image denoise_render(Image image, const RenderScene& scene, const Sky& sky, const Camera& camera, const Haze& haze,
                     const DenoiseSettings& settings = {}, double* primary_layer_s = nullptr);

}  // namespace render
