// Renders a person would keep (render/README.md: Denoising, Tone mapping, Progressive
// rendering, Camera paths): the denoiser brings a few samples nearer a many-sample
// reference, keeps a normal's edge and leaves a converged image as it is; passes of samples add up to one trace bit for bit;
// white balance by hand; camera paths through their keys, their bad files in one line,
// and a frame the same bytes whichever range rendered it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "generate/pipeline.h"
#include "render/camera_path.h"
#include "render/denoise.h"
#include "render/image_error.h"
#include "render/image_io.h"
#include "render/pass_budget.h"
#include "render/path_tracer.h"
#include "render/render.h"
#include "render/render_path.h"
#include "render/scene.h"
#include "render/white_balance.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

using namespace render;
namespace fs = std::filesystem;

namespace {

exacity::City small_city() {
  const std::string text = R"({"type": "FeatureCollection", "exacity": {"seed": 3}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [400, 0], [400, 300], [0, 300], [0, 0]]]}}]})";
  exacity::Sketch sketch = exacity::parse_sketch(text, "quality.geojson");
  exacity::StageClock clock(nullptr, exacity::kCityStages);
  return exacity::build_city(sketch, clock);
}

// A plane with two blocks on it, one lifted on a post so the ground under it is lit by
// the sky alone.
std::vector<TriangleSoup> blocks_on_a_plane() {
  TriangleSoup plane;
  plane.vertices = {{-500, -500, 0}, {500, -500, 0}, {500, 500, 0}, {-500, 500, 0}};
  plane.triangles = {{0, 1, 2}, {0, 2, 3}};
  plane.material = {Material::Diffuse, {0.5f, 0.4f, 0.3f}};
  auto block = [](V3 lo, V3 hi, V3 albedo) {
    TriangleSoup b;
    for (int i = 0; i < 8; ++i) b.vertices.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    b.triangles = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                   {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
    b.material = {Material::Diffuse, albedo};
    return b;
  };
  return {plane, block({-5, -5, 0}, {5, 5, 10}, {0.8f, 0.8f, 0.8f}), block({8, -4, 4}, {16, 4, 6}, {0.7f, 0.3f, 0.2f}),
          block({11, -1, 0}, {13, 1, 4}, {0.3f, 0.3f, 0.3f})};
}

}  // namespace

TEST(Denoise, BringsAFewSamplesNearerAManySampleReference) {
  // Blocks on a plane in sun and sky light: shadows, sky light under overhangs, and the
  // noise of a few samples; the filter must bring 4 samples nearer 256 as a person sees
  // them (tone-mapped), edges and shadows included.
  RenderScene scene(blocks_on_a_plane());
  const Sky sky(200, 40);
  const Camera c = Camera::look({-30, -40, 25}, {0, 0, 3}, 50);
  const Image raw = trace(scene, sky, c, TraceSettings{64, 48, 4});
  const Image reference = trace(scene, sky, c, TraceSettings{64, 48, 256});
  const double before = display_rmse(raw, reference), after = display_rmse(denoise(raw), reference);
  EXPECT_LT(after, 0.7 * before) << "raw " << before << ", denoised " << after;
}

TEST(Denoise, BringsACitysFewSamplesNearerWithItsPrimaryLayer) {
  // Roofs, walls, window grids and grass are finer than a pixel here: the primary layer's
  // camera rays, with their albedo and sun, carry them; the path samples' own leave their
  // sampling error in, which no filter of the image removes.
  const exacity::City city = small_city();
  const Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  const Camera c = scene.to_scene(Camera::orbit({200, 150, 0}, 235, 25, 120, 45));
  const Image raw = trace(scene, sky, c, TraceSettings{64, 48, 4});
  const Image reference = trace(scene, sky, c, TraceSettings{64, 48, 256});
  const double before = display_rmse(raw, reference), alone = display_rmse(denoise(raw), reference),
               after = display_rmse(denoise_render(raw, scene, sky, c, Haze{}), reference);
  EXPECT_LT(after, 0.7 * before) << "raw " << before << ", denoised " << after;
  EXPECT_LT(after, 0.85 * alone) << "the primary layer must help: without it " << alone;
}

// The denoiser at most half the tracing's time at 16 samples: with 32 primary rays a
// pixel at any count it cost 0.8 of the tracing there. Its time is a benchmark's
// (docs/benchmarks.md, The denoiser's cost and --time); what a test can hold is its work:
// at 16 samples the primary layer casts 8 camera rays a pixel and at most a shadow ray
// from each, a small share of the rays the path samples cast on a city.
TEST(Denoise, ItsPrimaryLayerAtSixteenSamplesCastsAFewOfTheTracingsRays) {
  const exacity::City city = small_city();
  const Sky sky(200, 40);
  RenderScene scene(city, sky.sun_direction(), SceneOptions{});
  const Camera c = scene.to_scene(Camera::orbit({200, 150, 0}, 235, 25, 120, 45));
  const int w = 32, h = 24, spp = 16;
  Film film(w, h);
  RayCounts traced;
  add_samples(film, scene, sky, c, TraceSettings{w, h, spp}, &traced);
  const double tracing = static_cast<double>(traced.camera + traced.bounce + traced.shadow);
  const double layer = 2.0 * primary_rays(spp) * w * h;
  EXPECT_EQ(primary_rays(spp), spp / 2);
  EXPECT_LT(layer / tracing, 0.3) << "the tracing cast " << tracing / (w * h) << " rays a pixel";
}

// Haze of 1500 m visibility over blocks on a plane, 150 m off, the sun behind the camera's
// left: most of the light is the haze's, scattered many times. Two traces of 16 samples,
// independent (samples 0 to 15 and 16 to 31 of each pixel), differ by twice the grain of
// one, as a person sees them (tone-mapped), traced and denoised; and the denoised image's
// mean over blocks of 8x8 pixels stays near the many-sample reference's (the filter may
// smooth, not shift: by up to 9%, where the samples' own mean errs by 3%). The denoiser
// took the haze's light as the rest of a pixel's, stopped by its luminance against the
// pixel's noise: 0.0209 of grain (traced, 0.0686), blotches in the sky; with the light
// scattered more than once smoothed apart, 0.0139, the sky clean, the grain left the
// ground's (its light from the haze, bounced off it).
TEST(Denoise, HazeConvergesAtAFewSamples) {
  std::vector<TriangleSoup> soups = blocks_on_a_plane();
  for (V3& v : soups[0].vertices) v = v * 40;  // the plane to the horizon, 20 km across
  RenderScene scene(soups);
  const Sky sky(160, 30);
  const Haze haze{Haze::density_for_visibility(1500), 500, 0.7f};
  const Camera c = Camera::look({-90, -120, 12}, {0, 0, 6}, 30);
  const int w = 48, h = 32;
  const TraceSettings settings{w, h, 16, 8, haze};
  Film first(w, h), second(w, h);
  add_samples(first, scene, sky, c, settings);
  second.layers = first.layers, second.samples = 16;  // samples 16 to 31, on the same data layers
  add_samples(second, scene, sky, c, settings);
  second.samples = 16;  // its sums hold those 16 alone
  const Image a = first.image(), b = second.image();
  const double traced = display_rmse(a, b) / std::sqrt(2.0), denoised = display_rmse(denoise(a), denoise(b)) / std::sqrt(2.0);
  EXPECT_LT(denoised, 0.017) << "the denoised grain; traced " << traced;
  // The mean over 8x8 blocks, against 256 samples'.
  const Image reference = trace(scene, sky, c, TraceSettings{w, h, 256, 8, haze});
  const Image smooth = denoise(a);
  for (int by = 0; by < h; by += 8)
    for (int bx = 0; bx < w; bx += 8) {
      double got = 0, want = 0;
      for (int y = by; y < by + 8; ++y)
        for (int x = bx; x < bx + 8; ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * w + x;
          got += luminance(smooth.beauty[i]), want += luminance(reference.beauty[i]);
        }
      EXPECT_NEAR(got, want, 0.1 * want) << "block at " << bx << ", " << by;
    }
}

TEST(Denoise, FlattensNoiseButKeepsANormalsEdge) {
  // Left half faces up and has radiance 1, the right half faces east and has 0.2; each
  // pixel's value is off by up to +-30% (a fixed pseudo-random pattern), its variance set
  // to match. The filter must flatten each half and leave the step where it is.
  Image img;
  img.width = 32, img.height = 24;
  std::uint64_t state = 12345;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const bool left = x < 16;
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      const float u = static_cast<float>(state >> 40) * 0x1.0p-24f * 2 - 1;  // [-1, 1)
      const float truth = left ? 1.0f : 0.2f, v = truth * (1 + 0.3f * u);
      img.beauty.push_back({v, v, v});
      img.variance.push_back(truth * truth * 0.09f / 3);
      img.depth.push_back(50);
      img.normal.push_back(left ? V3{0, 0, 1} : V3{1, 0, 0});
      img.albedo.push_back({0.5f, 0.5f, 0.5f});
      img.id.push_back(0);
    }
  const Image out = denoise(img);
  for (int half = 0; half < 2; ++half) {
    const float truth = half == 0 ? 1.0f : 0.2f;
    double before = 0, after = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = half * 16; x < half * 16 + 16; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
        before += std::pow(img.beauty[i].x - truth, 2), after += std::pow(out.beauty[i].x - truth, 2);
        // Beside the step too, each side keeps its own level.
        EXPECT_NEAR(out.beauty[i].x, truth, 0.12 * truth) << x << "," << y;
      }
    EXPECT_LT(after, before / 9) << "half " << half;
  }
}

