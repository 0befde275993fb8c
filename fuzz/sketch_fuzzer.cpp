// The sketch reader on any bytes: a Sketch or one UserError, nothing else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_target.h"
#include "generate/sketch/sketch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  exacity::fuzz::expect_user_errors_only([&] { exacity::parse_sketch(text, "fuzz.geojson"); });
  return 0;
}
