#include "generate/placement/model_placement.h"

#include "generate/placement/placer.h"

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

ModelInstance made(const Model& m, const Placement& p, geom::Ring ring) {
  ModelInstance placed;
  placed.kind = m.kind;
  placed.placed = p;
  placed.polygon.outer = std::move(ring);
  placed.height = m.height * p.scale;
  return placed;
}

}  // namespace

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

std::vector<ModelInstance> place_models(Occupancy& occupancy, const std::vector<int>& choices, ModelKind kind,
                                        const ModelLibrary& lib, const ZoneParams& params, Random& rng) {
  std::vector<ModelInstance> out;
  if (choices.empty()) return out;
  const geom::Cell& piece = occupancy.piece();
  const Frontage& f = occupancy.frontage();
  if (!(f.t1 > f.t0)) return out;
  const double along = std::atan2(f.u.y, f.u.x);
  auto at = [&](double t, double d) { return f.at(t, d); };
  auto try_place = [&](int model, Placement p) {
    geom::Ring ring = placed_outline(lib.models[model], p);
    if (!occupancy.take(ring)) return false;
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

namespace {

class ModelPlacer : public Placer {
 public:
  ModelPlacer(const ModelLibrary& library, std::vector<int> choices, ModelKind kind)
      : library_(library), choices_(std::move(choices)), kind_(kind) {}
  void place(const Lot&, const ZoneParams& params, Occupancy& occupancy, Random& rng, Structures& out) const override {
    for (ModelInstance& m : place_models(occupancy, choices_, kind_, library_, params, rng))
      out.models.push_back(std::move(m));
  }

 private:
  const ModelLibrary& library_;
  std::vector<int> choices_;
  ModelKind kind_;
};

}  // namespace

std::unique_ptr<Placer> make_model_placer(const ModelLibrary& library, ZoneType zone, ModelKind kind) {
  std::vector<int> choices = library.choices(zone, kind);
  if (choices.empty()) return nullptr;
  return std::make_unique<ModelPlacer>(library, std::move(choices), kind);
}

}  // namespace exacity
