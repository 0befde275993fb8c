// Cancelling a build within its stages (docs/design.md, The pipeline: cancelling). Whoever
// runs the stages installs a flag for its thread (CancelScope); the long stages' loops take
// that flag before they start (CancelCheck, which a tbb::parallel_for body may call from any
// thread) and throw Cancelled once it is set. Without a scope, nothing is ever cancelled.
#pragma once

#include <atomic>
#include <stdexcept>

namespace exacity {

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled") {}
};

namespace detail {
inline thread_local const std::atomic<bool>* cancel_flag = nullptr;
}

// While it lives, the stages this thread runs stop once `flag` is set; the caller keeps the
// flag alive at least as long.
class CancelScope {
 public:
  explicit CancelScope(const std::atomic<bool>& flag) : previous_(detail::cancel_flag) { detail::cancel_flag = &flag; }
  ~CancelScope() { detail::cancel_flag = previous_; }
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

// The calling thread's flag, taken when made, so the body of a parallel loop checks the flag
// of the thread that started the loop. check() is one relaxed load: cheap per iteration.
class CancelCheck {
 public:
  CancelCheck() : flag_(detail::cancel_flag) {}
  bool requested() const { return flag_ && flag_->load(std::memory_order_relaxed); }
  void check() const {
    if (requested()) throw Cancelled();
  }

 private:
  const std::atomic<bool>* flag_;
};

}  // namespace exacity
