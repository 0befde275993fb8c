// `exacity stats --real` on any bytes: statistics or one UserError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_target.h"
#include "generate/export/statistics.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto dir = exacity::fuzz::scratch();
  exacity::fuzz::write(dir / "real.geojson", std::string(reinterpret_cast<const char*>(data), size));
  exacity::fuzz::expect_user_errors_only([&] { exacity::real_statistics(dir / "real.geojson"); });
  return 0;
}
