#include "generate/placement/model_placement.h"

#include "generate/placement/building_settings.h"
#include "generate/placement/placer.h"

#include <algorithm>
#include <cmath>

#include "geom/grid.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::Vec2;

// Centre-to-centre spacing along a row, in model widths (docs/sketch.md: density).
std::pair<double, double> spacing(const std::string& density) {
  if (density == "dense") return {1.25, 1.5};
  if (density == "sparse") return {4, 5};
  return {2, 3};
}

}  // namespace

Choices choices_at(const std::vector<int>& models, const ModelLibrary& lib, const Channels* channels,
                   const geom::Cell& piece) {
  if (!channels || channels->empty()) return choices_at(models, lib, nullptr, geom::Vec2{});
  return choices_at(models, lib, channels, piece.centroid());
}

ModelInstance made(const Model& m, const Placement& p, geom::Ring ring) {
  ModelInstance placed;
  placed.kind = m.kind;
  placed.placed = p;
  placed.polygon.outer = std::move(ring);
  placed.height = m.height * p.scale;
  return placed;
}

namespace {

// A ring of the model's frame turned by the placement's angle, scaled, moved and rounded.
geom::Ring placed_ring(const geom::Ring& model_ring, const Placement& p) {
  const double c = std::cos(p.angle) * p.scale, s = std::sin(p.angle) * p.scale;
  geom::Ring ring;
  for (Vec2 v : model_ring) {
    Vec2 w = geom::snap(Vec2{p.position.x + c * v.x - s * v.y, p.position.y + s * v.x + c * v.y});
    if (ring.empty() || !(w == ring.back())) ring.push_back(w);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  return ring;
}

}  // namespace

geom::Ring placed_outline(const Model& m, const Placement& p) { return placed_ring(m.outline, p); }

std::vector<Slab> placed_slabs(const Model& m, const Placement& p, const geom::Ring& footprint) {
  std::vector<Slab> slabs = slabs_of(m);
  for (Slab& s : slabs) {
    s.bottom *= p.scale, s.top *= p.scale;
    for (geom::Ring& r : s.outline) r = placed_ring(r, p);
    if (std::any_of(s.outline.begin(), s.outline.end(), [](const geom::Ring& r) { return geom::ring_orientation(r) != 1; }))
      s.outline = {footprint};
  }
  return slabs;
}

namespace {

// What the placers of one lot piece share: the piece, its frontage, the library and the
// models placed so far.
struct Placing {
  Occupancy& occupancy;
  const ModelLibrary& lib;
  const Frontage& f;
  double along;  // the frontage's heading, radians
  std::vector<ModelInstance>& out;

