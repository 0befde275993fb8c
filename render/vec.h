// Small 3-vector maths for the renderer, in floats as Embree's rays are.
#pragma once

#include <algorithm>
#include <cmath>

namespace render {

struct V3 {
  float x = 0, y = 0, z = 0;
  V3 operator+(V3 o) const { return {x + o.x, y + o.y, z + o.z}; }
  V3 operator-(V3 o) const { return {x - o.x, y - o.y, z - o.z}; }
  V3 operator*(V3 o) const { return {x * o.x, y * o.y, z * o.z}; }
  V3 operator*(float s) const { return {x * s, y * s, z * s}; }
  V3 operator/(float s) const { return {x / s, y / s, z / s}; }
  V3& operator+=(V3 o) { return *this = *this + o; }
  V3& operator*=(V3 o) { return *this = *this * o; }
  float operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};

inline float dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline float length(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 normalize(V3 a) { return a / length(a); }
inline float max_component(V3 a) { return std::max({a.x, a.y, a.z}); }
inline float luminance(V3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// An orthonormal frame around n (Duff et al. 2017, branchless).
struct Frame {
  V3 t, b, n;
  Frame() = default;
  explicit Frame(V3 normal) : n(normal) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z), c = n.x * n.y * a;
    t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
    b = {c, sign + n.y * n.y * a, -n.y};
  }
  V3 to_world(V3 v) const { return t * v.x + b * v.y + n * v.z; }
  V3 to_local(V3 v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
};

inline constexpr float kPi = 3.14159265358979f;

}  // namespace render
