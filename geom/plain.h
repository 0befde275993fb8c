// Plain geometry values that cross module boundaries. No CGAL here: render/ and cli/
// see only these types.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace geom {

struct Vec2 {
  double x = 0, y = 0;
  friend bool operator==(const Vec2&, const Vec2&) = default;
};

// The few vector operations choices in doubles need (exact work is CGAL's, geom/exact.h).
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double distance(Vec2 a, Vec2 b) { return std::hypot(b.x - a.x, b.y - a.y); }
inline Vec2 lerp(Vec2 a, Vec2 b, double t) { return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t}; }
// `a` scaled to unit length; zero for zero.
inline Vec2 unit(Vec2 a) {
  const double l = std::hypot(a.x, a.y);
  return l > 0 ? a * (1 / l) : Vec2{0, 0};
}
// The unit vector along the edge a -> b, and the edge's left normal: into a ring's inside,
// for rings that run with the inside on their left. Zero for an edge of no length. The
// one divides by the length and the other scales by its reciprocal, which can round apart
// in the last bit: unit_along is what model rows and lot shapes always divided by, the
// normal what lot allocation always scaled by (both choices in doubles, then snapped to
// the grid; the other users of the normal, which used to divide, gave the same outputs on
// every example and shape).
inline Vec2 unit_along(Vec2 a, Vec2 b) {
  const double len = std::hypot(b.x - a.x, b.y - a.y);
  return len > 0 ? Vec2{(b.x - a.x) / len, (b.y - a.y) / len} : Vec2{0, 0};
}
inline Vec2 left_normal(Vec2 a, Vec2 b) {
  const Vec2 u = unit(b - a);
  return {-u.y, u.x};
}

// For hash maps keyed by exact double positions.
struct Vec2Hash {
  std::size_t operator()(const Vec2& p) const { return std::hash<double>()(p.x) * 31 ^ std::hash<double>()(p.y); }
};

// A street leaving a junction's node: towards its next vertex, `length` metres along it
// (0: just to that vertex), with its half width.
struct JunctionArm {
  Vec2 toward;
  double half_width = 0;
  double length = 0;
};

// An undirected segment as a key of exact double positions: its ends in order, so a-b and
// b-a are one key.
using SegmentKey = std::pair<std::pair<double, double>, std::pair<double, double>>;
inline SegmentKey segment_key(Vec2 a, Vec2 b) {
  const std::pair<double, double> x{a.x, a.y}, y{b.x, b.y};
  return x < y ? SegmentKey{x, y} : SegmentKey{y, x};
}

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

  // A box that holds nothing yet, to grow with add().
  static Box none() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {inf, inf, -inf, -inf};
  }
  bool holds_nothing() const { return min_x > max_x; }
  void add(Vec2 p) {
    min_x = std::min(min_x, p.x), min_y = std::min(min_y, p.y);
    max_x = std::max(max_x, p.x), max_y = std::max(max_y, p.y);
  }
  void add(const Box& b) {
    if (b.holds_nothing()) return;
    add(Vec2{b.min_x, b.min_y}), add(Vec2{b.max_x, b.max_y});
  }
  // Whether the boxes share a point (touching counts).
  bool meets(const Box& b) const {
    return min_x <= b.max_x && b.min_x <= max_x && min_y <= b.max_y && b.min_y <= max_y;
  }
};

}  // namespace geom
