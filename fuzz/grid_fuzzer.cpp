// A grid map (.grid) on any bytes, read as a sketch: a Sketch or one UserError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_target.h"
#include "generate/sketch/sketch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto dir = exacity::fuzz::scratch();
  exacity::fuzz::write(dir / "fuzz.grid", std::string(reinterpret_cast<const char*>(data), size));
  exacity::fuzz::expect_user_errors_only([&] { exacity::load_sketch(dir / "fuzz.grid"); });
  return 0;
}
