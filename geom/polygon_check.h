// Exact checks on polygons given in doubles (the exports as they were written).
#pragma once

#include <set>
#include <utility>
#include <vector>

#include "geom/plain.h"

namespace geom {

// Exact sign of the ring's area: +1 counter-clockwise, -1 clockwise, 0 degenerate.
int ring_orientation(const Ring& ring);

// No vertex repeated, no two edges meeting except neighbours at their shared vertex.
bool ring_is_simple(const Ring& ring);

// The same by CGAL's sweep alone, which ring_is_simple asks of rings of many vertices (tests
// compare the two on small ones).
bool cgal_ring_is_simple(const Ring& ring);

// The closed regions the two simple rings bound meet (touching counts), decided exactly.
bool rings_meet(const Ring& a, const Ring& b);

// The simple ring lies in the closed region the simple ring `outer` bounds, given that
// the two do not cross (they may touch, or share edges), decided exactly.
bool ring_within(const Ring& ring, const Ring& outer);

// The pairs (i < j) of polygons (simple rings, outer counter-clockwise, holes clockwise)
// whose interiors meet: they overlap in some area, not only along edges or at points.
// Exact: every ring in one planar map, polygon i's winding counter i, and a pair for each
// face two of them wind around.
std::set<std::pair<int, int>> overlapping_pairs(const std::vector<const Polygon*>& polygons);

// The same for two polygons.
bool interiors_overlap(const Polygon& a, const Polygon& b);

// The sign of (a + b) - (c + d), exact: heights counted from different floors compared.
int compare_sums(double a, double b, double c, double d);

// Where p lies against the simple ring, decided exactly: +1 inside, 0 on it, -1 outside.
int point_side(const Ring& ring, Vec2 p);

// The same against a polygon of simple rings (inside: inside its outer ring and outside
// every hole).
int point_side(const Polygon& polygon, Vec2 p);

// The convex hull of the points, counter-clockwise, without collinear points; exact.
Ring convex_hull(const std::vector<Vec2>& points);

// A convex polygon of `sides` sides (fewer where corners round to one) around the points,
// on the grid: each side on a line no point lies beyond, moved out by a grid step so that
// rounding its corners to the grid keeps every point inside.
Ring polygon_around(const std::vector<Vec2>& points, int sides);

}  // namespace geom
