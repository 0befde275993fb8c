#include "render/pass_budget.h"

#include <algorithm>

namespace render {

Passes run_passes(const PassBudget& budget, const std::function<void(int samples)>& trace,
                  const std::function<double()>& now) {
  // A still of more samples than this is not progressive rendering's to make.
  constexpr int kMostSamples = 65536;
  Passes done;
  int next = 1;
  bool least = false;  // planning with the least finishing
  while (next > 0) {
    const double begun = now();
    trace(next);
    done.traced_s += now() - begun;
    done.samples += next;
    ++done.passes;
    const double writing = budget.write_s();
    if (done.passes == 1) done.least_s = now() + writing;
    // The most samples, up to spp, that end with the finishing and writing within the budget (the
    // clock read after finish_s, which may time the finishing the first time it is asked).
    const double per_sample = done.traced_s / done.samples;
    auto fits = [&](int n) {
      const double finish = (least ? budget.least_finish_s : budget.finish_s)(done.samples + n, per_sample);
      return per_sample * n + finish + writing <= budget.budget_s - now();
    };
    const int most = std::min(budget.spp, kMostSamples - done.samples);
    next = most;
    while (next > 0 && !fits(next)) --next;
    if (next == 0 && done.samples == 1 && budget.least_finish_s && !least) {
      least = true;
      for (next = most; next > 0 && !fits(next);) --next;
    }
  }
  return done;
}

}  // namespace render
