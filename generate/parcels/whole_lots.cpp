// A trial lot layout: every block is one lot.
#include "generate/parcels/lot_layout.h"

namespace exacity {
namespace {

class WholeLots : public LotLayout {
 public:
  std::vector<PlannedLot> plan(const Block& block, int index, Random&) const override {
    return {{index, block.zone, {}, block.cell}};
  }
};

class WholeLotsChoice : public LotLayoutChoice {
 public:
  WholeLotsChoice() : LotLayoutChoice("whole") {}
  std::unique_ptr<LotLayout> make(ZoneType, const ModelLibrary*, const Channels&) const override {
    return std::make_unique<WholeLots>();
  }
};

}  // namespace

std::shared_ptr<const LotLayoutChoice> read_whole_lots(const LotLayoutReading&) {
  return std::make_shared<WholeLotsChoice>();
}

}  // namespace exacity
