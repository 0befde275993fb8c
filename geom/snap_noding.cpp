#include "geom/snap_noding.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "geom/segment_buckets.h"

namespace geom {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// Which side of a -> b point p is on, decided exactly on the doubles given.
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

}  // namespace

Vec2 snap_to(Vec2 p, double step) { return {std::nearbyint(p.x / step) * step, std::nearbyint(p.y / step) * step}; }

std::vector<Polyline> snap_round_segments(const std::vector<std::pair<Vec2, Vec2>>& segments, double step,
                                          const std::vector<bool>& monotone) {
  const std::size_t n = segments.size();
  std::vector<std::pair<Vec2, Vec2>> s(n);
  Box box = Box::none();
  std::vector<Vec2> hot;
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = {snap_to(segments[i].first, step), snap_to(segments[i].second, step)};
    box.add(s[i].first), box.add(s[i].second);
    hot.push_back(s[i].first), hot.push_back(s[i].second);
  }
  std::vector<Polyline> out(n);
  if (n == 0) return out;
  const double extent = std::max({box.width(), box.height(), step});
  const SegmentBuckets grid(box, std::max(extent / std::sqrt(static_cast<double>(n)), 8 * step));

  auto xy_less = [](Vec2 p, Vec2 q) { return p.x != q.x ? p.x < q.x : p.y < q.y; };
  std::vector<std::pair<long, int>> entries;  // (bucket, segment)
  // Crossings: decided exactly on the snapped ends, placed in doubles, then snapped.
  auto crossings = [&] {
    entries.clear();
    for (std::size_t i = 0; i < n; ++i)
      if (!(s[i].first == s[i].second))
        grid.along(s[i].first, s[i].second, step, [&](long k) { entries.push_back({k, static_cast<int>(i)}); });
    std::sort(entries.begin(), entries.end());
    std::vector<Vec2> found;
    for (std::size_t begin = 0, end; begin < entries.size(); begin = end) {
      for (end = begin; end < entries.size() && entries[end].first == entries[begin].first;) ++end;
      for (std::size_t p = begin; p < end; ++p)
        for (std::size_t q = p + 1; q < end; ++q) {
          const auto [a, b] = s[entries[p].second];
          const auto [c, d] = s[entries[q].second];
          const int sc = side(a, b, c), sd = side(a, b, d), sa = side(c, d, a), sb = side(c, d, b);
          if (sc * sd >= 0 || sa * sb >= 0) continue;  // touching and overlapping ends are hot already
          const double ca = cross(d - c, a - c), cb = cross(d - c, b - c);
          found.push_back(snap_to(lerp(a, b, ca / (ca - cb)), step));
        }
    }
    std::sort(found.begin(), found.end(), xy_less);
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  };
  // An end within one pixel of a crossing merges into it, unless it ends a segment that
  // must stay monotone (a vertex the arrangement has): a road computed to stop at another
  // and snapped a pixel past it would otherwise end in a tail one pixel long beyond the
  // junction (the snapping tolerance of a snapping noder).
  std::vector<Vec2> crossing = crossings();
  if (!crossing.empty()) {
    std::vector<Vec2> fixed;
    for (std::size_t i = 0; i < n && i < monotone.size(); ++i)
      if (monotone[i]) fixed.push_back(s[i].first), fixed.push_back(s[i].second);
    std::sort(fixed.begin(), fixed.end(), xy_less);
    auto merged = [&](Vec2 e) {
      if (std::binary_search(fixed.begin(), fixed.end(), e, xy_less)) return e;
      auto it = std::lower_bound(crossing.begin(), crossing.end(), Vec2{e.x - step, -INFINITY}, xy_less);
      Vec2 best = e;
      double best_d = INFINITY;
      for (; it != crossing.end() && it->x <= e.x + step; ++it) {
        const double d = std::max(std::abs(it->x - e.x), std::abs(it->y - e.y));
        if (d > 0 && d <= step * (1 + 1e-9) && d < best_d) best = *it, best_d = d;
      }
      return best;
    };
    for (auto& [a, b] : s) a = merged(a), b = merged(b);
    crossing = crossings();
  }
  hot.clear();
  for (const auto& [a, b] : s) hot.push_back(a), hot.push_back(b);
  hot.insert(hot.end(), crossing.begin(), crossing.end());
  std::sort(hot.begin(), hot.end(), [](Vec2 a, Vec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  hot.erase(std::unique(hot.begin(), hot.end()), hot.end());
  std::vector<std::pair<long, int>> hot_in;  // (bucket, hot pixel)
  for (std::size_t k = 0; k < hot.size(); ++k) hot_in.push_back({grid.key(hot[k]), static_cast<int>(k)});
  std::sort(hot_in.begin(), hot_in.end());

  // Each segment through the hot pixels it meets, a hair past half a step so a pixel the
  // segment grazes in exact arithmetic is not missed by rounding; then each piece again,
  // until no piece meets a hot pixel not its own (iterated snap rounding: the result, noded
  // again on the same grid, stays as it is).
  const double half = step * (0.5 + 1e-9);
  std::vector<std::pair<double, Vec2>> found;
  auto hot_on = [&](Vec2 p, Vec2 q) {
    found.clear();
    const Vec2 d = q - p;
    grid.along(p, q, step, [&](long k) {
      for (auto it = std::lower_bound(hot_in.begin(), hot_in.end(), std::pair<long, int>(k, INT_MIN));
           it != hot_in.end() && it->first == k; ++it) {
        const Vec2 c = hot[it->second];
        if (c == p || c == q || enters_square(p, q, c, half) < 0) continue;
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
    const bool rightwards = xy_less(a, b), one_way = i < monotone.size() && monotone[i];
    auto ahead = [&](Vec2 p, Vec2 q) { return !one_way || (rightwards ? xy_less(p, q) : xy_less(q, p)); };
    Polyline line{a, b};
    for (int round = 0; round < 16; ++round) {
      Polyline next{a};
      bool changed = false;
      for (std::size_t k = 0; k + 1 < line.size(); ++k) {
        hot_on(line[k], line[k + 1]);
        for (const auto& [u, c] : found)
          if (ahead(next.back(), c) && ahead(c, line[k + 1]) && !(c == next.back()) &&
              std::find(line.begin(), line.end(), c) == line.end())
            next.push_back(c), changed = true;
        next.push_back(line[k + 1]);
      }
      line = std::move(next);
      if (!changed) break;
    }
    out[i] = std::move(line);
  }
  return out;
}

}  // namespace geom
