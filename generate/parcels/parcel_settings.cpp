#include "generate/parcels/parcel_settings.h"

#include "generate/city/named_row.h"

namespace exacity {

// Each layout's reader, in its layout's file.
std::shared_ptr<const LotLayoutChoice> read_allocation(const LotLayoutReading& reading);
std::shared_ptr<const LotLayoutChoice> read_split(const LotLayoutReading& reading);
std::shared_ptr<const LotLayoutChoice> read_library_lots(const LotLayoutReading& reading);

const std::vector<LotLayoutType>& lot_layout_types() {
  static const std::vector<LotLayoutType> table{
      {"allocation", "lots along the street", {"lot_width", "lot_frontages", "lot_depth", "min_lot_edge"}, read_allocation},
      {"split", "recursive splitting", {"lot_area"}, read_split},
      {"library", "the model library's lots", {}, read_library_lots},
  };
  return table;
}

const LotLayoutType& lot_layout_type(std::string_view name) { return named_row(lot_layout_types(), name, "lot layout"); }

LotSettings default_lot_settings(ZoneType type) {
  static const nlohmann::json none = nlohmann::json::object();
  LotSettings l;
  l.layout = lot_layout_types().front().read({SettingsReader(none, "", ""), type, true});
  return l;
}

const std::set<std::string>& parcel_setting_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k{"min_block_area", "min_block_width", "lots", "min_lot_area"};
    for (const LotLayoutType& t : lot_layout_types()) k.insert(t.keys.begin(), t.keys.end());
    return k;
  }();
  return keys;
}

BlockSettings read_block_settings(const SettingsReader& s, BlockSettings b) {
  s.number("min_block_area", b.min_block_area, 0, 1e9);
  s.number("min_block_width", b.min_block_width, 0, 1e4);
  return b;
}

LotSettings read_lot_settings(const SettingsReader& s, ZoneType type, LotSettings l, const RoadLayoutChoice& road_layout) {
  s.number("min_lot_area", l.min_lot_area, 0, 1e8);
  const auto& table = lot_layout_types();
  const LotLayoutType& chosen = s.row("lots", table, lot_layout_type(road_layout.default_lots()));
  // As for road layouts: every layout's keys are checked where written; the chosen one's
  // reading is kept.
  for (const LotLayoutType& t : table) {
    auto layout = t.read({s, type, &t == &chosen});
    if (&t == &chosen) l.layout = std::move(layout);
  }
  return l;
}

}  // namespace exacity
