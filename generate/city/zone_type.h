#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace exacity {

enum class ZoneType { Residential, Commercial, Industrial, Park, Water };
inline constexpr std::array<std::string_view, 5> kZoneTypeNames = {"residential", "commercial",
                                                                   "industrial", "park", "water"};

enum class RoadClass { Highway, Main, Local };
inline constexpr std::array<std::string_view, 3> kRoadClassNames = {"highway", "main", "local"};

// The zone types roads grow in.
inline bool grows_roads(ZoneType t) {
  return t == ZoneType::Residential || t == ZoneType::Commercial || t == ZoneType::Industrial;
}

inline std::string_view name(ZoneType t) { return kZoneTypeNames[static_cast<int>(t)]; }
inline std::string_view name(RoadClass c) { return kRoadClassNames[static_cast<int>(c)]; }

std::optional<ZoneType> parse_zone_type(std::string_view s);
std::optional<RoadClass> parse_road_class(std::string_view s);

// The valid name closest to `s` by edit distance, for "did you mean" hints.
std::string_view nearest_zone_name(std::string_view s);
std::string_view nearest_road_class_name(std::string_view s);

}  // namespace exacity
