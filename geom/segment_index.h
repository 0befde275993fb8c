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
    for (long j = key(std::min(a.y, b.y)); j <= key(std::max(a.y, b.y)); ++j)
      for (long i = key(std::min(a.x, b.x)); i <= key(std::max(a.x, b.x)); ++i) buckets_[{i, j}].push_back(id);
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