namespace {

// A synthetic image of two halves of 8 samples each, as a Film gives: each pixel's
// `truth(x)` times (1 + noise x u) in each half, u a fixed pseudo-random pattern in
// [-1, 1), the variance of the mean set to match; one normal, depth and albedo everywhere
// (the guides see nothing), no sun split off.
Image halves_image(int width, int height, float noise, const std::function<float(int)>& truth) {
  Image img;
  img.width = width, img.height = height;
  std::uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<float>(state >> 40) * 0x1.0p-24f * 2 - 1;
  };
  for (Image::Half& h : img.halves) h.samples = 8;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float t = truth(x), a = t * (1 + noise * next()), b = t * (1 + noise * next());
      img.halves[0].beauty.push_back({a, a, a}), img.halves[1].beauty.push_back({b, b, b});
      for (Image::Half& h : img.halves) h.albedo.push_back({0.5f, 0.5f, 0.5f}), h.sun.push_back({0, 0, 0});
      img.beauty.push_back({(a + b) / 2, (a + b) / 2, (a + b) / 2});
      // Each half's variance t^2 noise^2 / 3, the mean of two halves' half of it.
      img.variance.push_back(t * t * noise * noise / 6);
      img.depth.push_back(50), img.normal.push_back({0, 0, 1}), img.albedo.push_back({0.5f, 0.5f, 0.5f});
      img.mean_albedo.push_back({0.5f, 0.5f, 0.5f}), img.first_sun.push_back({0, 0, 0}), img.id.push_back(0);
    }
  return img;
}

}  // namespace

