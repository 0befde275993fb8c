#include "geom/snap_noding.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>

#include "geom/segment_buckets.h"

namespace geom {
namespace {

#if EXACITY_FLOAT_KERNEL == 5
// The grid build (geom/grid_kernel.h) as a practitioner writes it: crossings decided in
// rounded doubles, and one pass of snap rounding (Hobby's, not iterated).
// Its hot pixels are written where the sketch drew them (Placement): snapped to a decimal
// grid, every drawn zone was written up to 0.7 µm off its drawn outline.
using K = CGAL::Simple_cartesian<double>;
constexpr int kSnapRounds = 1;
constexpr bool kPixelsPlaced = true;
#else
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
constexpr int kSnapRounds = 16;
constexpr bool kPixelsPlaced = false;  // every pixel at its grid point: on 2^-24 m a drawn corner moves under 30 nm
#endif

// Which side of a -> b point p is on, decided on the doubles given (exactly but in the grid build).
int side(Vec2 a, Vec2 b, Vec2 p) {
  return static_cast<int>(CGAL::orientation(K::Point_2(a.x, a.y), K::Point_2(b.x, b.y), K::Point_2(p.x, p.y)));
}

// Where the segment a -> b enters the closed square of half side h around c, as a
// fraction of its length; negative when it misses it (Liang and Barsky's clipping).
double enters_square(Vec2 a, Vec2 b, Vec2 c, double h) {
  double t0 = 0, t1 = 1;
  const double d[2] = {b.x - a.x, b.y - a.y}, lo[2] = {c.x - h - a.x, c.y - h - a.y}, hi[2] = {c.x + h - a.x, c.y + h - a.y};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0) {
      if (lo[k] > 0 || hi[k] < 0) return -1;
      continue;
    }
    double u = lo[k] / d[k], v = hi[k] / d[k];
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
    if (t0 > t1) return -1;
  }
  return t0;
}

// Where the grid build writes each hot pixel (its grid point, on which snap rounding decided
// which pixels each segment passes through: Hobby's topology). A pixel holding an end of a
// vertex the arrangement has or of an edge given as doubles (the sketch's own corners) is
// that end; one holding a crossing on a drawn edge is that crossing as computed on the
// drawn ends; one a drawn edge or an arrangement's edge is routed through is moved onto
// that edge; any other is its grid point. The first placement of a pixel holds.
class Placement {
 public:
  void put(Vec2 pixel, Vec2 at) { placed_.emplace(pixel, at); }
  bool has(Vec2 pixel) const { return placed_.count(pixel) > 0; }
  Vec2 of(Vec2 pixel) const {
    auto it = placed_.find(pixel);
    return it == placed_.end() ? pixel : it->second;
  }
  // Each polyline's vertices where they are written; repeats dropped, a polyline left with
  // one point emptied.
  void apply(std::vector<Polyline>& lines) const {
    for (Polyline& line : lines) {
      Polyline written;
      for (Vec2 v : line)
        if (written.empty() || !(written.back() == of(v))) written.push_back(of(v));
      if (written.size() < 2) written.clear();
      line = std::move(written);
    }
  }

 private:
  struct XyLess {
    bool operator()(Vec2 p, Vec2 q) const { return p.x != q.x ? p.x < q.x : p.y < q.y; }
  };
  std::map<Vec2, Vec2, XyLess> placed_;
};

// The point of segment a -> b nearest to p, in doubles (exactly on it when it runs along an axis).
Vec2 nearest_on(Vec2 a, Vec2 b, Vec2 p) {
  const Vec2 d = b - a;
  return lerp(a, b, std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0));
}

}  // namespace

Vec2 snap_to(Vec2 p, double step) { return {std::nearbyint(p.x / step) * step, std::nearbyint(p.y / step) * step}; }

