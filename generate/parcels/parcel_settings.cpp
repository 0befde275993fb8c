#include "generate/parcels/parcel_settings.h"

#include "generate/city/named_row.h"

namespace exacity {

// Each layout's factory, in its layout's file.
std::unique_ptr<LotLayout> make_allocation(const LotSettings&, ZoneType, const ModelLibrary*, const Channels&);
std::unique_ptr<LotLayout> make_split(const LotSettings&, ZoneType, const ModelLibrary*, const Channels&);
std::unique_ptr<LotLayout> make_library_lots(const LotSettings&, ZoneType, const ModelLibrary*, const Channels&);

const std::vector<LotLayoutType>& lot_layout_types() {
  static const std::vector<LotLayoutType> table{
      {"allocation", "lots along the street", make_allocation},
      {"split", "recursive splitting", make_split},
      {"library", "the model library's lots", make_library_lots, true},
  };
  return table;
}

const LotLayoutType& lot_layout_type(std::string_view name) { return named_row(lot_layout_types(), name, "lot layout"); }

LotSettings default_lot_settings(ZoneType type) {
  LotSettings l;
  l.layout = &lot_layout_types().front();
  if (type == ZoneType::Commercial) l.lot_area = 1500, l.lot_width = {20, 45}, l.lot_depth = 35;
  if (type == ZoneType::Industrial) l.lot_area = 3000, l.lot_width = {40, 90}, l.lot_depth = 60;
  return l;
}

const std::set<std::string>& parcel_setting_keys() {
  static const std::set<std::string> keys{"min_block_area", "min_block_width", "lots",        "lot_width",
                                          "lot_depth",      "lot_area",        "min_lot_edge", "min_lot_area"};
  return keys;
}

BlockSettings read_block_settings(const SettingsReader& s, BlockSettings b) {
  s.number("min_block_area", b.min_block_area, 0, 1e9);
  s.number("min_block_width", b.min_block_width, 0, 1e4);
  return b;
}

LotSettings read_lot_settings(const SettingsReader& s, LotSettings l, const RoadLayoutChoice& road_layout) {
  s.number("lot_area", l.lot_area, 10, 1e8);
  s.number("min_lot_edge", l.min_lot_edge, 0, 1e4);
  s.number("min_lot_area", l.min_lot_area, 0, 1e8);
  s.number("lot_depth", l.lot_depth, 2, 1e4);
  s.range("lot_width", l.lot_width, 2, 1e4, "lot frontage in metres");
  l.layout = &s.row("lots", lot_layout_types(), lot_layout_type(road_layout.default_lots()));
  return l;
}

}  // namespace exacity