TEST(Denoise, LeavesAConvergedImageAsItIs) {
  // Stripes one pixel wide that no guide tells apart (light 1 and 0.3 in turn), with 0.5%
  // noise: the image has converged, and the filter must not blur what it cannot see.
  auto stripes = [](int x) { return x % 2 ? 1.0f : 0.3f; };
  const Image img = halves_image(32, 24, 0.005f, stripes);
  const Image out = denoise(img);
  double change = 0;
  for (std::size_t i = 0; i < img.beauty.size(); ++i) {
    EXPECT_NEAR(out.beauty[i].x, img.beauty[i].x, 0.02 * img.beauty[i].x) << i;
    change += std::pow(out.beauty[i].x - img.beauty[i].x, 2);
  }
  EXPECT_LT(std::sqrt(change / static_cast<double>(img.beauty.size())), 0.005);
}

TEST(Denoise, HalvesBringANoisyImageNearItsTruth) {
  // The same stripes, under +-30% noise but over blocks of 8 pixels: the filter must
  // smooth within a block, where it brings the image nearer the truth, and choose the
  // unfiltered image across the blocks' edges, which it cannot see.
  auto blocks = [](int x) { return (x / 8) % 2 ? 1.0f : 0.3f; };
  const Image img = halves_image(32, 24, 0.3f, blocks);
  const Image out = denoise(img);
  double before = 0, after = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
      before += std::pow(img.beauty[i].x - blocks(x), 2), after += std::pow(out.beauty[i].x - blocks(x), 2);
    }
  EXPECT_LT(after, before / 5) << "before " << before << ", after " << after;
}

