// An OpenStreetMap extract (.osm XML, read with libosmium) on any bytes, read as
// `exacity generate` reads it (projected to metres, its tags made zones and roads, then
// the sketch reader's checks): a Sketch or one UserError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_target.h"
#include "generate/sketch/sketch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto dir = exacity::fuzz::scratch();
  exacity::fuzz::write(dir / "fuzz.osm", std::string(reinterpret_cast<const char*>(data), size));
  exacity::fuzz::expect_user_errors_only([&] { exacity::load_sketch(dir / "fuzz.osm"); });
  return 0;
}
