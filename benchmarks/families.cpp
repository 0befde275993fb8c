#include "benchmarks/families.h"

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

// 1. Kettner et al.'s classroom example in a city: a zone's corner p, stepped over a
// 256 x 256 grid around the point (100.5, 100.5) of the line y = x, on which a
// neighbouring zone's edge runs; the two zones overlap, touch or part by a sliver, as the
// orientation of (q, r, p) decides. The grid's step is 2^e ulps, e from 0 (Kettner's
// single ulps, 1e-14 m) up to 36 (1e-3 m), so the corner goes from an ordinary sketch's
// distances off the line down to ulps.
// Level: 8 less log2 of (1 + the ulps p lies off the line), 8 on it.
json near_collinear(Random& rng, int index, double& level) {
  const int i = static_cast<int>(rng.next() % 256), j = static_cast<int>(rng.next() % 256);
  const int e = 4 * (index % 10);
  // An ulp of 100.5 is 2^-46, so these sums are exact.
  const double step = std::ldexp(1.0, e - 46);
  level = 8 - std::log2(1.0 + std::abs(i - j) * std::ldexp(1.0, e));
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
// 1e-12 m, to either side. Level: -log10 of the offset.
json off_edge(Random& rng, int index, double& level) {
  const double d = sweep(1, 12, index / 2, 12) * (rng.next() % 2 ? 1 : -1);
  level = -std::log10(std::abs(d));
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
// touch themselves. Level: -log10 of the width.
json slivers(Random& rng, int index, double& level) {
  const double w = sweep(3, 9, index / 3, 7);
  level = -std::log10(w);
  const double a = rng.uniform(200, 400), b = rng.uniform(200, 400);
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

// 7. Many highways through one point; a dense tangle of random polylines. Level: how many
// lines pass through one point (2 in a tangle: they cross in pairs).
json many_highways(Random& rng, int index, double& level) {
  json features = json::array({zone("residential", {rect(0, 0, 500, 500)}), zone("commercial", {rect(500, 0, 800, 500)})});
  if (index % 2 == 0) {
    const P c{rng.uniform(100, 400), rng.uniform(100, 400)};
    const int n = 3 + index % 10;
    level = n;
    for (int k = 0; k < n; ++k) {
      const double t = rng.uniform(0, M_PI);
      features.push_back(road("main", 8, {{c.x - 700 * std::cos(t), c.y - 700 * std::sin(t)}, c,
                                          {c.x + 700 * std::cos(t), c.y + 700 * std::sin(t)}}));
    }
  } else {
    level = 2;
    for (int k = 0; k < 10; ++k) {
      Line line;
      for (int v = 0; v < 8; ++v) line.push_back({rng.uniform(0, 800), rng.uniform(0, 500)});
      features.push_back(road(k % 3 ? "local" : "main", k % 3 ? 6 : 10, line));
    }
  }
  return features;
}

// 8. Zones whose edges run side by side 1e-1 down to 1e-12 m apart, a road across the gap.
// Level: -log10 of the gap.
json near_touching(Random& rng, int index, double& level) {
  const double gap = sweep(1, 12, index, 12);
  level = -std::log10(gap);
  const double a = rng.uniform(200, 400), b = rng.uniform(200, 400), y = rng.uniform(0.2 * b, 0.8 * b);
  return json::array({zone("residential", {rect(0, 0, a, b)}), zone("commercial", {rect(a + gap, 0, 2 * a, b)}),
                      zone("industrial", {rect(0, b + gap, a, 2 * b)}),
                      road("main", 10, {{-50, y}, {2 * a + 50, y + rng.uniform(-2, 2)}})});
}

using Maker = json (*)(Random&, int, double& level);
struct Entry {
  Family family;
  Maker make;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list{
      {{"near-collinear", "a zone corner stepped over a 256x256 grid of 1 to 2^36 ulps around its neighbour's edge",
        "8 - log2(1 + ulps off the line)"},
       near_collinear},
      {{"translated", "a random city at 1e5, 1e6, 1e7 and 1e9 m", "log10 of the translation (m)"}, translated},
      {{"thin-angles", "highways crossing at 1e-3 to 1e-12 rad, or nearly parallel", "-log10 of the angle (rad)"},
       thin_angles},
      {{"off-edge", "corners 1e-1 to 1e-12 m off a shared edge or a highway", "-log10 of the offset (m)"}, off_edge},
      {{"shared-edges", "zones sharing edges, overlapping along them, touching at a point, drawn twice",
        "rings along one edge"},
       shared_edges},
      {{"slivers", "zones and spikes 1e-3 to 1e-9 m wide, rings touching themselves", "-log10 of the width (m)"},
       slivers},
      {{"many-highways", "up to 12 highways through one point, tangles of random polylines", "lines through one point"},
       many_highways},
      {{"near-touching", "zones side by side 1e-1 to 1e-12 m apart, a road across the gap", "-log10 of the gap (m)"},
       near_touching},
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
