// The exact insides of Path and Cell, for geom/*.cpp only.
#pragma once

#include "geom/cell.h"
#include "geom/exact.h"

namespace geom {

struct Path::Impl {
  std::vector<exact::Point> points;
};

// A ring with the interior on its left: counter-clockwise outside, clockwise for holes.
struct KindRing {
  std::vector<exact::Point> points;
  std::vector<int> kinds;  // kinds[i]: the edge points[i] -> points[i + 1]
  // points rounded to doubles (exact::to_plain), by make_cell unless given one per point:
  // rounding an exact vertex is costly, and a map's cells share their vertices
  std::vector<Vec2> rounded;
};

struct Cell::Impl {
  KindRing outer;
  std::vector<KindRing> holes;
  double area = 0;
  Box bounds;
};

// Builds a cell, rounding its vertices and computing its area and bounds.
Cell make_cell(KindRing outer, std::vector<KindRing> holes);

}  // namespace geom
