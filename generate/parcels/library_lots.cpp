// The lot library (docs/design.md, Lots): a block's street edges divided into the lots the
// model library's entries ask for ("lot": [width, depth]), corner lots first, each entry
// drawn by weight and channels where its lot fronts the street, until no entry's lot fits;
// what is left inside the block stays open space. Each lot remembers its model, which the
// placement stage stands in it, its front to the street (docs/design.md, Lots).
#include "generate/parcels/lot_layout.h"

#include <algorithm>
#include <cmath>

#include "geom/grid.h"
#include "geom/measure.h"

namespace exacity {
namespace {

using geom::Vec2;

// Lots reach this far past the block's street edge, so the map cuts them exactly there.
constexpr double kFrontOverhang = 0.5;  // m
// Lots stand this far inside the block's other edges and each other, as a choice in
// doubles; the map decides the lots exactly.
constexpr double kClearance = 0.05;  // m
// How far along an edge the next try moves when a lot does not fit.
constexpr double kStep = 1;  // m

// Whether two convex rings overlap (separating axes; touching counts as apart).
bool convex_overlap(const geom::Ring& a, const geom::Ring& b) {
  for (const geom::Ring* r : {&a, &b})
    for (std::size_t i = 0; i < r->size(); ++i) {
      const Vec2 e = (*r)[(i + 1) % r->size()] - (*r)[i], axis{-e.y, e.x};
      double a0 = INFINITY, a1 = -INFINITY, b0 = INFINITY, b1 = -INFINITY;
      for (Vec2 p : a) a0 = std::min(a0, geom::dot(p, axis)), a1 = std::max(a1, geom::dot(p, axis));
      for (Vec2 p : b) b0 = std::min(b0, geom::dot(p, axis)), b1 = std::max(b1, geom::dot(p, axis));
      if (a1 <= b0 || b1 <= a0) return false;
    }
  return true;
}

// One street edge of the block: from a to b, the block on its left.
struct StreetEdge {
  Vec2 a, u, n;
  double length;
  Vec2 at(double t, double d) const { return {a.x + u.x * t + n.x * d, a.y + u.y * t + n.y * d}; }
};

// A lot's front may stray this far from the block's edge: the front overhang covers it.
constexpr double kStraightness = 0.4;  // m

// The ring's street edges as straight runs: consecutive road edges (the map splits a street
// side wherever something meets it) joined while every corner between stays within
// kStraightness of the run's chord and the run turns under 90 degrees.
void street_edges(const geom::KindedRing& r, std::vector<StreetEdge>& out) {
  const std::size_t n = r.points.size();
  auto road = [&](std::size_t e) { return BlockEdge::is_road(r.kinds[e % n]); };
  // Start each walk after a non-road edge, so that a run is not cut where the ring closes.
  std::size_t start = 0;
  while (start < n && road(start)) ++start;
  if (start == n) start = 0;  // all road: a block ringed by streets; runs start anywhere
  for (std::size_t k = 0; k < n;) {
    const std::size_t e = (start + k) % n;
    if (!road(e)) {
      ++k;
      continue;
    }
    const Vec2 a = r.points[e];
    std::size_t end = k + 1;  // the run is edges [k, end)
    while (end < n && road(start + end)) {
      const Vec2 b = r.points[(start + end + 1) % n];
      bool straight = geom::dot(r.points[(start + end) % n] - a, b - a) > 0;
      for (std::size_t j = k + 1; straight && j <= end; ++j)
        straight = geom::distance_to_segment(r.points[(start + j) % n], a, b) <= kStraightness;
      if (!straight) break;
      ++end;
    }
    const Vec2 b = r.points[(start + end) % n];
    if (!(a == b)) {
      const Vec2 u = geom::unit_along(a, b);
      out.push_back({a, u, {-u.y, u.x}, geom::distance(a, b)});
    }
    k = end;
  }
}

class LibraryLots : public LotLayout {
 public:
  LibraryLots(const ModelLibrary& library, std::vector<int> models, const Channels& channels)
      : library_(library), models_(std::move(models)), channels_(channels) {}

  std::vector<PlannedLot> plan(const Block& block, int index, Random& rng) const override {
    Planning p{block, index, rng, block.cell.kinded_rings(), {}, {}, {}};
    for (const geom::KindedRing& r : p.rings) street_edges(r, p.edges);
    // Corner lots first: one at each end of every street edge; then each edge from its start.
    for (const StreetEdge& e : p.edges) lay(p, e, 0, false), lay(p, e, e.length, true);
    for (const StreetEdge& e : p.edges)
      for (double t = 0; t < e.length;) {
        const double width = lay(p, e, t, false);
        t += width > 0 ? width : kStep;
      }
    return std::move(p.lots);
  }

