// Where one simple ring's edges lie against another's region, decided exactly on the
// written doubles: orientations of written points and comparisons of their coordinates, no
// constructed point. Validation proves with these that a lot or a building would pass every
// check of the polygons' map before it builds that map (docs/design.md, Validation by tiles).
#pragma once

#include "geom/plain.h"

namespace exacity {

// How the edges of ring b, each split at the vertices of ring a on it, lie against the
// closed region a bounds. Each piece's inside meets a's boundary nowhere or lies on it, so
// it lies wholly inside, outside or on the boundary. Both rings simple and open (the first
// vertex not repeated), a counter-clockwise.
struct RingSides {
  bool crosses = false;  // an edge of b crosses an edge of a at a point inside both (nothing else is looked at then)
  bool inside = false;   // some piece lies in a's interior
  bool outside = false;  // some piece lies outside a's closed region
};
RingSides ring_sides(const geom::Ring& b, const geom::Ring& a);

// Whether the simple counter-clockwise ring lies in the closed region of the polygon (simple
// rings, the outer counter-clockwise, holes clockwise, inside it and apart).
bool ring_in_polygon(const geom::Ring& ring, const geom::Polygon& polygon);

// Whether the regions the two simple counter-clockwise rings bound have no interior point in
// common (touching along edges or at points is apart).
bool interiors_apart(const geom::Ring& a, const geom::Ring& b);

// Whether the segment a-b meets the closed box (touching counts): the boxes meet and the
// box's corners lie on both sides of the segment's line, or on it.
bool segment_meets_box(geom::Vec2 a, geom::Vec2 b, const geom::Box& box);

// How many times the ring winds around p (counter-clockwise positive), exactly (geom::winding_number
// counts in doubles); p on no edge of it.
// The ring need not be simple.
int exact_winding_number(const geom::Ring& ring, geom::Vec2 p);

// How the segments a0-a1 and b0-b1 (neither a point) meet, exactly: nowhere but at an end
// of both (Apart), as the same segment either way (Same), or otherwise (crossing, an end
// inside the other, running along each other in part).
enum class SegmentMeeting { Apart, Same, Otherwise };
SegmentMeeting segment_meeting(geom::Vec2 a0, geom::Vec2 a1, geom::Vec2 b0, geom::Vec2 b1);

// Whether the segments a0-a1 and b0-b1 (neither a point) run along each other for a positive length.
bool segments_run_along(geom::Vec2 a0, geom::Vec2 a1, geom::Vec2 b0, geom::Vec2 b1);

}  // namespace exacity
