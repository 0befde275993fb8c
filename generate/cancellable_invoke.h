// Independent pieces of a stage run at once on TBB's threads, each stopping when the
// stage is cancelled (generate/cancel.h: the flag belongs to the thread that runs the stage).
#pragma once

#include <atomic>
#include <cstddef>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

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

// Pieces 0, ..., n - 1 of an output made at once (make(i, piece), on any thread, under the
// calling thread's cancel flag) and handed to write(piece) one at a time in order, so the
// output is the same bytes whatever the thread count. Only a few pieces wait made at a
// time (two per thread), so the output is never held whole.
template <typename Piece, typename Make, typename Write>
void make_in_order(std::size_t n, Make&& make, Write&& write) {
  const std::atomic<bool>* flag = detail::cancel_flag;
  std::size_t next = 0;
  const auto tokens = static_cast<std::size_t>(2 * tbb::this_task_arena::max_concurrency());
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& control) -> std::size_t {
                                            if (next == n) control.stop();
                                            return next++;
                                          }) &
          tbb::make_filter<std::size_t, Piece>(tbb::filter_mode::parallel,
                                               [&](std::size_t i) {
                                                 detail::FlagScope scope(flag);
                                                 CancelCheck().check();
                                                 Piece piece{};
                                                 make(i, piece);
                                                 return piece;
                                               }) &
          tbb::make_filter<Piece, void>(tbb::filter_mode::serial_in_order, [&](Piece piece) { write(piece); }));
}

}  // namespace exacity
