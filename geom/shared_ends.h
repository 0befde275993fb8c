// Whether the arrangements this thread builds answer the intersection of two segments that
// share an end from an orientation of the ends (SegmentTraits, geom/planar_map_arrangement.h).
// Validation turns it on for its maps, whose ends are all doubles read from the written
// layers: there it saves most of the exact arithmetic. The other stages' maps keep CGAL's
// answer, which is the same: with it on everywhere the lots stage of the 10 km city took
// 30% longer (measured, not explained).
#pragma once

namespace geom {

class SharedEndsByOrientation {
 public:
  SharedEndsByOrientation() : was_(on_) { on_ = true; }
  ~SharedEndsByOrientation() { on_ = was_; }
  SharedEndsByOrientation(const SharedEndsByOrientation&) = delete;
  SharedEndsByOrientation& operator=(const SharedEndsByOrientation&) = delete;
  static bool on() { return on_; }

 private:
  inline static thread_local bool on_ = false;
  bool was_;
};

}  // namespace geom
