#include "benchmarks/families.h"

#include <algorithm>
#include <cmath>
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

// 1. Kettner et al.'s classroom example in a city: a zone's corner p, stepped over a
// 256 x 256 grid around the point (100.5, 100.5) of the line y = x, on which a
// neighbouring zone's edge runs; the two zones overlap, touch or part by a sliver, as the
// orientation of (q, r, p) decides. The grid's step is 2^e ulps, e from 0 (Kettner's
// single ulps, 1e-14 m) up to 36 (1e-3 m), so the corner goes from an ordinary sketch's
// distances off the line (up to 0.25 m) down to ulps.
// Level: p's distance off the line, |i - j| steps / sqrt 2, below the grid
// (level_below_grid: from about -6.6 at 0.25 m to 6.6, half an ulp, on the line).
json near_collinear(Random& rng, int index, double& level) {
  const int i = static_cast<int>(rng.next() % 256), j = static_cast<int>(rng.next() % 256);
  const int e = 4 * (index % 10);
  // An ulp of 100.5 is 2^-46, so these sums are exact.
  const double step = std::ldexp(1.0, e - 46);
  level = level_below_grid(std::abs(i - j) * step / std::sqrt(2.0), 100.5);
  const P p{100.5 + i * step, 100.5 + j * step};
  const P q{-200, -200}, r{400, 400};
  return json::array({zone("commercial", {{q, r, {-200, 400}}}), zone("residential", {{q, {400, -200}, r, p}}),
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

// 2. One random city translated to 1e5, 1e6 (UTM), 1e7 and 1e9 m. Level: log10 of the
// translation.
json translated(Random& rng, int index, double& level) {
  static const double offsets[] = {1e5, 1e6, 1e7, 1e9};
  const double o = offsets[index % 4];
  level = std::log10(o);
  return random_city(rng, {o, o / 2});
}

// 3. Highways crossing at angles from 1e-3 down to 1e-12 radians inside a zone, or (odd
// cases) nearly parallel, 5 m apart where they enter it. Level: -log10 of the angle.
json thin_angles(Random& rng, int index, double& level) {
  const double angle = sweep(3, 12, index / 2, 10);
  level = -std::log10(angle);
  const P at{rng.uniform(150, 350), rng.uniform(150, 250)};
  const double apart = index % 2 ? 5 : 0;
  const double reach = 600;
  Line first{{at.x - reach, at.y}, {at.x + reach, at.y}};
  Line second{{at.x - reach * std::cos(angle), at.y + apart - reach * std::sin(angle)},
              {at.x + reach * std::cos(angle), at.y + apart + reach * std::sin(angle)}};
  return json::array({zone("residential", {rect(0, 0, 500, 400)}), zone("commercial", {rect(500, 0, 800, 400)}),
                      road("highway", 18, first), road("main", 10, second)});
}

// 4. Zone corners moved off a shared edge, or off a highway's centre line, by 1e-1 down to
// 1e-12 m, to either side. Level: the offset as drawn (300 + d less 300, in doubles) below
// the grid (level_below_grid: -6.2 at 0.1 m, 4.8 at 1e-12 m).
json off_edge(Random& rng, int index, double& level) {
  const double d = sweep(1, 12, index / 2, 12) * (rng.next() % 2 ? 1 : -1);
  level = level_below_grid(std::abs((300 + d) - 300), 300);
  const double y = rng.uniform(50, 350);
  if (index % 2 == 0)
    return json::array({zone("residential", {rect(0, 0, 300, 400)}),
                        zone("commercial", {{{300, 0}, {600, 0}, {600, 400}, {300, 400}, {300 + d, y}}})});
  const double x = rng.uniform(50, 550);
  return json::array({zone("residential", {{{0, 0}, {600, 0}, {600, 300}, {x, 300 + d}, {0, 300}}}),
                      zone("industrial", {rect(0, 300, 600, 600)}), road("highway", 16, {{-100, 300}, {700, 300}})});
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

// 6. Slivers 1e-3 down to 1e-9 m wide beside or inside a zone; spikes as thin; rings that
// touch themselves. Level: the width below the grid (level_below_grid: -4.2 at 1e-3 m, 1.8
// at 1e-9 m).
json slivers(Random& rng, int index, double& level) {
  const double w = sweep(3, 9, index / 3, 7);
  const double a = rng.uniform(200, 400), b = rng.uniform(200, 400);
  level = level_below_grid(w, a);
  switch (index % 3) {
    case 0:
      return json::array({zone("residential", {rect(0, 0, a, b)}), zone("commercial", {rect(a, 0, a + w, b)}),
                          zone("industrial", {rect(a + w, 0, 2 * a, b)}), zone("park", {rect(a / 3, -w, a / 2, b / 2)})});
    case 1:
      return json::array({zone("residential", {{{0, 0}, {a, 0}, {a, b / 2}, {a + 300, b / 2 + w}, {a, b / 2 + 2 * w},
                                               {a, b}, {0, b}}})});
    default:
      // An outer ring through one point twice, and a hole touching the outer ring.
      return json::array({zone("residential", {{{0, 0}, {a, 0}, {a / 2, b / 2}, {a, b}, {0, b}, {a / 2, b / 2}}}),
                          zone("commercial", {rect(a + 50, 0, 2 * a + 50, b), {{a + 50, b / 3}, {a + 150, b / 3 + w},
                                                                                {a + 150, 2 * b / 3}}})});
  }
}

// 7. 2 to 13 roads through one point at random angles: in even cases each has a vertex there
// (they meet exactly), in odd ones each is one straight segment whose ends are rounded to
// doubles, so they pass that point only within a few ulps and their crossings crowd into a
// cluster a few ulps wide. Level: how many roads pass through the point.
json many_highways(Random& rng, int index, double& level) {
  json features = json::array({zone("residential", {rect(0, 0, 500, 500)}), zone("commercial", {rect(500, 0, 800, 500)})});
  const P c{rng.uniform(100, 400), rng.uniform(100, 400)};
  const int n = 2 + (index / 2) % 12;
  level = n;
  for (int k = 0; k < n; ++k) {
    const double t = rng.uniform(0, M_PI);
    const P from{c.x - 700 * std::cos(t), c.y - 700 * std::sin(t)}, to{c.x + 700 * std::cos(t), c.y + 700 * std::sin(t)};
    features.push_back(road(k == 0 ? "highway" : "main", k == 0 ? 16 : 8, index % 2 ? Line{from, to} : Line{from, c, to}));
  }
  return features;
}

// 8. Zones whose edges run side by side 1e-1 down to 1e-12 m apart, a road across the gap.
// Level: the gap as drawn (a + gap less a, in doubles) below the grid (level_below_grid:
// -6.2 at 0.1 m, 4.8 at 1e-12 m).
json near_touching(Random& rng, int index, double& level) {
  const double gap = sweep(1, 12, index, 12);
  const double a = rng.uniform(200, 400), b = rng.uniform(200, 400), y = rng.uniform(0.2 * b, 0.8 * b);
  level = level_below_grid((a + gap) - a, a);
  return json::array({zone("residential", {rect(0, 0, a, b)}), zone("commercial", {rect(a + gap, 0, 2 * a, b)}),
                      zone("industrial", {rect(0, b + gap, a, 2 * b)}),
                      road("main", 10, {{-50, y}, {2 * a + 50, y + rng.uniform(-2, 2)}})});
}

// 9. Holes 1e-3 down to 1e-12 m across in a zone (even cases: three triangles of that
// circumradius, one under a main road), or an ordinary hole whose edge runs that far inside the zone's outer ring,
// nearly touching it (odd cases). Level: the hole's size or the gap below the grid
// (level_below_grid: -4.2 at 1e-3 m, 4.8 at 1e-12 m).
json tiny_holes(Random& rng, int index, double& level) {
  const double s = sweep(3, 12, index / 2, 12);
  const double a = rng.uniform(300, 500), b = rng.uniform(300, 500);
  const Line outer = rect(0, 0, a, b);
  std::vector<Line> rings{outer};
  if (index % 2 == 0) {
    const double road_y = rng.uniform(0.3, 0.7) * b;
    const P at[] = {{rng.uniform(20, a - 20), rng.uniform(20, 0.25 * b)}, {rng.uniform(20, a - 20), road_y},
                    {rng.uniform(20, a - 20), rng.uniform(0.75 * b, b - 20)}};
    for (const P& c : at) {
      const double t = rng.uniform(0, 2 * M_PI);
      Line hole;
      for (int k = 0; k < 3; ++k)
        hole.push_back({c.x + s * std::cos(t + 2 * M_PI * k / 3), c.y + s * std::sin(t + 2 * M_PI * k / 3)});
      rings.push_back(hole);
    }
    level = level_below_grid(s, std::max(a, b));
    return json::array({zone("residential", rings), zone("commercial", {rect(a, 0, a + 200, b)}),
                        road("main", 10, {{-50, road_y}, {a + 250, road_y + rng.uniform(-5, 5)}})});
  }
  // A hole 100 m across, one corner s inside the outer ring's right edge (in doubles: the
  // gap as drawn).
  const double y = rng.uniform(100, b - 100), x = a - s;
  rings.push_back({{x - 100, y - 50}, {x, y}, {x - 100, y + 50}});
  level = level_below_grid(a - x, a);
  return json::array({zone("residential", rings), zone("industrial", {rect(a, 0, a + 200, b)})});
}

using Maker = json (*)(Random&, int, double& level);
struct Entry {
  Family family;
  Maker make;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list{
      {{"near-collinear", "a zone corner stepped over a 256x256 grid of 1 to 2^36 ulps around its neighbour's edge",
        "log10(grid / distance off the line)"},
       near_collinear},
      {{"translated", "a random city at 1e5, 1e6, 1e7 and 1e9 m", "log10 of the translation (m)"}, translated},
      {{"thin-angles", "highways crossing at 1e-3 to 1e-12 rad, or nearly parallel", "-log10 of the angle (rad)"},
       thin_angles},
      {{"off-edge", "corners 1e-1 to 1e-12 m off a shared edge or a highway", "log10(grid / offset)"}, off_edge},
      {{"shared-edges", "zones sharing edges, overlapping along them, touching at a point, drawn twice",
        "rings along one edge"},
       shared_edges},
      {{"slivers", "zones and spikes 1e-3 to 1e-9 m wide, rings touching themselves", "log10(grid / width)"},
       slivers},
      {{"many-highways", "2 to 13 roads through one point, meeting at a vertex or crossing within ulps of it",
        "roads through one point"},
       many_highways},
      {{"near-touching", "zones side by side 1e-1 to 1e-12 m apart, a road across the gap", "log10(grid / gap)"},
       near_touching},
      {{"tiny-holes", "holes 1e-3 to 1e-12 m across, or an ordinary hole that far inside its outer ring",
        "log10(grid / size or gap)"},
       tiny_holes},
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
