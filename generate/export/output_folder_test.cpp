#include "generate/export/output_folder.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <thread>

namespace exacity {
namespace {

using namespace std::chrono_literals;

// exacity serve's handler stops the server, a local of the function that replaces the handler
// once the server has stopped: replacing it while it still runs let the function return and
// the handler use a destroyed server (a crash after SIGTERM, seen once in CI).
// Exit code 0 when on_interrupt(nullptr) returned only after the handler a SIGTERM called.
[[noreturn]] void replace_the_handler_while_it_runs() {
  clean_up_on_interrupt();
  std::atomic<bool> called{false}, returned{false};
  on_interrupt([&](int) {
    called = true;
    std::this_thread::sleep_for(300ms);
    returned = true;
  });
  kill(getpid(), SIGTERM);
  for (int i = 0; i < 10000 && !called; ++i) std::this_thread::sleep_for(1ms);
  if (!called) std::_Exit(1);
  on_interrupt(nullptr);
  std::_Exit(returned ? 0 : 2);
}

TEST(Interrupt, ReplacingTheHandlerWaitsForOneAlreadyCalled) {
  // In a process of its own, started afresh: a signal sent to the process goes to any thread
  // that does not block it, and the threads earlier tests of this program started (TBB's
  // workers) were started before clean_up_on_interrupt blocked it, so the signal ended the
  // whole program where it ran after them.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(replace_the_handler_while_it_runs(), testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace exacity