std::vector<Polyline> snap_round_segments(const std::vector<std::pair<Vec2, Vec2>>& segments, double step,
                                          const std::vector<bool>& monotone, const std::vector<bool>& given) {
  const std::size_t n = segments.size();
  std::vector<std::pair<Vec2, Vec2>> s(n);
  Box box = Box::none();
  // The ends of a `monotone` segment are vertices an arrangement has: they stay where they
  // are, on the grid or not (a crossing passed by below is constructed off it by CGAL's
  // sweep). Snapped, a steep edge less than a step wide, split at such a crossing, became a
  // vertical copy running the other way in (x, y) order, and a block's lots took its outside
  // for its inside (CGAL's precondition `f == f2`).
  for (std::size_t i = 0; i < n; ++i) {
    const bool stays = !kPixelsPlaced && i < monotone.size() && monotone[i];  // the grid build puts them back after
    s[i] = stays ? segments[i] : std::pair{snap_to(segments[i].first, step), snap_to(segments[i].second, step)};
    box.add(s[i].first), box.add(s[i].second);
  }
  std::vector<Polyline> out(n);
  if (n == 0) return out;
  const double extent = std::max({box.width(), box.height(), step});
  const SegmentBuckets grid(box, std::max(extent / std::sqrt(static_cast<double>(n)), 8 * step));
  auto xy_less = [](Vec2 p, Vec2 q) { return p.x != q.x ? p.x < q.x : p.y < q.y; };
  auto apart = [](Vec2 p, Vec2 q) { return std::max(std::abs(p.x - q.x), std::abs(p.y - q.y)); };
  // Half the side of a pixel, a hair more so a pixel a segment grazes in exact arithmetic is
  // not missed by rounding; and of the square around an end within which a segment is
  // routed through that end (the snap tolerance).
  const double half = step * (0.5 + 1e-9), end_reach = step * (kEndReach + 1e-9);

  // An end within the end reach of a vertex the arrangement has (an end of a segment that
  // must stay monotone) moves onto it: a road that starts where an earlier batch's road
  // stopped was computed from that road's end before the earlier batch moved it.
  std::vector<Vec2> fixed;
  for (std::size_t i = 0; i < n && i < monotone.size(); ++i)
    if (monotone[i]) fixed.push_back(s[i].first), fixed.push_back(s[i].second);
  std::sort(fixed.begin(), fixed.end(), xy_less);
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  if (!fixed.empty()) {
    auto moved = [&](Vec2 e) {
      if (std::binary_search(fixed.begin(), fixed.end(), e, xy_less)) return e;
      Vec2 best = e;
      double best_d = INFINITY;
      for (auto it = std::lower_bound(fixed.begin(), fixed.end(), Vec2{e.x - end_reach, -INFINITY}, xy_less);
           it != fixed.end() && it->x <= e.x + end_reach; ++it)
        if (const double d = apart(e, *it); d <= end_reach && d < best_d) best = *it, best_d = d;
      return best;
    };
    for (auto& [a, b] : s) a = moved(a), b = moved(b);
  }

  // Whether segment i is routed through end e beside it: e lies within the end reach of it
  // and farther than that from its own ends (near those, two ends are apart, not an end
  // beside an edge).
  auto takes_end = [&](std::size_t i, Vec2 e) {
    const auto [a, b] = s[i];
    return apart(e, a) > end_reach && apart(e, b) > end_reach && enters_square(a, b, e, end_reach) >= 0;
  };

  // Crossings: decided exactly on the snapped ends, placed in doubles, then snapped. One
  // within a pixel of an end of either segment, where the other segment is routed through
  // that end, is that end: a road computed to stop at another and snapped a pixel past or
  // short of it would otherwise end in a tail or a gap one pixel long beside the junction.
  std::vector<std::pair<long, int>> entries;  // (bucket, segment)
  for (std::size_t i = 0; i < n; ++i)
    if (!(s[i].first == s[i].second))
      grid.along(s[i].first, s[i].second, step, [&](long k) { entries.push_back({k, static_cast<int>(i)}); });
  std::sort(entries.begin(), entries.end());
  std::vector<Vec2> hot;
  auto is_given = [&](std::size_t i) { return kPixelsPlaced && i < given.size() && given[i]; };
  auto is_monotone = [&](std::size_t i) { return i < monotone.size() && monotone[i]; };
  Placement placement;  // the grid build's (else every pixel is its grid point)
  for (std::size_t i = 0; i < n; ++i)
    if (kPixelsPlaced && is_monotone(i))
      placement.put(s[i].first, segments[i].first), placement.put(s[i].second, segments[i].second);
  for (std::size_t i = 0; i < n; ++i)
    if (is_given(i)) {
      // An end the end reach moved onto a vertex the arrangement has is that vertex.
      if (s[i].first == snap_to(segments[i].first, step)) placement.put(s[i].first, segments[i].first);
      if (s[i].second == snap_to(segments[i].second, step)) placement.put(s[i].second, segments[i].second);
    }
  // Where the drawn edges i and j (or a drawn and a constructed one) cross, computed on the
  // drawn ends, each coordinate from an edge running along that axis where one does (so a
  // crossing on an edge along an axis lies exactly on it).
  auto drawn_crossing = [&](std::size_t i, std::size_t j) {
    const auto [a, b] = is_given(i) ? segments[i] : s[i];
    const auto [c, d] = is_given(j) ? segments[j] : s[j];
    const double ca = cross(d - c, a - c), cb = cross(d - c, b - c), ac = cross(b - a, c - a), ad = cross(b - a, d - a);
    const Vec2 on_i = lerp(a, b, ca / (ca - cb)), on_j = lerp(c, d, ac / (ac - ad));
    return Vec2{a.x == b.x ? a.x : c.x == d.x ? c.x : on_j.x, a.y == b.y ? a.y : c.y == d.y ? c.y : on_i.y};
  };
  for (std::size_t begin = 0, end; begin < entries.size(); begin = end) {
    for (end = begin; end < entries.size() && entries[end].first == entries[begin].first;) ++end;
    for (std::size_t p = begin; p < end; ++p)
      for (std::size_t q = p + 1; q < end; ++q) {
        const std::size_t i = entries[p].second, j = entries[q].second;
        const auto [a, b] = s[i];
        const auto [c, d] = s[j];
        const int sc = side(a, b, c), sd = side(a, b, d), sa = side(c, d, a), sb = side(c, d, b);
        if (sc * sd >= 0 || sa * sb >= 0) continue;  // touching and overlapping ends are hot already
        const double ca = cross(d - c, a - c), cb = cross(d - c, b - c);
        const Vec2 x = snap_to(lerp(a, b, ca / (ca - cb)), step);
        auto at_end = [&](Vec2 e, std::size_t other) { return apart(x, e) <= step * (1 + 1e-9) && takes_end(other, e); };
        if (at_end(a, j) || at_end(b, j) || at_end(c, i) || at_end(d, i)) continue;
        hot.push_back(x);
        if (is_given(i) || is_given(j)) {
          const Vec2 on = drawn_crossing(i, j);  // re-tested: within its pixel
          if (apart(on, x) <= half) placement.put(x, on);
        }
      }
  }
  const std::size_t crossings = hot.size();
  for (const auto& [a, b] : s) hot.push_back(a), hot.push_back(b);
  // Each pixel once; an end's reach wins over a crossing's.
  std::vector<std::pair<Vec2, bool>> pixels;  // (centre, an end)
  for (std::size_t k = 0; k < hot.size(); ++k) pixels.push_back({hot[k], k >= crossings});
  std::sort(pixels.begin(), pixels.end(), [&](const auto& u, const auto& v) {
    return u.first == v.first ? u.second > v.second : xy_less(u.first, v.first);
  });
  pixels.erase(std::unique(pixels.begin(), pixels.end(), [](const auto& u, const auto& v) { return u.first == v.first; }),
               pixels.end());
  std::vector<std::pair<long, int>> hot_in;  // (bucket, pixel)
  for (std::size_t k = 0; k < pixels.size(); ++k) hot_in.push_back({grid.key(pixels[k].first), static_cast<int>(k)});
  std::sort(hot_in.begin(), hot_in.end());

  // Each segment through the hot pixels it meets (and the ends it passes within the end
  // reach of); then each piece again, until no piece meets a hot pixel not its own
  // (iterated snap rounding: the result, noded again on the same grid, stays as it is; one pass in the grid build).
  std::vector<std::pair<double, Vec2>> found;
  auto hot_on = [&](Vec2 p, Vec2 q, Vec2 a, Vec2 b) {
    found.clear();
    const Vec2 d = q - p;
    grid.along(p, q, end_reach, [&](long k) {
      for (auto it = std::lower_bound(hot_in.begin(), hot_in.end(), std::pair<long, int>(k, INT_MIN));
           it != hot_in.end() && it->first == k; ++it) {
        const auto [c, is_end] = pixels[it->second];
        if (c == p || c == q) continue;
        const bool beside = is_end && apart(c, a) > end_reach && apart(c, b) > end_reach;
        if (enters_square(p, q, c, beside ? end_reach : half) < 0) continue;
        found.push_back({std::clamp(dot(c - p, d) / dot(d, d), 0.0, 1.0), c});
      }
    });
    std::sort(found.begin(), found.end(), [&](const auto& u, const auto& v) {
      return u.first != v.first ? u.first < v.first : xy_less(u.second, v.second);
    });
  };
  for (std::size_t i = 0; i < n; ++i) {
    const auto [a, b] = s[i];
    if (a == b) continue;
    // A segment that must stay monotone takes only vertices that keep it running one way
    // in (x, y) order: a split edge's pieces must follow each other from its left end to its
    // right one. Others take every hot pixel they meet once.
    // In the grid build, in (x, y) order as written (Placement), and a drawn or map edge places
    // the pixels it takes that nothing placed before it.
    const bool one_way = is_monotone(i), kept = kPixelsPlaced && (one_way || is_given(i));
    const bool rightwards = xy_less(placement.of(a), placement.of(b));
    auto ahead = [&](Vec2 p, Vec2 q) { return !one_way || (rightwards ? xy_less(p, q) : xy_less(q, p)); };
    Polyline line{a, b};
    for (int round = 0; round < kSnapRounds; ++round) {
      Polyline next{a};
      bool changed = false;
      for (std::size_t k = 0; k + 1 < line.size(); ++k) {
        hot_on(line[k], line[k + 1], a, b);
        for (const auto& [u, c] : found) {
          if (c == next.back() || std::find(line.begin(), line.end(), c) != line.end()) continue;
          // Placed within its own pixel only, so pixels stay apart (an end a segment passes
          // within the end reach of lies farther off it).
          const Vec2 onto = nearest_on(segments[i].first, segments[i].second, c);
          const bool places = kept && !placement.has(c) && apart(onto, c) <= half;
          const Vec2 at = places ? onto : placement.of(c);
          if (!ahead(placement.of(next.back()), at) || !ahead(at, placement.of(line[k + 1]))) continue;
          if (places) placement.put(c, at);
          next.push_back(c), changed = true;
        }
        next.push_back(line[k + 1]);
      }
      line = std::move(next);
      if (!changed) break;
    }
    out[i] = std::move(line);
  }
  if constexpr (kPixelsPlaced) placement.apply(out);
  return out;
}

}  // namespace geom
