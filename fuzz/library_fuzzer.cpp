// The model library manifest on any bytes, its entries naming a small house and a lamp that
// exist: a library or one UserError. The keys (lots, channels, clutter kinds and
// their spacing) are read too, the channels checked against a sketch's one as generate
// does, and the library then drawn from and cut into slabs as placement and nesting do.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_target.h"
#include "generate/city/random.h"
#include "generate/placement/model_library.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto dir = exacity::fuzz::scratch();
  exacity::fuzz::write(dir / "house.obj",
                       "v 0 0 0\nv 6 0 0\nv 6 0 -8\nv 0 0 -8\nv 0 5 0\nv 6 5 0\nv 6 5 -8\nv 0 5 -8\n"
                       "f 1 2 3 4\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  exacity::fuzz::write(dir / "lamp.obj",
                       "v 0 0 0\nv 0.2 0 0\nv 0.2 0.2 0\nv 0 0.2 0\nv 0 0 5\nv 0.2 0 5\nv 0.2 0.2 5\nv 0 0.2 5\n"
                       "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  exacity::fuzz::write(dir / "library.json", std::string(reinterpret_cast<const char*>(data), size));
  exacity::fuzz::expect_user_errors_only([&] {
    exacity::ModelLibrary library = exacity::load_model_library(dir / "library.json");
    library.check_channels({{"downtown", dir / "downtown.png", {0, 0, 100, 100}}});
    // What placement draws from: every zone's lot models and every kind's models, by weight.
    for (std::size_t z = 0; z < exacity::kZoneTypeNames.size(); ++z) {
      const auto zone = static_cast<exacity::ZoneType>(z);
      library.lot_choices(zone);
      for (exacity::ModelKind kind : exacity::kModelKinds) {
        exacity::Random rng(z);
        exacity::pick(exacity::choices_at(library.choices(zone, kind), library, nullptr, {0, 0}), rng);
      }
    }
    // The slabs nesting cuts each building into (exact work on the scaled models).
    exacity::cut_slabs(library);
  });
  return 0;
}
