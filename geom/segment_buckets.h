// A grid of square buckets over a box, each segment entered in every bucket it passes
// within `reach` of: how snap rounding and snapping near pairs find what lies near a
// segment without comparing every pair.
#pragma once

#include <algorithm>
#include <cmath>

#include "geom/plain.h"

namespace geom {

struct SegmentBuckets {
  Box box;
  double size;
  long columns, rows;

  SegmentBuckets(const Box& b, double bucket_size)
      : box(b), size(bucket_size), columns(static_cast<long>(b.width() / bucket_size) + 1),
        rows(static_cast<long>(b.height() / bucket_size) + 1) {}

  long column(double x) const { return std::clamp(static_cast<long>(std::floor((x - box.min_x) / size)), 0L, columns - 1); }
  long row(double y) const { return std::clamp(static_cast<long>(std::floor((y - box.min_y) / size)), 0L, rows - 1); }
  long key(Vec2 p) const { return column(p.x) * rows + row(p.y); }

  // f(key) for every bucket the segment a -> b passes within `reach` of: per column, the
  // segment's y-range over that column only (over all of it within one or two columns).
  template <typename F>
  void along(Vec2 a, Vec2 b, double reach, F f) const {
    const double x0 = std::min(a.x, b.x) - reach, x1 = std::max(a.x, b.x) + reach;
    for (long i = column(x0); i <= column(x1); ++i) {
      double y0 = std::min(a.y, b.y), y1 = std::max(a.y, b.y);
      if (column(x1) - column(x0) > 1) {
        const double lo = std::max(x0, box.min_x + static_cast<double>(i) * size - reach);
        const double hi = std::min(x1, box.min_x + static_cast<double>(i + 1) * size + reach);
        auto y_at = [&](double x) { return a.y + (b.y - a.y) * std::clamp((x - a.x) / (b.x - a.x), 0.0, 1.0); };
        y0 = std::min(y_at(lo), y_at(hi)), y1 = std::max(y_at(lo), y_at(hi));
      }
      for (long j = row(y0 - reach); j <= row(y1 + reach); ++j) f(i * rows + j);
    }
  }
};

}  // namespace geom
