#include "generate/city/zone_type.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace exacity {
namespace {

// Ignoring case: "WATER" is nearest to "water".
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

template <typename E, std::size_t N>
std::optional<E> parse(std::string_view s, const std::array<std::string_view, N>& names) {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == s) return static_cast<E>(i);
  return std::nullopt;
}

}  // namespace

template <std::size_t N>
std::string_view nearest_name(std::string_view s, const std::array<std::string_view, N>& candidates) {
  return *std::min_element(candidates.begin(), candidates.end(), [&](auto a, auto b) {
    return edit_distance(s, a) < edit_distance(s, b);
  });
}

std::optional<ZoneType> parse_zone_type(std::string_view s) { return parse<ZoneType>(s, kZoneTypeNames); }
std::optional<RoadClass> parse_road_class(std::string_view s) { return parse<RoadClass>(s, kRoadClassNames); }
std::string_view nearest_zone_name(std::string_view s) { return nearest_name(s, kZoneTypeNames); }
std::string_view nearest_road_class_name(std::string_view s) { return nearest_name(s, kRoadClassNames); }

}  // namespace exacity