TEST(Denoise, ChangesAManySampleRenderLittle) {
  // Blocks on a plane at 512 samples: the denoised image stays within what a person sees
  // as the same (RMSE of the tone-mapped images).
  RenderScene scene(blocks_on_a_plane());
  const Sky sky(200, 40);
  const Camera c = Camera::look({-30, -40, 25}, {0, 0, 3}, 50);
  const Image converged = trace(scene, sky, c, TraceSettings{48, 32, 512});
  const double change = display_rmse(denoise_render(converged, scene, sky, c, Haze{}), converged);
  EXPECT_LT(change, 0.004) << change;
}

TEST(Film, PassesOfSamplesAddUpToOneTraceBitForBit) {
  RenderScene scene(blocks_on_a_plane());
  const Sky sky(200, 40);
  const Camera c = Camera::look({-30, -40, 25}, {0, 0, 3}, 50);
  // Passes that cut the camera rays' packets of 16 (RenderScene::kPacket) differently.
  const Image whole = trace(scene, sky, c, TraceSettings{24, 16, 37});
  Film film(24, 16);
  for (int spp : {2, 1, 18, 16}) add_samples(film, scene, sky, c, TraceSettings{24, 16, spp});
  const Image passes = film.image();
  ASSERT_EQ(film.samples, 37);
  for (std::size_t i = 0; i < whole.beauty.size(); ++i) {
    EXPECT_EQ(whole.beauty[i].x, passes.beauty[i].x) << i;
    EXPECT_EQ(whole.beauty[i].z, passes.beauty[i].z) << i;
    EXPECT_EQ(whole.variance[i], passes.variance[i]) << i;
    EXPECT_EQ(whole.depth[i], passes.depth[i]) << i;
  }
  // And more passes are a different, less noisy image: the passes count.
  add_samples(film, scene, sky, c, TraceSettings{24, 16, 3});
  double variance_37 = 0, variance_40 = 0;
  const Image more = film.image();
  for (std::size_t i = 0; i < whole.beauty.size(); ++i) variance_37 += whole.variance[i], variance_40 += more.variance[i];
  EXPECT_LT(variance_40, variance_37);
}

// A time budget is the whole still's, the scene's build and the denoiser included: one
// spent before the first pass is traced gives that pass alone, of one sample, not spp
// (a whole pass of spp ran however far past the budget it took), and the denoiser, which
// would end past the budget, is left out (it ran whatever the budget, and took longer
// than the tracing).
TEST(Film, ABudgetSpentBeforeTracingGivesOnePassAndNoDenoiser) {
  const exacity::City city = small_city();
  RenderRequest request;
  request.camera = Camera::orbit({200, 150, 0}, 235, 25, 120, 45);
  request.width = 32, request.height = 24, request.spp = 8;
  request.time_budget_s = 1e-6;  // the scene's build alone takes longer
  const auto dir = testing_util::temp_dir("spent-budget");
  request.still = dir / "still.png";
  const nlohmann::ordered_json report = render_city(city, request);
  EXPECT_EQ(report["passes"], 1);
  EXPECT_EQ(report["samples_per_pixel"], 1);
  EXPECT_EQ(report["denoised"], false);
  // With no budget the same request is denoised, with half its samples' primary rays,
  // eight at least.
  request.time_budget_s = 0;
  const nlohmann::ordered_json whole = render_city(city, request);
  EXPECT_EQ(whole["denoised"], true);
  EXPECT_EQ(whole["primary_rays"], 8);
}

