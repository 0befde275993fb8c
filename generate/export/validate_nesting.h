// Nesting (a 3D occupancy grid) in `exacity validate` (docs/design.md, Placement: nesting): two models
// whose footprints overlap are valid only where the slabs each writes (heights from its
// floor, the outlines of what it holds between them) prove one lies wholly below the
// other wherever they share the plan. Decided exactly on the written doubles.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace exacity {

// Why the buildings `a` and `b` (named so in the message), whose footprints overlap, may not
// overlap; nothing when their slabs prove them apart in 3D: every pair of slabs whose
// closed height ranges meet has outlines apart (not touching). Each must write "floor" and
// "slabs": [{"bottom", "top", "outline": [closed counter-clockwise rings]}], bottom to top,
// each slab's bottom the one below's top, the last's top its "height".
std::optional<std::string> nested_overlap_problem(const nlohmann::ordered_json& a, const std::string& a_name,
                                                  const nlohmann::ordered_json& b, const std::string& b_name);

}  // namespace exacity
