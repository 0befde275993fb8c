// What the kernel this build computes with (geom/exact.h) can vouch for.
#pragma once

namespace geom {

// False in the robustness benchmark's snapped float build: its planar map nodes every
// batch on its grid, so checking a written city in it would snap the city again, and snap
// rounding a snap-rounded city can fold a spike narrower than the grid onto itself. That
// build's outputs are validated by the exact build (`exacity validate`) instead.
bool kernel_validates_its_output();

}  // namespace geom