  // Places the model there when its outline is free; whether it did.
  bool try_place(int model, const Placement& p) {
    geom::Ring ring = placed_outline(lib.models[model], p);
    if (!occupancy.take(ring)) return false;
    out.push_back(made(lib.models[model], p, std::move(ring)));
    return true;
  }
};

// One every `spacing` metres along the road frontage, in the middle of the setback strip.
void place_street_furniture(Placing& s, const Choices& choices, const BuildingSettings& params, Random& rng) {
  if (!s.f.on_road) return;
  for (double t = s.f.t0 + s.lib.models[choices.models[0]].spacing / 2; t < s.f.t1;) {
    const std::optional<int> drawn = pick(choices, rng);
    if (!drawn) return;
    const int m = *drawn;
    double scale = rng.uniform(s.lib.models[m].min_scale, s.lib.models[m].max_scale);
    int tint = static_cast<int>(rng.next() % kTints);
    s.try_place(m, {m, s.f.at(t, params.setback / 2), s.along, scale, tint});
    t += s.lib.models[m].spacing;
  }
}

// Trees at random places and headings, a try per 150 m² of the piece (1 to 24).
void place_trees(Placing& s, const Choices& choices, Random& rng) {
  const geom::Cell& piece = s.occupancy.piece();
  const geom::Box box = piece.bounds();
  const int attempts = static_cast<int>(std::clamp(piece.area() / 150, 1.0, 24.0));
  for (int i = 0; i < attempts; ++i) {
    const std::optional<int> drawn = pick(choices, rng);
    if (!drawn) return;
    const int m = *drawn;
    Placement p{m, {rng.uniform(box.min_x, box.max_x), rng.uniform(box.min_y, box.max_y)}, rng.uniform(0, 2 * M_PI),
                rng.uniform(s.lib.models[m].min_scale, s.lib.models[m].max_scale), static_cast<int>(rng.next() % kTints)};
    s.try_place(m, p);
  }
}

// A building drawn for the rows, before it has a place.
struct Candidate {
  int model;
  double scale, spacing, area;
  int tint;
};

// Enough candidates to fill the piece at the zone's density, largest first; and the depth
// of a row that holds the deepest.
std::vector<Candidate> draw_candidates(const Placing& s, const Choices& choices, const BuildingSettings& params,
                                       Random& rng, double& row_depth) {
  const auto [lo, hi] = spacing(params.density);
  double mean_area = 0;
  for (int c : choices.models) mean_area += s.lib.models[c].width * s.lib.models[c].depth;
  mean_area /= static_cast<double>(choices.models.size());
  const double area = s.occupancy.piece().area();
  const int count = static_cast<int>(std::clamp(std::ceil(area / (mean_area * (lo + hi) / 2)), 1.0, 48.0));
  std::vector<Candidate> candidates;
  row_depth = 0;
  for (int i = 0; i < count; ++i) {
    const std::optional<int> drawn = pick(choices, rng);
    if (!drawn) break;
    const int m = *drawn;
    double scale = rng.uniform(s.lib.models[m].min_scale, s.lib.models[m].max_scale);
    const Model& model = s.lib.models[m];
    candidates.push_back({m, scale, rng.uniform(lo, hi), model.width * model.depth * scale * scale,
                          static_cast<int>(rng.next() % kTints)});
    row_depth = std::max(row_depth, model.depth * scale);
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.area > b.area; });
  return candidates;
}

// Taken intervals along one row, gaps included.
using Row = std::vector<std::pair<double, double>>;

// The candidate at the first free place along row k, `offset` back from the street;
// whether it found one.
bool place_in_row(Placing& s, const Candidate& c, Row& row, double offset) {
  const Model& m = s.lib.models[c.model];
  const double w = m.width * c.scale, d = m.depth * c.scale, gap = (c.spacing - 1) * w;
  int tries = 0;
  for (double t = s.f.t0; t + w <= s.f.t1 && tries < 48;) {
    auto busy = std::find_if(row.begin(), row.end(), [&](const auto& iv) {
      return iv.first < t + w + gap / 2 && t - gap / 2 < iv.second;
    });
    if (busy != row.end()) {
      // Past it; by a centimetre when rounding leaves t where it was.
      const double next = busy->second + gap / 2;
      t = next > t ? next : t + 0.01;
      continue;
    }
    ++tries;
    if (s.try_place(c.model, {c.model, s.f.at(t + w / 2, offset + d / 2), s.along, c.scale, c.tint})) {
      row.push_back({t - gap / 2, t + w + gap / 2});
      return true;
    }
    t += std::max(w / 4, 0.5);
  }
  return false;
}

// Rows facing the road (docs/design.md, Algorithms): the candidates largest first, each in the first row with room.
void place_building_rows(Placing& s, const Choices& choices, const BuildingSettings& params, Random& rng) {
  double row_depth = 0;
  const std::vector<Candidate> candidates = draw_candidates(s, choices, params, rng, row_depth);
  const double row_pitch = row_depth + 2 * params.setback;
  std::vector<Row> rows;
  for (const Candidate& c : candidates) {
    const double d = s.lib.models[c.model].depth * c.scale;
    for (std::size_t k = 0;; ++k) {
      const double offset = params.setback + static_cast<double>(k) * row_pitch;
      if (offset + d > s.f.depth) break;
      if (rows.size() <= k) rows.resize(k + 1);
      if (place_in_row(s, c, rows[k], offset)) break;
    }
  }
}

}  // namespace

