#include "generate/export/output_folder.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace exacity {
namespace {

using namespace std::chrono_literals;

// exacity serve's handler stops the server, a local of the function that replaces the handler
// once the server has stopped: replacing it while it still runs let the function return and
// the handler use a destroyed server (a crash after SIGTERM, seen once in CI).
TEST(Interrupt, ReplacingTheHandlerWaitsForOneAlreadyCalled) {
  clean_up_on_interrupt();
  std::atomic<bool> called{false}, returned{false};
  on_interrupt([&](int) {
    called = true;
    std::this_thread::sleep_for(300ms);
    returned = true;
  });
  kill(getpid(), SIGTERM);
  for (int i = 0; i < 10000 && !called; ++i) std::this_thread::sleep_for(1ms);
  ASSERT_TRUE(called);
  on_interrupt(nullptr);
  EXPECT_TRUE(returned);
}

}  // namespace
}  // namespace exacity
