// Rounding a ring (to doubles, to millimetres) can land distinct vertices on one value.
#pragma once

#include <vector>

namespace geom {

// Drops repeated vertices and the zero-width spikes (a, b, a) they leave, across the seam
// too; clears the ring when fewer than 3 vertices remain. Rings that share vertices lose
// them alike, so they still meet edge to edge.
template <typename T>
void drop_repeats_and_spikes(std::vector<T>& r) {
  std::vector<T> out;
  out.reserve(r.size());
  for (const T& v : r) {
    while (out.size() >= 2 && out[out.size() - 2] == v) out.pop_back();
    if (out.empty() || !(out.back() == v)) out.push_back(v);
  }
  for (bool changed = true; changed && out.size() >= 3;) {
    changed = false;
    if (out.front() == out.back()) out.pop_back(), changed = true;
    else if (out[out.size() - 2] == out.front()) out.pop_back(), changed = true;
    else if (out[1] == out.back()) out.erase(out.begin()), changed = true;
  }
  if (out.size() < 3) out.clear();
  r = std::move(out);
}

}  // namespace geom