// The passes under a time budget, on a clock of the test's own: a sample costs 1/8 s
// (binary fractions, so the sums are exact), the city and the scene took the first second
// of a 3 s budget. The first pass is one sample; then passes of up to spp that fit, the last
// shrunk to end on the budget; with the finishing (the denoiser) foretold, room is left
// for it; a pass that runs long (the machine slowed down) and ends past the budget is the
// last; a budget spent before tracing gives one pass of one sample; the writing's time is
// kept free too, and when the first pass and the writing end past the budget it is known.
TEST(PassBudget, PassesFitTheBudgetAndStopAfterThePassThatReachesIt) {
  double clock = 1, slowdown = 1;
  std::size_t slow_pass = 0;  // the pass (from 1) that runs `slowdown` times as long
  std::vector<int> passes;
  auto trace = [&](int n) {
    passes.push_back(n);
    clock += 0.125 * n * (passes.size() == slow_pass ? slowdown : 1);
  };
  auto now = [&] { return clock; };
  PassBudget budget{3, 4};
  Passes done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1, 4, 4, 4, 3}));
  EXPECT_EQ(done.passes, 5);
  EXPECT_EQ(done.samples, 16);
  EXPECT_EQ(done.traced_s, 2);
  EXPECT_EQ(clock, 3);

  // A quarter second of finishing after whatever was traced.
  budget.finish_s = [](int, double) { return 0.25; };
  clock = 1, passes.clear();
  done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1, 4, 4, 4, 1}));
  EXPECT_EQ(clock + 0.25, 3);

  // The third pass takes four times as long as foretold: it ends past the budget, and
  // nothing is traced after it.
  budget.finish_s = [](int, double) { return 0.0; };
  clock = 1, passes.clear(), slow_pass = 3, slowdown = 4;
  done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1, 4, 4}));
  EXPECT_EQ(clock, 3.625);

  // Spent before the first pass: that pass alone, of one sample.
  clock = 5, passes.clear(), slow_pass = 0;
  done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1}));
  EXPECT_EQ(done.samples, 1);

  // Half a second of writing: kept free after the passes, which end where it begins.
  budget.write_s = [] { return 0.5; };
  clock = 1, passes.clear();
  done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1, 4, 4, 3}));
  EXPECT_EQ(clock + 0.5, 3);
  EXPECT_EQ(done.least_s, 1.625);  // the first pass, then the writing

  // The city and scene took 2.75 s: the first pass and the writing end at 3.375 s, past
  // 3 s and its tenth, which the command says.
  clock = 2.75, passes.clear();
  done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1}));
  EXPECT_EQ(done.least_s, 3.375);

  // A finishing of 2 s from two samples on (the filter and its primary layer, which one
  // sample does without) fits after no pass: the still stopped at its first sample with
  // most of the budget left. With the least finishing (the filter alone, a quarter second)
  // the passes are planned with that from then on.
  budget.write_s = [] { return 0.0; };
  budget.finish_s = [](int samples, double) { return samples >= 2 ? 2.0 : 0.25; };
  clock = 1, passes.clear();
  done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1}));
  budget.least_finish_s = [](int, double) { return 0.25; };
  clock = 1, passes.clear();
  done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1, 4, 4, 4, 1}));
  EXPECT_EQ(clock + 0.25, 3);
  // Where the whole finishing fits after the first pass, it is planned for, not the least.
  budget.finish_s = [](int, double) { return 0.5; };
  clock = 1, passes.clear();
  done = run_passes(budget, trace, now);
  EXPECT_EQ(passes, (std::vector<int>{1, 4, 4, 3}));
  EXPECT_EQ(clock + 0.5, 3);
}

