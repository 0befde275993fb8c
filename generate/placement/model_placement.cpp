#include "generate/placement/model_placement.h"

#include <algorithm>
#include <cmath>

#include "geom/grid.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::Vec2;

int pick(const std::vector<int>& choices, const ModelLibrary& lib, Random& rng) {
  double total = 0;
  for (int c : choices) total += lib.models[c].weight;
  double r = rng.uniform() * total;
  for (int c : choices)
    if ((r -= lib.models[c].weight) < 0) return c;
  return choices.back();
}

// Centre-to-centre spacing along a row, in model widths (seed 002).
std::pair<double, double> spacing(const std::string& density) {
  if (density == "dense") return {1.25, 1.5};
  if (density == "sparse") return {4, 5};
  return {2, 3};
}

Building made(const Model& m, const Placement& p, geom::Ring ring) {
  Building b;
  b.placed = p;
  b.polygon.outer = std::move(ring);
  b.height = b.eaves = m.height * p.scale;
  b.roof = "model";
  return b;
}

}  // namespace

Frontage principal_frontage(const geom::Cell& piece, int road_kind) {
  auto edges = piece.edges_of_kind(road_kind);
  std::vector<Vec2> corners = piece.corners();
  Frontage f;
  f.on_road = !edges.empty();
  if (edges.empty())
    for (std::size_t i = 0; i < corners.size(); ++i) edges.push_back({corners[i], corners[(i + 1) % corners.size()]});
  double longest = 0;
  for (auto [a, b] : edges) {
    double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len > longest) longest = len, f.a = a, f.u = {(b.x - a.x) / len, (b.y - a.y) / len};
  }
  if (longest == 0) return f;
  f.n = {-f.u.y, f.u.x};  // the piece lies on each boundary edge's left
  f.t0 = INFINITY, f.t1 = -INFINITY;
  for (Vec2 c : corners) {
    double t = (c.x - f.a.x) * f.u.x + (c.y - f.a.y) * f.u.y, d = (c.x - f.a.x) * f.n.x + (c.y - f.a.y) * f.n.y;
    f.t0 = std::min(f.t0, t), f.t1 = std::max(f.t1, t), f.depth = std::max(f.depth, d);
  }
  return f;
}

bool fits(const geom::Cell& piece, const geom::Ring& ring, const std::vector<geom::Ring>& taken) {
  if (geom::ring_orientation(ring) != 1 || !piece.holds(ring)) return false;
  for (const geom::Ring& t : taken)
    if (geom::rings_meet(ring, t)) return false;
  return true;
}

geom::Ring placed_outline(const Model& m, const Placement& p) {
  const double c = std::cos(p.angle) * p.scale, s = std::sin(p.angle) * p.scale;
  geom::Ring ring;
  for (Vec2 v : m.outline) {
    Vec2 w = geom::snap(Vec2{p.position.x + c * v.x - s * v.y, p.position.y + s * v.x + c * v.y});
    if (ring.empty() || !(w == ring.back())) ring.push_back(w);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  return ring;
}

std::vector<Building> place_models(const geom::Cell& piece, int road_kind, std::vector<geom::Ring>& taken,
                                   const std::vector<int>& choices, ModelKind kind, const ModelLibrary& lib,
                                   const ZoneParams& params, Random& rng) {
  std::vector<Building> out;
  if (choices.empty()) return out;
  const Frontage f = principal_frontage(piece, road_kind);
  if (!(f.t1 > f.t0)) return out;
  const double along = std::atan2(f.u.y, f.u.x);
  auto at = [&](double t, double d) { return f.at(t, d); };
  auto try_place = [&](int model, Placement p) {
    geom::Ring ring = placed_outline(lib.models[model], p);
    if (!fits(piece, ring, taken)) return false;
    taken.push_back(ring);
    out.push_back(made(lib.models[model], p, std::move(ring)));
    return true;
  };

  if (kind == ModelKind::Street) {
    // One every `spacing` metres along the road frontage, in the middle of the setback strip.
    if (!f.on_road) return out;
    for (double t = f.t0 + lib.models[choices[0]].spacing / 2; t < f.t1;) {
      int m = pick(choices, lib, rng);
      double scale = rng.uniform(lib.models[m].min_scale, lib.models[m].max_scale);
      int tint = static_cast<int>(rng.next() % kTints);
      try_place(m, {m, at(t, params.setback / 2), along, scale, tint});
      t += lib.models[m].spacing;
    }
    return out;
  }
  if (kind == ModelKind::Tree) {
    const geom::Box box = piece.bounds();
    const int attempts = static_cast<int>(std::clamp(piece.area() / 150, 1.0, 24.0));
    for (int i = 0; i < attempts; ++i) {
      int m = pick(choices, lib, rng);
      Placement p{m, {rng.uniform(box.min_x, box.max_x), rng.uniform(box.min_y, box.max_y)}, rng.uniform(0, 2 * M_PI),
                  rng.uniform(lib.models[m].min_scale, lib.models[m].max_scale), static_cast<int>(rng.next() % kTints)};
      try_place(m, p);
    }
    return out;
  }

  // Buildings: draw enough candidates to fill the piece, then place the largest first,
  // each at the first free place along the first row with room.
  struct Candidate {
    int model;
    double scale, spacing, area;
    int tint;
  };
  const auto [lo, hi] = spacing(params.density);
  double mean_area = 0;
  for (int c : choices) mean_area += lib.models[c].width * lib.models[c].depth;
  mean_area /= static_cast<double>(choices.size());
  const int count = static_cast<int>(std::clamp(std::ceil(piece.area() / (mean_area * (lo + hi) / 2)), 1.0, 48.0));
  std::vector<Candidate> candidates;
  double row_depth = 0;
  for (int i = 0; i < count; ++i) {
    int m = pick(choices, lib, rng);
    double scale = rng.uniform(lib.models[m].min_scale, lib.models[m].max_scale);
    const Model& model = lib.models[m];
    candidates.push_back({m, scale, rng.uniform(lo, hi), model.width * model.depth * scale * scale,
                          static_cast<int>(rng.next() % kTints)});
    row_depth = std::max(row_depth, model.depth * scale);
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.area > b.area; });
  const double row_pitch = row_depth + 2 * params.setback;
  std::vector<std::vector<std::pair<double, double>>> rows;  // taken intervals along each row, gaps included
  for (const Candidate& c : candidates) {
    const Model& m = lib.models[c.model];
    const double w = m.width * c.scale, d = m.depth * c.scale, gap = (c.spacing - 1) * w;
    bool placed = false;
    for (std::size_t k = 0; !placed; ++k) {
      const double offset = params.setback + static_cast<double>(k) * row_pitch;
      if (offset + d > f.depth) break;
      if (rows.size() <= k) rows.resize(k + 1);
      int tries = 0;
      for (double t = f.t0; t + w <= f.t1 && tries < 48;) {
        auto busy = std::find_if(rows[k].begin(), rows[k].end(), [&](const auto& iv) {
          return iv.first < t + w + gap / 2 && t - gap / 2 < iv.second;
        });
        if (busy != rows[k].end()) {
          // Past it; by a centimetre when rounding leaves t where it was.
          const double next = busy->second + gap / 2;
          t = next > t ? next : t + 0.01;
          continue;
        }
        ++tries;
        if (try_place(c.model, {c.model, at(t + w / 2, offset + d / 2), along, c.scale, c.tint})) {
          rows[k].push_back({t - gap / 2, t + w + gap / 2});
          placed = true;
          break;
        }
        t += std::max(w / 4, 0.5);
      }
    }
  }
  return out;
}

}  // namespace exacity
