#include "benchmarks/families.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "generate/city/random.h"

namespace exacity::bench {
namespace {

using json = nlohmann::ordered_json;
struct P {
  double x, y;
};
using Line = std::vector<P>;

json positions(const Line& line, bool closed) {
  json out = json::array();
  for (const P& p : line) out.push_back({p.x, p.y});
  if (closed) out.push_back({line.front().x, line.front().y});
  return out;
}

json zone(const char* type, const std::vector<Line>& rings) {
  json coordinates = json::array();
  for (const Line& r : rings) coordinates.push_back(positions(r, true));
  return {{"type", "Feature"},
          {"properties", {{"zone", type}}},
          {"geometry", {{"type", "Polygon"}, {"coordinates", coordinates}}}};
}

json road(const char* cls, double width, const Line& line) {
  return {{"type", "Feature"},
          {"properties", {{"road", cls}, {"width", width}}},
          {"geometry", {{"type", "LineString"}, {"coordinates", positions(line, false)}}}};
}

Line rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

Line moved(Line line, P by) {
  for (P& p : line) p.x += by.x, p.y += by.y;
  return line;
}

// 10^-(from + (to - from) * t): a step of a logarithmic sweep, t in [0, 1].
double sweep(double from, double to, int index, int steps) {
  const double t = steps > 1 ? static_cast<double>(index % steps) / (steps - 1) : 0;
  return std::pow(10.0, -(from + (to - from) * t));
}

// A sweep's step for case `index`: the step runs fastest, so any run of `steps` cases or more
// covers every level; the variant (which drawing of the family) changes every `steps` cases.
int step_of(int index, int steps) { return index % steps; }
int variant_of(int index, int steps, int variants) { return (index / steps) % variants; }

// A side at random: +1 or -1.
double side(Random& rng) { return rng.next() % 2 ? 1 : -1; }

const char* const kBuilt[] = {"residential", "commercial", "industrial"};

// m: the grid the snap-rounding baselines round to (the practitioner's float build,
// geom/exact.h, and GEOS in fixed precision), 60 nm. At these cities' coordinates (up to
// 1 km) a double's step is 1e-13 m or less, far finer, so the grid is what a float
// pipeline resolves.
constexpr double kGrid = 1.0 / (1 << 24);

// A distance's level: how many powers of ten it lies below the grid (0 one grid step off,
// negative farther, about 6 at a double's step). A distance of 0 (exactly on) counts as
// half a double's step at `magnitude`, the coordinates it was drawn at.
double level_below_grid(double distance, double magnitude) {
  return std::log10(kGrid / std::max(distance, std::ldexp(std::nextafter(magnitude, INFINITY) - magnitude, -1)));
}

// The distance families are cumulative: a case at step s of the sweep holds one
// near-degenerate feature at every step from the harmless end (0.1 m) down to s, each
// where it does not meet the others, and its level is that of the nearest. A lone feature
// below the grid snaps onto the degenerate case, which a snapping pipeline handles, so
// without the shallower features a snapping pipeline's failures against the distance are
// a bump a few grid steps wide, not a rise (docs/benchmarks.md): a sketch with one corner
// 1e-12 m off an edge does not contain the corner 1e-7 m off that one with a few corners
// off has. Counting features, the deeper case holds the shallower one's and more.

// 1. Kettner et al.'s classroom example in a city: corners of a zone stepped off the line
// y = x, on which a neighbouring zone's edge runs, by 1e-1 down to 1e-14 m (a few ulps at
// 100 m: below that the corner is on the line), to either side; the two zones overlap,
// touch or part by a sliver there, as the orientation of (q, r, p) decides. Level: the
// nearest corner's distance off the line, as drawn, below the grid (level_below_grid:
// -6.2 at 0.1 m, 6.6 on the line).
json near_collinear(Random& rng, int index, double& level) {
  const int steps = 14, deepest = step_of(index, steps);
  const P q{-200, -200}, r{400, 400};
  Line residential{q, {400, -200}, r};
  level = -INFINITY;
  for (int k = 0; k <= deepest; ++k) {
    // Corners from r back towards q, in order along the line, each 500 / (deepest + 2) m apart.
    const double t = 350 - (k + 1) * 500.0 / (deepest + 2) + rng.uniform(-5, 5);
    const P p{t, t + side(rng) * sweep(1, 14, k, steps) * std::sqrt(2.0)};
    // Near the line p.y - p.x is exact (Sterbenz), so this is the distance as drawn.
    level = std::max(level, level_below_grid(std::abs(p.y - p.x) / std::sqrt(2.0), t));
    residential.push_back(p);
  }
  return json::array({zone("commercial", {{q, r, {-200, 400}}}), zone("residential", {residential}),
                      road("highway", 18, {{-300, 90 + rng.uniform(0, 20)}, {500, 80 + rng.uniform(0, 20)}})});
}

// A small city at random: a few overlapping zones of every kind and a highway or two.
json random_city(Random& rng, P offset) {
  json features = json::array();
  const int zones = 3 + static_cast<int>(rng.next() % 4);
  for (int k = 0; k < zones; ++k) {
    const double x = rng.uniform(0, 500), y = rng.uniform(0, 500), w = rng.uniform(80, 350), h = rng.uniform(80, 350);
    const double kind = rng.uniform();
    const char* type = kind < 0.1 ? "water" : kind < 0.2 ? "park" : kBuilt[rng.next() % 3];
    features.push_back(zone(type, {moved(rect(x, y, x + w, y + h), offset)}));
  }
  const int highways = static_cast<int>(rng.next() % 3);
  for (int k = 0; k < highways; ++k) {
    Line line{{rng.uniform(-100, 0), rng.uniform(0, 800)}, {rng.uniform(300, 500), rng.uniform(0, 800)},
              {rng.uniform(800, 900), rng.uniform(0, 800)}};
    features.push_back(road(k == 0 ? "highway" : "main", k == 0 ? 18 : 10, moved(line, offset)));
  }
  return features;
}

// 2. One random city translated to 1e5, 1e6 (UTM), 1e7, 1e8, 10^8.5, 1e9 and 10^9.5 m: a
// double's step there is 1.5e-11 to 4.8e-7 m, as coarse as the 2^-24 m grid from 2^29 m
// (5.4e8 m) on and half the 1e-6 m grid (the grid build's, geom/grid_kernel.h) at 10^9.5 m,
// the last half power of ten before 1e10 m, beyond which Exacity refuses a sketch
// (generate/sketch/sketch.cpp). Level: log10 of the translation.
json translated(Random& rng, int index, double& level) {
  static const double offsets[] = {1e5, 1e6, 1e7, 1e8, std::pow(10.0, 8.5), 1e9, std::pow(10.0, 9.5)};
  const double o = offsets[step_of(index, static_cast<int>(std::size(offsets)))];
  level = std::log10(o);
  return random_city(rng, {o, o / 2});
}

// 3. Highways crossing at angles from 1e-3 down to 1e-12 radians inside a zone, or (the
// second variant) nearly parallel, 5 m apart where they enter it. Level: -log10 of the
// angle.
json thin_angles(Random& rng, int index, double& level) {
  const double angle = sweep(3, 12, index, 10);
  level = -std::log10(angle);
  const P at{rng.uniform(150, 350), rng.uniform(150, 250)};
  const double apart = variant_of(index, 10, 2) ? 5 : 0;
  const double reach = 600;
  Line first{{at.x - reach, at.y}, {at.x + reach, at.y}};
  Line second{{at.x - reach * std::cos(angle), at.y + apart - reach * std::sin(angle)},
              {at.x + reach * std::cos(angle), at.y + apart + reach * std::sin(angle)}};
  return json::array({zone("residential", {rect(0, 0, 500, 400)}), zone("commercial", {rect(500, 0, 800, 400)}),
                      road("highway", 18, first), road("main", 10, second)});
}

// 4. Zone corners moved off a shared edge (first variant), or off a highway's centre line
// (second), by 1e-1 down to 1e-14 m, to either side, cumulative: at 300 m a double's step
// is 5.7e-14 m, so the last steps are two ulps off and on the edge (300 + 1e-14 is 300),
// the ulps the family is named for. Level: the nearest offset as drawn (300 + d less 300,
// in doubles) below the grid (level_below_grid: -6.2 at 0.1 m, 5.8 two ulps off, 6.8 on).
json off_edge(Random& rng, int index, double& level) {
  const int steps = 14, deepest = step_of(index, steps);
  const double spacing = 360.0 / (deepest + 1);
  std::vector<double> offsets;
  level = -INFINITY;
  for (int k = 0; k <= deepest; ++k) {
    offsets.push_back(sweep(1, 14, k, steps) * side(rng));
    level = std::max(level, level_below_grid(std::abs((300 + offsets.back()) - 300), 300));
  }
  // Corner k along the edge, from its far end back (the ring's order), somewhere in its share.
  auto along = [&](int k) { return 380 - (k + rng.uniform(0.2, 0.8)) * spacing; };
  if (variant_of(index, steps, 2) == 0) {
    Line commercial{{300, 0}, {600, 0}, {600, 400}, {300, 400}};
    for (int k = 0; k <= deepest; ++k) commercial.push_back({300 + offsets[k], along(k)});
    return json::array({zone("residential", {rect(0, 0, 300, 400)}), zone("commercial", {commercial})});
  }
  Line residential{{0, 0}, {600, 0}, {600, 300}};
  for (int k = 0; k <= deepest; ++k) residential.push_back({600 * along(k) / 400, 300 + offsets[k]});
  residential.push_back({0, 300});
  return json::array({zone("residential", {residential}), zone("industrial", {rect(0, 300, 600, 600)}),
                      road("highway", 16, {{-100, 300}, {700, 300}})});
}

// 5. Zones sharing edges exactly, overlapping along collinear edges, touching at a point,
// drawn twice. Level: how many rings run along one edge (two sharing it, two overlapping
// along part of it, two touching at a point with a road through it, three drawn on each
// other).
json shared_edges(Random& rng, int index, double& level) {
  const double a = rng.uniform(150, 400), b = rng.uniform(150, 400);
  level = index % 4 == 3 ? 3 : 2;
  switch (index % 4) {
    case 0:
      return json::array({zone("residential", {rect(0, 0, a, b)}), zone("commercial", {rect(a, 0, 2 * a, b)}),
                          zone("industrial", {rect(0, b, a, 2 * b)}), zone("park", {rect(a, b, 2 * a, 2 * b)})});
    case 1:
      return json::array({zone("residential", {rect(0, 0, a, b)}), zone("commercial", {rect(a, b / 3, 2 * a, 1.5 * b)}),
                          zone("industrial", {rect(a / 4, b, 0.75 * a, 2 * b)})});
    case 2:
      return json::array({zone("residential", {rect(0, 0, a, b)}), zone("commercial", {rect(a, b, 2 * a, 2 * b)}),
                          road("main", 10, {{0, 2 * b}, {a, b}, {2 * a, 0}})});
    default:
      return json::array({zone("residential", {rect(0, 0, a, b)}), zone("commercial", {rect(0, 0, a, b)}),
                          zone("residential", {rect(0, 0, a, b)})});
  }
}

// 6. Slivers 1e-1 down to 1e-12 m wide, cumulative: zones that wide side by side (first
// variant), spikes that wide out of a zone (second), or holes touching their outer ring
// whose first edge rises that far over 100 m (third). Level: the narrowest width below the
// grid (level_below_grid: -6.2 at 0.1 m, 4.8 at 1e-12 m).
json slivers(Random& rng, int index, double& level) {
  const int steps = 12, deepest = step_of(index, steps);
  const double a = rng.uniform(200, 400), b = rng.uniform(200, 400);
  std::vector<double> widths;
  for (int k = 0; k <= deepest; ++k) widths.push_back(sweep(1, 12, k, steps));
  level = level_below_grid(widths.back(), 2 * a);
  const double spacing = b / (deepest + 2);
  switch (variant_of(index, steps, 3)) {
    case 0: {
      json features = json::array({zone("residential", {rect(0, 0, a, b)})});
      double x = a;
      for (int k = 0; k <= deepest; ++k) {
        features.push_back(zone(kBuilt[1 + k % 2], {rect(x, 0, x + widths[k], b)}));
        x += widths[k];
      }
      features.push_back(zone("park", {rect(x, 0, 2 * a, b)}));
      return features;
    }
    case 1: {
      Line ring{{0, 0}, {a, 0}};
      for (int k = 0; k <= deepest; ++k) {
        const double y = (k + 1) * spacing;
        ring.push_back({a, y}), ring.push_back({a + 300, y + widths[k]}), ring.push_back({a, y + 2 * widths[k]});
      }
      ring.push_back({a, b}), ring.push_back({0, b});
      return json::array({zone("residential", {ring})});
    }
    default: {
      // An outer ring through one point twice, and holes touching the outer ring.
      std::vector<Line> commercial{rect(a + 50, 0, 2 * a + 50, b)};
      for (int k = 0; k <= deepest; ++k) {
        const double y = (k + 0.5) * spacing;
        commercial.push_back({{a + 50, y}, {a + 150, y + widths[k]}, {a + 150, y + 0.6 * spacing}});
      }
      return json::array({zone("residential", {{{0, 0}, {a, 0}, {a / 2, b / 2}, {a, b}, {0, b}, {a / 2, b / 2}}}),
                          zone("commercial", commercial)});
    }
  }
}

// 7. 2 to 13 roads through one point at random angles: in the first variant each has a
// vertex there (they meet exactly), in the second each is one straight segment whose ends
// are rounded to doubles, so they pass that point only within a few ulps and their
// crossings crowd into a cluster a few ulps wide. Level: how many roads pass through the
// point.
json many_highways(Random& rng, int index, double& level) {
  json features = json::array({zone("residential", {rect(0, 0, 500, 500)}), zone("commercial", {rect(500, 0, 800, 500)})});
  const P c{rng.uniform(100, 400), rng.uniform(100, 400)};
  const int n = 2 + step_of(index, 12);
  const bool straight = variant_of(index, 12, 2);
  level = n;
  for (int k = 0; k < n; ++k) {
    const double t = rng.uniform(0, M_PI);
    const P from{c.x - 700 * std::cos(t), c.y - 700 * std::sin(t)}, to{c.x + 700 * std::cos(t), c.y + 700 * std::sin(t)};
    features.push_back(road(k == 0 ? "highway" : "main", k == 0 ? 16 : 8, straight ? Line{from, to} : Line{from, c, to}));
  }
  return features;
}

// 8. Zones in a row whose edges run side by side 1e-1 down to 1e-12 m apart, cumulative, a
// road across the gaps. Level: the narrowest gap as drawn (x + gap less x, in doubles)
// below the grid (level_below_grid: -6.2 at 0.1 m, 4.8 at 1e-12 m).
json near_touching(Random& rng, int index, double& level) {
  const int steps = 12, deepest = step_of(index, steps);
  const double w = rng.uniform(50, 70), b = rng.uniform(200, 400), y = rng.uniform(0.2 * b, 0.8 * b);
  json features = json::array();
  double x = 0;
  level = -INFINITY;
  for (int k = 0; k <= deepest + 1; ++k) {
    features.push_back(zone(kBuilt[k % 3], {rect(x, 0, x + w, b)}));
    if (k > deepest) break;
    const double gap = sweep(1, 12, k, steps);
    level = std::max(level, level_below_grid((x + w + gap) - (x + w), x + w));
    x = x + w + gap;
  }
  features.push_back(road("main", 10, {{-50, y}, {x + w + 50, y + rng.uniform(-2, 2)}}));
  return features;
}

// 9. Holes 1e-1 down to 1e-12 m across, cumulative: in a zone (first variant: triangles of
// that circumradius, every third under a main road), or ordinary holes whose corners run
// that far inside the zone's outer ring, nearly touching it (second). Level: the smallest
// hole's size or the narrowest gap below the grid (level_below_grid: -6.2 at 0.1 m, 4.8 at
// 1e-12 m).
json tiny_holes(Random& rng, int index, double& level) {
  const int steps = 12, deepest = step_of(index, steps);
  const double a = rng.uniform(300, 500), b = rng.uniform(300, 500);
  std::vector<Line> rings{rect(0, 0, a, b)};
  level = -INFINITY;
  if (variant_of(index, steps, 2) == 0) {
    const double road_y = rng.uniform(0.3, 0.7) * b;
    for (int k = 0; k <= deepest; ++k) {
      const double s = sweep(1, 12, k, steps);
      // Spread along x so no two meet; every third on the road's centre line.
      const P c{(k + rng.uniform(0.3, 0.7)) * a / (deepest + 1), k % 3 == 1 ? road_y : rng.uniform(20, b - 20)};
      const double t = rng.uniform(0, 2 * M_PI);
      Line hole;
      for (int v = 0; v < 3; ++v) hole.push_back({c.x + s * std::cos(t + 2 * M_PI * v / 3), c.y + s * std::sin(t + 2 * M_PI * v / 3)});
      rings.push_back(hole);
      level = std::max(level, level_below_grid(s, std::max(a, b)));
    }
    return json::array({zone("residential", rings), zone("commercial", {rect(a, 0, a + 200, b)}),
                        road("main", 10, {{-50, road_y}, {a + 250, road_y + rng.uniform(-5, 5)}})});
  }
  // Holes 100 m across, each with one corner s inside the outer ring's right edge (in
  // doubles: the gap as drawn).
  const double spacing = (b - 20) / (deepest + 1);
  for (int k = 0; k <= deepest; ++k) {
    const double y = 10 + (k + 0.5) * spacing, x = a - sweep(1, 12, k, steps), h = 0.4 * spacing;
    rings.push_back({{x - 100, y - h}, {x, y}, {x - 100, y + h}});
    level = std::max(level, level_below_grid(a - x, a));
  }
  return json::array({zone("residential", rings), zone("industrial", {rect(a, 0, a + 200, b)})});
}

// 10 and 11. Zone edges in a band a few grid steps wide: each of 1 to 12 zones has one long
// edge from near a point P to near a point Q 400 m away (slanted, on no axis), the zones on
// alternate sides of it and over one background zone, and a main road crosses them all. In
// `stacked-edges` each end lies anywhere within half the band of P or Q, so the edges cross
// each other at angles near 1e-9 rad, each crossing inside the band; in `parallel-edges`
// both ends of an edge move by the same offset, so the edges run side by side, parallel and
// less than the band apart, and never cross. The band is 3e-7 m in the first variant (five
// steps of the 2^-24 m grid the snapped builds round to) and 5e-6 m in the second (five steps
// of the grid build's 1e-6 m). Snapping merges neither into one line: the band's hot pixels
// crowd, and each edge is routed through the pixels of the others' ends and crossings, more
// of them with every edge. Level: how many edges run in the band.
json edges_in_a_band(Random& rng, int index, double& level, bool crossing) {
  const int steps = 12, n = 1 + step_of(index, steps);
  const double band = variant_of(index, steps, 2) == 0 ? 3e-7 : 5e-6;
  level = n;
  const P from{rng.uniform(80, 120), rng.uniform(40, 80)}, to{rng.uniform(480, 520), rng.uniform(320, 360)};
  auto offset = [&] { return P{rng.uniform(-band / 2, band / 2), rng.uniform(-band / 2, band / 2)}; };
  static const char* const kinds[] = {"park", "commercial", "industrial"};
  json features = json::array({zone("residential", {rect(0, 0, 600, 420)})});
  for (int k = 0; k < n; ++k) {
    const P d = offset(), e = crossing ? offset() : d;
    const P p{from.x + d.x, from.y + d.y}, q{to.x + e.x, to.y + e.y};
    const double off = 20 + 15 * k;  // each zone a little wider than the last, so all show
    const Line ring = k % 2 == 0 ? Line{p, q, {q.x - off, q.y + 0.3 * off}, {p.x - off, p.y + 1.2 * off}}
                                 : Line{p, {p.x + 1.2 * off, p.y - 0.3 * off}, {q.x + off, q.y - off}, q};
    features.push_back(zone(kinds[k % 3], {ring}));
  }
  features.push_back(road("main", 10, {{rng.uniform(200, 300), -50}, {rng.uniform(300, 400), 450}}));
  return features;
}

// The band families' widths, per variant: a third of a step of the grid the snapped builds
// round to (2^-24 m) in the first, of the grid build's 1e-6 m in the second.
double third_of_a_step(int index, int steps) { return variant_of(index, steps, 2) == 0 ? 2e-8 : 3e-7; }

P along(P from, P u, P n, double a, double b) { return {from.x + a * u.x + b * n.x, from.y + a * u.y + b * n.y}; }

// 12. 1 to 12 square zones nested in each other, each a third of a grid step inside the last
// (2e-8 m in the first variant, 3e-7 m in the second), turned 0.15 to 0.6 rad off the axes
// and drawn in order over a background zone, each over the last, so every ring nearly
// touches the next all round, and a main road across. Level: how many rings are nested.
json nested_rings(Random& rng, int index, double& level) {
  const int steps = 12, n = 1 + step_of(index, steps);
  const double gap = third_of_a_step(index, steps);
  level = n;
  const double t = rng.uniform(0.15, 0.6), half = rng.uniform(120, 160);
  const P c{rng.uniform(280, 320), rng.uniform(190, 230)}, u{std::cos(t), std::sin(t)}, v{-u.y, u.x};
  static const char* const kinds[] = {"park", "commercial", "industrial"};
  json features = json::array({zone("residential", {rect(0, 0, 600, 420)})});
  for (int k = 0; k < n; ++k) {
    const double s = half - k * gap;
    features.push_back(zone(kinds[k % 3], {{along(c, u, v, -s, -s), along(c, u, v, s, -s), along(c, u, v, s, s), along(c, u, v, -s, s)}}));
  }
  features.push_back(road("main", 10, {{rng.uniform(200, 300), -50}, {rng.uniform(300, 400), 450}}));
  return features;
}

// 13. 1 to 12 zones side by side, each a third of a grid step wide (2e-8 m in the first
// variant, 3e-7 m in the second) and 400 m long, along a line 0.15 to 0.6 rad off the axes,
// over a background zone: slivers stacked, neighbours sharing their long edges, and a main
// road across. Level: how many slivers are stacked.
json sliver_stack(Random& rng, int index, double& level) {
  const int steps = 12, n = 1 + step_of(index, steps);
  const double w = third_of_a_step(index, steps);
  level = n;
  const double t = rng.uniform(0.15, 0.6);
  const P from{rng.uniform(80, 120), rng.uniform(40, 80)}, u{std::cos(t), std::sin(t)}, v{-u.y, u.x};
  static const char* const kinds[] = {"park", "commercial", "industrial"};
  json features = json::array({zone("residential", {rect(0, 0, 600, 420)})});
  for (int k = 0; k < n; ++k)
    features.push_back(zone(kinds[k % 3], {{along(from, u, v, 0, k * w), along(from, u, v, 400, k * w),
                                            along(from, u, v, 400, (k + 1) * w), along(from, u, v, 0, (k + 1) * w)}}));
  features.push_back(road("main", 10, {{rng.uniform(200, 300), -50}, {rng.uniform(300, 400), 450}}));
  return features;
}

using Maker = json (*)(Random&, int, double& level);
struct Entry {
  Family family;
  Maker make;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list{
      {{"near-collinear", "zone corners 1e-1 to 1e-14 m off their neighbour's edge, every step down to the case's",
        "log10(grid / the nearest corner's distance off the line)"},
       near_collinear},
      {{"translated", "a random city at 1e5, 1e6, 1e7, 1e8, 10^8.5, 1e9 and 10^9.5 m", "log10 of the translation (m)"}, translated},
      {{"thin-angles", "highways crossing at 1e-3 to 1e-12 rad, or nearly parallel", "-log10 of the angle (rad)"},
       thin_angles},
      {{"off-edge", "corners 1e-1 to 1e-14 m (on it) off a shared edge or a highway, every step down to the case's", "log10(grid / the nearest offset)"}, off_edge},
      {{"shared-edges", "zones sharing edges, overlapping along them, touching at a point, drawn twice",
        "rings along one edge"},
       shared_edges},
      {{"slivers", "zones, spikes and holes 1e-1 to 1e-12 m wide, every step down to the case's; rings touching themselves", "log10(grid / the narrowest width)"},
       slivers},
      {{"many-highways", "2 to 13 roads through one point, meeting at a vertex or crossing within ulps of it",
        "roads through one point"},
       many_highways},
      {{"near-touching", "zones in a row 1e-1 to 1e-12 m apart, every step down to the case's, a road across the gaps", "log10(grid / the narrowest gap)"},
       near_touching},
      {{"tiny-holes", "holes 1e-1 to 1e-12 m across, or ordinary holes that far inside their outer ring, every step down to the case's",
        "log10(grid / the smallest size or gap)"},
       tiny_holes},
      {{"stacked-edges", "1 to 12 zone edges in a band 3e-7 or 5e-6 m wide, crossing each other inside it",
        "edges in the band"},
       [](Random& rng, int index, double& level) { return edges_in_a_band(rng, index, level, true); }},
      {{"parallel-edges", "1 to 12 parallel zone edges in a band 3e-7 or 5e-6 m wide", "edges in the band"},
       [](Random& rng, int index, double& level) { return edges_in_a_band(rng, index, level, false); }},
      {{"nested-rings", "1 to 12 slanted square zones nested each a third of a grid step inside the last", "rings nested"},
       nested_rings},
      {{"sliver-stack", "1 to 12 slanted zones a third of a grid step wide, side by side", "slivers stacked"},
       sliver_stack},
      {{"random", "small random cities (the control)", "0 (the control)"},
       [](Random& rng, int, double&) { return random_city(rng, {0, 0}); }},
  };
  return list;
}

std::uint64_t hash(const std::string& s) {
  std::uint64_t h = 0;
  for (unsigned char c : s) h = mix(h, c);
  return h;
}

}  // namespace

const std::vector<Family>& families() {
  static const std::vector<Family> list = [] {
    std::vector<Family> out;
    for (const Entry& e : entries()) out.push_back(e.family);
    return out;
  }();
  return list;
}

FamilyCase family_case(const std::string& family, int index, std::uint64_t seed) {
  for (const Entry& e : entries()) {
    if (e.family.name != family) continue;
    const std::uint64_t id = mix(mix(seed, hash(family)), static_cast<std::uint64_t>(index));
    Random rng(id);
    FamilyCase c;
    json features = e.make(rng, index, c.level);
    // The city's own seed: 53 bits, so any JSON reader keeps it exactly.
    json sketch = {{"type", "FeatureCollection"},
                   {"exacity", {{"version", 1}, {"seed", mix(id) >> 11}}},
                   {"features", std::move(features)}};
    c.sketch = sketch.dump() + "\n";
    return c;
  }
  throw std::invalid_argument("no family named \"" + family + "\"");
}

std::string family_sketch(const std::string& family, int index, std::uint64_t seed) {
  return family_case(family, index, seed).sketch;
}

}  // namespace exacity::bench