TEST(ToneMap, WhiteBalanceMakesItsBlackBodyNeutral) {
  const V3 one = white_balance_gains(kNeutralKelvin);
  EXPECT_EQ(one.x, 1);
  EXPECT_EQ(one.y, 1);
  EXPECT_EQ(one.z, 1);
  // The sRGB white is near the 6500 K black body (D65 lies just off the Planckian locus).
  const V3 d65ish = black_body_rgb(6500);
  EXPECT_NEAR(d65ish.x, d65ish.z, 0.1);
  for (float k : {2500.0f, 3200.0f, 4500.0f, 9000.0f, 15000.0f}) {
    const V3 light = black_body_rgb(k), g = white_balance_gains(k), seen = light * g;
    EXPECT_NEAR(seen.x / seen.y, d65ish.x / d65ish.y, 1e-3) << k;
    EXPECT_NEAR(seen.z / seen.y, d65ish.z / d65ish.y, 1e-3) << k;
    EXPECT_NEAR(luminance(g), 1, 1e-5) << k;
  }
  // Warm light is neutralised with blue; cool light with red.
  EXPECT_GT(white_balance_gains(3200).z, white_balance_gains(3200).x);
  EXPECT_LT(white_balance_gains(10000).z, white_balance_gains(10000).x);
  EXPECT_GT(black_body_rgb(2000).x, black_body_rgb(2000).z);
}

TEST(CameraPath, PassesThroughItsKeysSmoothlyAndFramesAtItsRate) {
  // Eyes on a straight line at an even speed: the spline must keep to it exactly.
  const CameraPath line = parse_camera_path(R"({"fps": 10, "keys": [
      {"t": 0, "camera": "look:from=0,0,100,to=0,100,0"},
      {"t": 1, "camera": "look:from=10,0,100,to=0,100,0"},
      {"t": 3, "camera": "look:from=30,0,100,to=0,100,0"}]})", "line.json", 40);
  EXPECT_EQ(line.frame_count(), 31);
  for (int n : {0, 5, 10, 17, 30}) {
    const Camera c = line.frame(n);
    EXPECT_NEAR(c.from.x, n, 1e-4) << n;
    EXPECT_NEAR(c.from.z, 100, 1e-4) << n;
    EXPECT_NEAR(c.to.y, 100, 1e-4) << n;
    EXPECT_EQ(c.fov_y, 40);
  }
  // A turn: through the keys, and its velocity the same either side of the middle one.
  const CameraPath turn = parse_camera_path(R"({"fps": 24, "keys": [
      {"t": 0, "camera": "orbit:target=0,0,0,azimuth=0,elevation=30,distance=200"},
      {"t": 2, "camera": "orbit:target=0,0,0,azimuth=90,elevation=30,distance=200"},
      {"t": 3, "camera": "look:from=-150,50,80,to=10,10,0"}]})", "turn.json", 45);
  const Camera middle = Camera::orbit({0, 0, 0}, 90, 30, 200, 45);
  EXPECT_NEAR(turn.at(2).from.x, middle.from.x, 1e-3);
  EXPECT_NEAR(turn.at(2).from.y, middle.from.y, 1e-3);
  const double h = 1e-3;
  const V3 before = (turn.at(2).from - turn.at(2 - h).from) / static_cast<float>(h),
           after = (turn.at(2 + h).from - turn.at(2).from) / static_cast<float>(h);
  EXPECT_NEAR(length(before - after), 0, 0.02 * length(before));
  EXPECT_NEAR(turn.at(3).from.x, -150, 1e-4);
}

TEST(CameraPath, TwoKeysLookingAtEachOthersEyesStillLookSomewhereHalfWay) {
  // The eye and the target cross at t = 0.5: the view turns about the vertical instead of
  // having no direction (a NaN ray, which Embree aborted the render on).
  const CameraPath swap = parse_camera_path(R"({"fps": 10, "keys": [
      {"t": 0, "camera": "look:from=0,0,10,to=10,0,10"},
      {"t": 1, "camera": "look:from=10,0,10,to=0,0,10"}]})", "swap.json", 40);
  for (int n = 0; n < swap.frame_count(); ++n) {
    const V3 f = swap.frame(n).forward();
    EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.z)) << n;
    EXPECT_NEAR(length(f), 1, 1e-4) << n;
    EXPECT_NEAR(f.z, 0, 1e-4) << n;  // both keys look level: so does every frame
  }
  EXPECT_NEAR(swap.at(0.5).forward().x, 0, 1e-4);  // half-way round from east to west
}

