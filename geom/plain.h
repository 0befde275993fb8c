// Plain geometry values that cross module boundaries. No CGAL here: render/ and cli/
// see only these types.
#pragma once

#include <vector>

namespace geom {

struct Vec2 {
  double x = 0, y = 0;
  friend bool operator==(const Vec2&, const Vec2&) = default;
};

// A closed ring written without repeating its first point.
using Ring = std::vector<Vec2>;
using Polyline = std::vector<Vec2>;

struct Polygon {
  Ring outer;               // counter-clockwise
  std::vector<Ring> holes;  // clockwise
};

struct Box {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  double width() const { return max_x - min_x; }
  double height() const { return max_y - min_y; }
};

}  // namespace geom
