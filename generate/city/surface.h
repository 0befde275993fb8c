// What a face of a mesh is, which the exports write and the renderer shades by.
#pragma once

namespace exacity {

// A foundation's top counts as roof: it is what the model stands on.
enum class Surface : int { Ground = 0, Wall = 1, Roof = 2 };
inline constexpr const char* kSurfaceNames[] = {"ground", "wall", "roof"};

}  // namespace exacity
