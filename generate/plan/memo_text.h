// The items a city's build keeps by their input (generate/regenerate.h's RegionCache) as
// text that reads back to the same value, field for field: doubles as hex floats (C's %a),
// exact coordinates as geom::exact_text, strings with their length. A plan's tasks write
// the items they computed so, and its merge reads them into the cache of the build that
// joins them (generate/plan/plan.h), so reading must give back exactly what was computed.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "generate/city/memo.h"
#include "generate/layout/road_layout.h"
#include "generate/parcels/lot_layout.h"
#include "generate/placement/buildings.h"

namespace exacity {

// A value as text, and back; reading throws std::invalid_argument on text it did not write.
// Defined for RoadPlan, std::vector<PlannedLot> and Structures.
template <typename Value>
std::string value_text(const Value& value);
template <typename Value>
Value value_from_text(std::string_view text);

// Every item the memo holds, one a line: the key and the value, each with its length, so
// any byte may appear in either. Lines are sorted by key, so a task's file does not depend
// on the order its threads computed them.
template <typename Value>
std::string memo_text(const Memo<Value>& memo);
// Puts memo_text's items into `memo` (Memo::put). Throws std::invalid_argument on a text
// memo_text did not write.
template <typename Value>
void read_memo_text(std::string_view text, Memo<Value>& memo);

}  // namespace exacity