std::vector<ModelInstance> place_models(Occupancy& occupancy, const Choices& choices, ModelKind kind,
                                        const ModelLibrary& lib, const BuildingSettings& params, Random& rng) {
  std::vector<ModelInstance> out;
  if (choices.empty()) return out;
  const Frontage& f = occupancy.frontage();
  if (!(f.t1 > f.t0)) return out;
  Placing placing{occupancy, lib, f, std::atan2(f.u.y, f.u.x), out};
  if (kind == ModelKind::Street) place_street_furniture(placing, choices, params, rng);
  else if (kind == ModelKind::Tree) place_trees(placing, choices, rng);
  else place_building_rows(placing, choices, params, rng);
  return out;
}

namespace {

class ModelPlacer : public Placer {
 public:
  ModelPlacer(const ModelLibrary& library, std::vector<int> models, ModelKind kind, const Channels& channels)
      : library_(library), models_(std::move(models)), kind_(kind), channels_(channels) {}
  void place(const Lot&, const BuildingSettings& params, Occupancy& occupancy, Random& rng,
             Structures& out) const override {
    const Choices choices = choices_at(models_, library_, &channels_, occupancy.piece());
    for (ModelInstance& m : place_models(occupancy, choices, kind_, library_, params, rng))
      out.models.push_back(std::move(m));
  }

 private:
  const ModelLibrary& library_;
  std::vector<int> models_;
  ModelKind kind_;
  const Channels& channels_;
};

}  // namespace

namespace {

// The lot library: the lot's own model in the middle of the lot, its front to the
// street, at a random size within its range, smaller where the lot is (down to the
// smallest; the library made sure that fits a lot of the entry's size).
class OwnLotPlacer : public Placer {
 public:
  explicit OwnLotPlacer(const ModelLibrary& library) : library_(library) {}
  void place(const Lot& lot, const BuildingSettings&, Occupancy& occupancy, Random& rng, Structures& out) const override {
    if (!lot.model) return;
    const Model& m = library_.models[*lot.model];
    const Frontage& f = occupancy.frontage();
    if (!(f.t1 > f.t0)) return;
    const double room = std::min((f.t1 - f.t0 - 2 * kLotMargin) / m.width, (f.depth - 2 * kLotMargin) / m.depth);
    const double drawn = rng.uniform(m.min_scale, m.max_scale);
    const int tint = static_cast<int>(rng.next() % kTints);
    for (double scale : {std::max(std::min(drawn, room), m.min_scale), m.min_scale}) {
      const Placement p{*lot.model, f.at((f.t0 + f.t1) / 2, f.depth / 2), std::atan2(f.u.y, f.u.x), scale, tint};
      geom::Ring ring = placed_outline(m, p);
      if (!occupancy.take(ring)) continue;
      out.models.push_back(made(m, p, std::move(ring)));
      return;
    }
  }

 private:
  const ModelLibrary& library_;
};

}  // namespace

std::unique_ptr<Placer> make_own_lot_placer(const ModelLibrary& library) { return std::make_unique<OwnLotPlacer>(library); }

namespace {

// Rows facing the road, largest first: no settings of its own.
class RowPlacerChoice : public PlacerChoice {
 public:
  RowPlacerChoice() : PlacerChoice("rows") {}
  std::unique_ptr<Placer> make(const ModelLibrary& library, ZoneType zone, const Channels& channels) const override {
    return make_model_placer(library, zone, ModelKind::Building, channels);
  }
};

}  // namespace

std::shared_ptr<const PlacerChoice> read_row_placer(const PlacerReading&) { return std::make_shared<RowPlacerChoice>(); }

std::unique_ptr<Placer> make_model_placer(const ModelLibrary& library, ZoneType zone, ModelKind kind,
                                          const Channels& channels) {
  std::vector<int> models = library.choices(zone, kind);
  if (models.empty()) return nullptr;
  return std::make_unique<ModelPlacer>(library, std::move(models), kind, channels);
}

}  // namespace exacity