TEST(CameraPath, BadFilesSayWhichFileAndKeyInOneLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"[1, 2]", "path.json: not a JSON object"},
      {R"({"keys": [{"t": 0, "camera": "look:from=0,0,1,to=1,0,0"}]})", "path.json: \"fps\""},
      {R"({"fps": 24, "keys": []})", "path.json: \"keys\""},
      {R"({"fps": 24, "keys": [{"t": 0, "camera": "look:from=0,0,1,to=1,0,0"}, {"camera": "look:from=0,0,1,to=1,0,0"}]})",
       "path.json: keys[1]: no \"t\""},
      {R"({"fps": 24, "keys": [{"t": 1, "camera": "look:from=0,0,1,to=1,0,0"}, {"t": 1, "camera": "look:from=0,0,1,to=1,0,0"}]})",
       "path.json: keys[1]: t 1 is not after"},
      {R"({"fps": 24, "keys": [{"t": 0, "camera": "pan:x=1"}]})", "path.json: keys[0]: camera \"pan:x=1\""},
      // Spans whose frame count overflows an int said they had minus two billion frames.
      {R"({"fps": 1, "keys": [{"t": 0, "camera": "look:from=0,0,1,to=1,0,0"}, {"t": 1e300, "camera": "look:from=0,0,1,to=1,0,0"}]})",
       "path.json: more than a million frames"},
      {R"({"fps": 1000, "keys": [{"t": -1e6, "camera": "look:from=0,0,1,to=1,0,0"}, {"t": 1e6, "camera": "look:from=0,0,1,to=1,0,0"}]})",
       "path.json: more than a million frames"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      parse_camera_path(text, "path.json", 45);
      ADD_FAILURE() << text << " parsed";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(expected, 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(CameraPath, AFrameIsTheSameBytesWhicheverRangeRenderedIt) {
  const exacity::City city = small_city();
  const CameraPath path = parse_camera_path(R"({"fps": 2, "keys": [
      {"t": 0, "camera": "orbit:target=200,150,0,azimuth=200,elevation=35,distance=350"},
      {"t": 1, "camera": "orbit:target=200,150,0,azimuth=250,elevation=30,distance=300"}]})", "bytes.json", 45);
  ASSERT_EQ(path.frame_count(), 3);
  RenderRequest request;
  request.width = 32, request.height = 24, request.spp = 2;
  const fs::path whole = testing_util::temp_dir("frames-whole"), parts = testing_util::temp_dir("frames-parts");
  render_path_frames(city, path, 0, 2, request, whole);
  render_path_frames(city, path, 2, 2, request, parts);
  render_path_frames(city, path, 0, 1, request, parts);
  for (int n = 0; n < 3; ++n)
    for (const char* ext : {".png", ".exr"}) {
      const std::string name = fs::path(frame_file_name(n)).replace_extension(ext).string();
      const std::string a = cli_util::read(whole / name), b = cli_util::read(parts / name);
      ASSERT_FALSE(a.empty()) << name;
      EXPECT_TRUE(a == b) << name;
    }
  EXPECT_NE(cli_util::read(whole / "frame_0000.png"), cli_util::read(whole / "frame_0002.png")) << "the camera moves";
}

TEST(CameraPath, SharesCoverTheFramesOnceInOrder) {
  for (int parts : {1, 3, 7, 12, 20})
    for (auto [first, last] : {std::pair{0, 11}, std::pair{5, 5}, std::pair{3, 40}}) {
      int next = first;
      for (int part = 0; part < parts; ++part) {
        const auto [a, b] = frame_share(first, last, part, parts);
        if (a > b) {
          EXPECT_EQ(a, next) << parts;
          continue;  // an empty share, where the frames ran out
        }
        EXPECT_EQ(a, next) << parts << " " << part;
        const int count = last - first + 1;
        EXPECT_LE(b - a + 1, (count + parts - 1) / parts) << parts << " " << part;
        EXPECT_GE(b - a + 1, count / parts) << parts << " " << part;
        next = b + 1;
      }
      EXPECT_EQ(next, last + 1) << parts;
    }
}
