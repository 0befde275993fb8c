#include "geom/crowding.h"

#include <algorithm>
#include <cmath>

#include <CGAL/box_intersection_d.h>

#include "geom/measure.h"

namespace geom {
namespace {

using SegmentBox = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;

// Whether the segments ab and cd cross or touch.
bool segments_meet(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  auto side = [](Vec2 p, Vec2 q, Vec2 r) {
    const double s = cross(q - p, r - p);
    return (s > 0) - (s < 0);
  };
  const int s1 = side(a, b, c), s2 = side(a, b, d), s3 = side(c, d, a), s4 = side(c, d, b);
  return s1 != s2 && s3 != s4 && s1 * s2 <= 0 && s3 * s4 <= 0;
}

double segment_distance(const FatSegment& s, const FatSegment& t) {
  if (segments_meet(s.a, s.b, t.a, t.b)) return 0;
  return std::min({distance_to_segment(s.a, t.a, t.b), distance_to_segment(s.b, t.a, t.b),
                   distance_to_segment(t.a, s.a, s.b), distance_to_segment(t.b, s.a, s.b)});
}

bool follow_each_other(const FatSegment& s, const FatSegment& t) {
  if (s.chain != t.chain) return false;
  const int gap = std::abs(s.index - t.index);
  return gap == 1 || (s.ring && gap == s.last_index);
}

struct Enough {};

}  // namespace

std::size_t count_meetings(const std::vector<FatSegment>& segments, std::size_t limit, std::vector<std::size_t>& per_chain) {
  std::vector<SegmentBox> boxes;
  boxes.reserve(segments.size());
  int chains = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const FatSegment& s = segments[i];
    double lo[2] = {std::min(s.a.x, s.b.x) - s.radius, std::min(s.a.y, s.b.y) - s.radius};
    double hi[2] = {std::max(s.a.x, s.b.x) + s.radius, std::max(s.a.y, s.b.y) + s.radius};
    boxes.push_back(SegmentBox(lo, hi, i));
    chains = std::max(chains, s.chain + 1);
  }
  per_chain.assign(static_cast<std::size_t>(chains), 0);
  std::size_t count = 0;
  try {
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const SegmentBox& x, const SegmentBox& y) {
      const FatSegment &s = segments[x.info()], &t = segments[y.info()];
      if (follow_each_other(s, t) || segment_distance(s, t) > s.radius + t.radius) return;
      ++per_chain[static_cast<std::size_t>(s.chain)];
      if (t.chain != s.chain) ++per_chain[static_cast<std::size_t>(t.chain)];
      if (++count >= limit) throw Enough{};
    });
  } catch (const Enough&) {
  }
  return count;
}

}  // namespace geom
