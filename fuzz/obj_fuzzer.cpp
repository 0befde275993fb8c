// The OBJ reader (and the .mtl it names) on any bytes: a mesh or one UserError. The input
// is the OBJ; an "mtllib fuzz.mtl" line in it reads the same bytes as a material library.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz/fuzz_target.h"
#include "generate/placement/obj_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto dir = exacity::fuzz::scratch();
  exacity::fuzz::write(dir / "fuzz.mtl", text);
  std::istringstream in(text);
  exacity::fuzz::expect_user_errors_only([&] {
    exacity::TriangleMesh mesh = exacity::read_obj(in, dir / "fuzz.obj");
    for (const auto& t : mesh.triangles)
      for (int i : t)
        if (i < 0 || i >= static_cast<int>(mesh.vertices.size())) std::abort();
  });
  return 0;
}