 private:
  struct Planning {
    const Block& block;
    int index;
    Random& rng;
    std::vector<geom::KindedRing> rings;
    std::vector<StreetEdge> edges;
    std::vector<geom::Ring> taken;  // the lots laid so far, less the clearance
    std::vector<PlannedLot> lots;
  };

  // Whether the convex ring lies inside the block, away from its edges, and apart from the
  // lots laid.
  bool free(const Planning& p, const geom::Ring& ring) const {
    for (Vec2 corner : ring) {
      bool inside = false;
      for (const geom::KindedRing& r : p.rings) inside ^= geom::odd_crossings(r.points, corner);
      if (!inside) return false;
    }
    for (const geom::KindedRing& r : p.rings)
      for (std::size_t e = 0; e < r.points.size(); ++e)
        if (convex_overlap(ring, {r.points[e], r.points[(e + 1) % r.points.size()]})) return false;
    return std::none_of(p.taken.begin(), p.taken.end(), [&](const geom::Ring& t) { return convex_overlap(ring, t); });
  }

  // Lays a lot on edge e with its front starting at t (ending at t, when `backwards`), of
  // an entry drawn by weight and channels there among those whose lot fits the edge, else
  // of the others that fit, heaviest first. Its width, or 0 when none fits.
  double lay(Planning& p, const StreetEdge& e, double t, bool backwards) const {
    const double room = backwards ? t : e.length - t;
    std::vector<int> fitting;
    for (int m : models_)
      if (library_.models[m].lot_width <= room) fitting.push_back(m);
    if (fitting.empty()) return 0;
    const Vec2 front = e.at(backwards ? t - library_.models[fitting[0]].lot_width / 2 : t, 0);
    Choices choices = choices_at(fitting, library_, &channels_, front);
    const std::optional<int> drawn = pick(choices, p.rng);
    if (!drawn) return 0;
    // The drawn entry first, then the rest by weight.
    std::vector<std::size_t> order(choices.models.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
      const bool di = choices.models[i] == *drawn, dj = choices.models[j] == *drawn;
      return di != dj ? di : choices.weights[i] > choices.weights[j];
    });
    for (std::size_t i : order) {
      if (!(choices.weights[i] > 0)) break;
      const Model& m = library_.models[choices.models[i]];
      const double t0 = backwards ? t - m.lot_width : t, t1 = t0 + m.lot_width;
      const geom::Ring inner{e.at(t0 + kClearance, kClearance), e.at(t1 - kClearance, kClearance),
                             e.at(t1 - kClearance, m.lot_depth - kClearance), e.at(t0 + kClearance, m.lot_depth - kClearance)};
      if (!free(p, inner)) continue;
      PlannedLot lot{p.index, p.block.zone, {}, {}, choices.models[i]};
      for (Vec2 v : {e.at(t0, -kFrontOverhang), e.at(t1, -kFrontOverhang), e.at(t1, m.lot_depth), e.at(t0, m.lot_depth)})
        lot.ring.push_back(geom::snap(v));
      p.taken.push_back(inner);
      p.lots.push_back(std::move(lot));
      return m.lot_width;
    }
    return 0;
  }

  const ModelLibrary& library_;
  std::vector<int> models_;
  const Channels& channels_;
};

}  // namespace

std::unique_ptr<LotLayout> make_library_lots(const ModelLibrary& library, ZoneType zone, const Channels& channels) {
  std::vector<int> models = library.lot_choices(zone);
  if (models.empty()) return nullptr;
  return std::make_unique<LibraryLots>(library, std::move(models), channels);
}

namespace {

// Its lots come with their models, which the placement stage stands on them (make_own_lot_placer).
class LibraryLotsChoice : public LotLayoutChoice {
 public:
  LibraryLotsChoice() : LotLayoutChoice("library") {}
  std::unique_ptr<LotLayout> make(ZoneType zone, const ModelLibrary* library, const Channels& channels) const override {
    return make_library_lots(*library, zone, channels);
  }
  bool models_own_lots() const override { return true; }
};

}  // namespace

std::shared_ptr<const LotLayoutChoice> read_library_lots(const LotLayoutReading&) {
  return std::make_shared<LibraryLotsChoice>();
}

}  // namespace exacity
