// The passes of a still with a time budget (RenderRequest::time_budget_s): how many
// samples each pass takes and when to stop, apart from the tracer and the clock so that a
// test can drive it with its own (render/README.md, Progressive rendering).
#pragma once

#include <functional>

namespace render {

struct PassBudget {
  double budget_s = 0;  // the whole command's, counted from its start
  int spp = 16;         // the most samples a pass
  // Seconds the finishing (the denoiser and its primary layer) takes after `samples`
  // samples a pixel, at `per_sample_s` seconds a sample; none without the denoiser.
  std::function<double(int samples, double per_sample_s)> finish_s = [](int, double) { return 0.0; };
  // Seconds the still's writing takes, whatever was traced (asked after the first pass).
  std::function<double()> write_s = [] { return 0.0; };
  // The least finishing (the filter without its primary layer, which needs two samples):
  // planned for instead when no pass after the first fits with finish_s's, since a still
  // left at one sample gets no layer anyway. None: no finishing is cheaper than finish_s.
  std::function<double(int samples, double per_sample_s)> least_finish_s = nullptr;
};

struct Passes {
  int passes = 0, samples = 0;  // samples a pixel over the passes
  double traced_s = 0;          // the passes' time
  // When the least the command can do (its first pass, then the writing) ends, from the
  // command's start: past the budget (and its tenth's grace), the budget cannot be met.
  double least_s = 0;
};

// Traces passes while the budget holds them: the first of one sample (to time a sample
// before committing to more; traced however much of the budget is already spent, for an
// image), then each of as many samples, up to spp, as the time a sample has taken so far
// says will end, with the finishing after them, within the budget; none is begun when not
// one sample would. When none fits after the first pass, passes are planned with the least
// finishing instead, from then on. The writing's time is kept free after the finishing. A
// pass that ends past the budget (the machine slowed down) is the last.
// `trace(n)` traces a pass of n samples; `now()` is the seconds since the command started.
Passes run_passes(const PassBudget& budget, const std::function<void(int samples)>& trace,
                  const std::function<double()>& now);

}  // namespace render
