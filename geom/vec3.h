// Points and directions in 3D, in doubles: roof faces (geom/roof.h), model meshes
// (generate/placement/obj_file.h) and the meshes made from them.
#pragma once

#include <array>

namespace geom {

// A point or direction in 3D (metres, z up): roof faces, model and ground meshes.
using Vec3 = std::array<double, 3>;
inline Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// The normal of the triangle a, b, c (counter-clockwise seen from its front), twice its
// area long.
inline Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) { return cross(minus(b, a), minus(c, a)); }

}  // namespace geom
