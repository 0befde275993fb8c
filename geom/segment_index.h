// Segments in buckets, to find those near a point (a measure in doubles, for checks
// against the drawn sketch and for statistics; never for topology).
#pragma once

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geom/measure.h"
#include "geom/plain.h"

namespace geom {

class SegmentIndex {
 public:
  explicit SegmentIndex(double bucket) : bucket_(bucket) {}
  void add(Vec2 a, Vec2 b, int owner = -1) {
    std::size_t id = segments_.size();
    segments_.push_back({a, b});
    owners_.push_back(owner);
    // The buckets within one of those the segment passes through, in its box: the whole box
    // of a long diagonal edge (water over a map of 1e6 m) held buckets past counting.
    const double y0 = std::min(a.y, b.y), y1 = std::max(a.y, b.y);
    auto x_at = [&](double y) { return a.y == b.y ? a.x : a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y); };
    const long i0 = key(std::min(a.x, b.x)), i1 = key(std::max(a.x, b.x));
    for (long j = key(y0); j <= key(y1); ++j) {
      const double xa = x_at(std::max(y0, (j - 1) * bucket_)), xb = x_at(std::min(y1, (j + 2) * bucket_));
      const double x0 = a.y == b.y ? std::min(a.x, b.x) : std::min(xa, xb),
                   x1 = a.y == b.y ? std::max(a.x, b.x) : std::max(xa, xb);
      for (long i = std::max(i0, key(x0) - 1); i <= std::min(i1, key(x1) + 1); ++i) buckets_[{i, j}].push_back(id);
    }
  }
  void add_polygon(const Polygon& p, int owner = -1) {
    for (const Ring* r : rings(p))
      for (std::size_t i = 0; i < r->size(); ++i) add((*r)[i], (*r)[(i + 1) % r->size()], owner);
  }
  // Whether a segment not owned by `except` passes within `tolerance` of p.
  bool near(Vec2 p, double tolerance, int except = -2) const {
    auto it = buckets_.find({key(p.x), key(p.y)});
    if (it == buckets_.end()) return false;
    for (std::size_t id : it->second) {
      if (owners_[id] == except) continue;
      auto [a, b] = segments_[id];
      if (distance_to_segment(p, a, b) <= tolerance) return true;
    }
    return false;
  }

 private:
  long key(double v) const { return static_cast<long>(std::floor(v / bucket_)); }
  struct PairHash {
    std::size_t operator()(const std::pair<long, long>& k) const { return std::hash<long>()(k.first * 1000003 ^ k.second); }
  };
  static std::vector<const Ring*> rings(const Polygon& p) {
    std::vector<const Ring*> r{&p.outer};
    for (const auto& h : p.holes) r.push_back(&h);
    return r;
  }
  double bucket_;
  std::vector<std::pair<Vec2, Vec2>> segments_;
  std::vector<int> owners_;
  std::unordered_map<std::pair<long, long>, std::vector<std::size_t>, PairHash> buckets_;
};

}  // namespace geom
