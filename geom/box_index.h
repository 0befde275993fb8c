// Boxes in buckets of a uniform grid, to find those that may meet a query box without a
// pass over all of them: the layouts' passes that compared every road with every other
// (settling a grammar's thousands of roads, joining their ends) were quadratic. A filter
// in doubles only: callers decide on the candidates exactly as they did over all boxes.
#pragma once

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geom/plain.h"

namespace geom {

class BoxIndex {
 public:
  // `bucket`: the grid's step, about the size of a query (a non-positive or non-finite
  // step keeps every box in one list).
  explicit BoxIndex(double bucket) : bucket_(std::isfinite(bucket) && bucket > 0 ? bucket : 0) {}

  // Box number `id` (ids may repeat: a box that grew is added again under its id).
  void add(int id, const Box& b) {
    if (static_cast<int>(boxes_.size()) <= id) boxes_.resize(id + 1, Box::none());
    boxes_[id].add(b);
    const Box& all = boxes_[id];
    if (all.holds_nothing()) return;  // meets no query
    long x0, y0, x1, y1;
    if (!keys(all, x0, y0, x1, y1) || buckets(x0, y0, x1, y1) > kMaxBuckets) {
      wide_.push_back(id);
      return;
    }
    for (long j = y0; j <= y1; ++j)
      for (long i = x0; i <= x1; ++i) {
        std::vector<int>& bucket = buckets_[{i, j}];
        if (bucket.empty() || bucket.back() != id) bucket.push_back(id);
      }
  }

  // The ids of the boxes meeting q (touching counts), ascending, each once.
  std::vector<int> meeting(const Box& q) const {
    std::vector<int> out;
    long x0, y0, x1, y1;
    if (!keys(q, x0, y0, x1, y1) || buckets(x0, y0, x1, y1) > static_cast<double>(buckets_.size())) {
      for (std::size_t id = 0; id < boxes_.size(); ++id)
        if (boxes_[id].meets(q)) out.push_back(static_cast<int>(id));
      return out;
    }
    for (long j = y0; j <= y1; ++j)
      for (long i = x0; i <= x1; ++i)
        if (auto it = buckets_.find({i, j}); it != buckets_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    out.insert(out.end(), wide_.begin(), wide_.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    out.erase(std::remove_if(out.begin(), out.end(), [&](int id) { return !boxes_[id].meets(q); }), out.end());
    return out;
  }

 private:
  static constexpr double kMaxBuckets = 1024;  // a box over more lies in every query's list
  static constexpr double kMaxKey = 1e15;      // keys stay exact in a long and a double

  // The buckets the box covers; false when there is no grid or the box is past it. Boxes
  // that meet share a bucket: dividing and flooring keep the order of coordinates.
  bool keys(const Box& b, long& x0, long& y0, long& x1, long& y1) const {
    if (bucket_ == 0 || b.holds_nothing()) return false;
    const double k[4] = {std::floor(b.min_x / bucket_), std::floor(b.min_y / bucket_), std::floor(b.max_x / bucket_),
                         std::floor(b.max_y / bucket_)};
    for (double v : k)
      if (!(std::abs(v) < kMaxKey)) return false;
    x0 = static_cast<long>(k[0]), y0 = static_cast<long>(k[1]), x1 = static_cast<long>(k[2]), y1 = static_cast<long>(k[3]);
    return true;
  }
  static double buckets(long x0, long y0, long x1, long y1) {
    return (static_cast<double>(x1) - x0 + 1) * (static_cast<double>(y1) - y0 + 1);
  }

  struct PairHash {
    std::size_t operator()(const std::pair<long, long>& k) const { return std::hash<unsigned long>()(static_cast<unsigned long>(k.first) * 1000003u ^ static_cast<unsigned long>(k.second)); }
  };
  double bucket_;
  std::vector<Box> boxes_;
  std::vector<int> wide_;
  std::unordered_map<std::pair<long, long>, std::vector<int>, PairHash> buckets_;
};

}  // namespace geom
