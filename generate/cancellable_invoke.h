// Independent pieces of a stage run at once on TBB's threads, each stopping when the
// stage is cancelled (generate/cancel.h: the flag belongs to the thread that runs the stage).
#pragma once

#include <atomic>
#include <cstddef>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "generate/cancel.h"

namespace exacity {

namespace detail {
// Gives the thread it is made on `flag` until it ends (null: nothing cancels).
class FlagScope {
 public:
  explicit FlagScope(const std::atomic<bool>* flag) : previous_(cancel_flag) { cancel_flag = flag; }
  ~FlagScope() { cancel_flag = previous_; }
  FlagScope(const FlagScope&) = delete;
  FlagScope& operator=(const FlagScope&) = delete;

 private:
  const std::atomic<bool>* previous_;
};
}  // namespace detail

// Runs every f at once (one after another with one thread), each under the calling
// thread's cancel flag; returns when all have ended, rethrowing what one threw.
template <typename... F>
void invoke_cancellable(F&&... f) {
  const std::atomic<bool>* flag = detail::cancel_flag;
  tbb::parallel_invoke([&] {
    detail::FlagScope scope(flag);
    CancelCheck().check();  // none begins once cancelled
    f();
  }...);
}

// f(0), ..., f(n - 1) at once, in the same way.
template <typename F>
void for_each_cancellable(std::size_t n, F&& f) {
  const std::atomic<bool>* flag = detail::cancel_flag;
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    detail::FlagScope scope(flag);
    CancelCheck().check();
    f(i);
  });
}

}  // namespace exacity
