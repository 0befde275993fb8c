// The path tracer (Embree's tutorial layout: render a tile, render a pixel, shade): next
// event estimation towards the sun and the sky, each combined with the surface's own
// sampling by multiple importance sampling (power heuristic); Russian roulette after
// three bounces.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "render/camera.h"
#include "render/night.h"
#include "render/sampling.h"
#include "render/scene.h"
#include "render/sky.h"

namespace render {

struct Image {
  int width = 0, height = 0;
  std::vector<V3> beauty;          // linear radiance, the mean of the samples
  std::vector<float> depth;        // distance to the first hit (infinity: sky)
  std::vector<V3> normal, albedo;  // of the first hit, world space
  std::vector<std::uint32_t> id;   // the first hit's entity (see Entity)
  // For the denoiser (render/denoise.h): the variance of the mean's luminance (the
  // samples' over their count), and the first hits' albedo over all samples, the sky's
  // as white, so that a texture finer than a pixel is divided out as the beauty saw it.
  std::vector<float> variance;
  std::vector<V3> mean_albedo;
  // The samples in two halves, even- and odd-numbered, each with its mean beauty, first-hit
  // albedo and sun's next event at the first hit (part of the beauty): two independent
  // estimates of the image, whose differences tell the denoiser how far it may smooth
  // each pixel. Empty where the image did not come from a Film of two samples or more.
  struct Half {
    std::vector<V3> beauty, albedo, sun;
    int samples = 0;
    std::vector<V3> inscatter;  // as Image::inscatter; empty in clear air
  };
  std::array<Half, 2> halves;
  std::vector<V3> first_sun;  // over all samples
  // In haze (render/README.md, Denoising in haze): the light the camera ray's haze scattered
  // towards the camera more than once, part of the beauty, which the denoiser smooths
  // apart; and the mean transmittance of the haze to the first surface (0 for the sky),
  // which guides it. Empty in clear air.
  std::vector<V3> inscatter;
  std::vector<float> seen;
  // Camera rays beyond the path samples (render/primary_layer.h): the sums of their first
  // hits' albedo and sun next event, which the denoiser adds to the path samples' own.
  struct Primaries {
    std::vector<V3> albedo, sun;
    int samples = 0;
  };
  Primaries extra;
};

// A homogeneous layer of haze from the ground up to `top` (scene z): light scatters in it
// (Henyey–Greenstein, asymmetry g) and is not absorbed, which gives aerial perspective
// and, where buildings shade it from the sun, light shafts, physically.
struct Haze {
  float density = 0;  // scattering per metre; 0: clear air
  float top = 500;
  float g = 0.7f;
  // Koschmieder: the visibility at which contrast falls to 2%.
  static float density_for_visibility(float metres) { return 3.912f / metres; }
  // Clear air's aerial perspective, where density is 0: on a camera ray, a surface's light
  // is dimmed by the air's transmittance and the horizon sky's light in that direction,
  // scattered in, makes up the rest, so distance fades towards the sky's colour (the
  // single-scattering fog of Hoffman and Preetham's "Rendering outdoor light scattering in
  // real time", 2002, with the horizon's sky radiance standing for the light scattered in).
  // The air thins with height: extinction air_density at air_ground, e-folding every
  // kAirScaleHeight metres up, as the aerosols near the ground do. 0: none.
  float air_density = 0, air_ground = 0;
  static constexpr float kAirScaleHeight = 1200;
  // The air's transmittance along the ray from o towards d, t metres long (infinite: to the sky).
  float air_transmittance(V3 o, V3 d, float t) const;
};

struct TraceSettings {
  TraceSettings() = default;
  TraceSettings(int w, int h, int samples, int depth = 8, Haze fog = {})
      : width(w), height(h), spp(samples), max_depth(depth), haze(fog) {}
  int width = 960, height = 540, spp = 16;
  int max_depth = 8;
  Haze haze;
  const StreetLights* lights = nullptr;  // at night (render/night.h); none by day
};

struct RayCounts {
  std::uint64_t camera = 0, bounce = 0, shadow = 0;
  RayCounts& operator+=(const RayCounts& o) {
    camera += o.camera, bounce += o.bounce, shadow += o.shadow;
    return *this;
  }
};

// Called with the tiles done and the tile count, from the calling thread only.
using TileProgress = std::function<void(int, int)>;

// A pixel's samples summed as they come, so that passes of samples can follow one another
// (progressive rendering, render/README.md): after passes of n1, n2, ... samples the image
// is the same bytes as one trace of n1 + n2 + ... samples, whatever the pass sizes.
struct Film {
  Film(int width, int height);
  Image layers;  // the size and the data layers (depth, normal, albedo, id), from sample 0
  std::vector<V3> sum, albedo_sum;
  std::vector<V3> sun_sum;                                  // Image::first_sun's
  std::vector<V3> even_sum, even_albedo_sum, even_sun_sum;  // the even-numbered samples' (Image::halves)
  std::vector<V3> inscatter_sum, even_inscatter_sum;        // in haze (Image::inscatter)
  std::vector<float> seen_sum;
  std::vector<double> luminance_squares;
  int samples = 0;
  // The mean of the samples so far and its variance, with the data layers.
  Image image() const;
};

// Adds settings.spp samples a pixel to `film`, numbered on from those it holds.
void add_samples(Film& film, const RenderScene& scene, const Sky& sky, const Camera& camera,
                 const TraceSettings& settings, RayCounts* counts = nullptr, const TileProgress& progress = nullptr);

// `camera` in scene coordinates.
Image trace(const RenderScene& scene, const Sky& sky, const Camera& camera, const TraceSettings& settings,
            RayCounts* counts = nullptr, const TileProgress& progress = nullptr);

// One path's radiance along a ray (exposed for tests); the rays it casts are added to
// `counts`. The sun's next event at the first surface, and in haze the sunlight the ray's
// haze scatters once towards it, part of the radiance, are also added to `first_sun`
// where given.
V3 radiance(const RenderScene& scene, const Sky& sky, V3 origin, V3 direction, Sampler& rng, int max_depth,
            RayCounts& counts, Surface* first = nullptr, const Haze& haze = {}, V3* first_sun = nullptr,
            const StreetLights* lights = nullptr);

// The haze's transmittance along the ray from o towards d, t long (1 in clear air).
float haze_transmittance(const Haze& haze, V3 o, V3 d, float t);

// A pixel's camera rays traced as one Embree packet (RenderScene::intersect_packet), with
// the sun's next events at their first surfaces where asked, whose shadow rays make one more.
struct CameraPacket {
  static constexpr int kSize = RenderScene::kPacket;
  // How many samples from k0 (before `end`) make its packet: packets run between multiples
  // of kSize, by sample number alone, so passes of samples that are multiples of kSize
  // trace the very packets one trace of them all would.
  static int size_from(int k0, int end) { return std::min(end, (k0 / kSize + 1) * kSize) - k0; }
  int n = 0;
  V3 o[kSize], d[kSize];
  Surface hits[kSize];
  bool found[kSize];
  V3 sun[kSize];
  // Clear air's aerial perspective on each ray (Haze::air_density): the transmittance to
  // its surface and the light scattered in (1 and 0 without it, or where it met nothing).
  float fade[kSize];
  V3 inscattered[kSize];
  // The sample's beauty, first-hit albedo and sun next event as seen through the air.
  void through_air(int j, V3& beauty, V3& albedo, V3& sun) const {
    beauty = beauty * fade[j] + inscattered[j], albedo = albedo * fade[j] + V3{1, 1, 1} * (1 - fade[j]);
    sun = sun * fade[j];
  }  // the sun at each first surface: zero where the ray met nothing or it was blocked
};

// Camera rays k0 .. k0 + n - 1 (n at most CameraPacket::kSize) of pixel (x, y), numbered
// `pixel`, as add_samples draws them; with `with_sun` (clear air only), their first
// surfaces' sun next events too, as radiance() adds them to `first_sun`; and the clear air's
// fade (`air`'s air_density, where its density is 0). Each sample's sampler, past the draws
// made here, is left in `rngs` for its path.
void trace_camera_packet(const RenderScene& scene, const Sky& sky, const Lens& lens, int x, int y, std::size_t pixel,
                         int k0, int n, bool with_sun, std::vector<Sampler>& rngs, CameraPacket& packet,
                         RayCounts& counts, const Haze& air = {});

// Henyey–Greenstein's phase function for the angle between the light's old and new
// directions, and a new direction drawn from it.
float henyey_greenstein(float cos_theta, float g);
V3 sample_henyey_greenstein(V3 direction, float g, float u1, float u2);

}  // namespace render
