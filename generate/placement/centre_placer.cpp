// A trial placer: the zone's first library building in the middle of each lot, at `centre_scale`.
#include "generate/placement/building_settings.h"
#include "generate/placement/model_placement.h"
#include "generate/placement/placer.h"

namespace exacity {
namespace {

class CentrePlacer : public Placer {
 public:
  CentrePlacer(const ModelLibrary& library, int model, double scale) : library_(library), model_(model), scale_(scale) {}
  void place(const Lot&, const BuildingSettings&, Occupancy& occupancy, Random&, Structures& out) const override {
    const Frontage& f = occupancy.frontage();
    if (!(f.t1 > f.t0)) return;
    const Placement p{model_, f.at((f.t0 + f.t1) / 2, f.depth / 2), std::atan2(f.u.y, f.u.x), scale_, 0};
    geom::Ring ring = placed_outline(library_.models[model_], p);
    if (occupancy.take(ring)) out.models.push_back(made(library_.models[model_], p, std::move(ring)));
  }

 private:
  const ModelLibrary& library_;
  int model_;
  double scale_;
};

class CentreChoice : public PlacerChoice {
 public:
  explicit CentreChoice(double scale) : PlacerChoice("centre"), scale_(scale) {}
  std::unique_ptr<Placer> make(const ModelLibrary& library, ZoneType zone, const Channels&) const override {
    const std::vector<int> models = library.choices(zone, ModelKind::Building);
    if (models.empty()) return nullptr;
    return std::make_unique<CentrePlacer>(library, models.front(), scale_);
  }

 private:
  double scale_;
};

}  // namespace

std::shared_ptr<const PlacerChoice> read_centre_placer(const PlacerReading& reading) {
  double scale = 1;
  reading.settings.number("centre_scale", scale, 0.1, 10);
  return std::make_shared<CentreChoice>(scale);
}

}  // namespace exacity
