#include "generate/placement/street_nodes.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace exacity {

int StreetJunction::major_arms() const {
  return static_cast<int>(
      std::count_if(arms.begin(), arms.end(), [](const RoadArm& a) { return is_major(a.road_class); }));
}

double StreetJunction::reach() const {
  double widest = 0;
  for (const RoadArm& a : arms) widest = std::max(widest, a.half_width);
  return widest;
}

std::vector<StreetJunction> street_junctions(const std::vector<RoadLine>& roads) {
  std::unordered_map<geom::Vec2, int, geom::Vec2Hash> node_of;
  std::vector<StreetJunction> nodes;
  auto add_arm = [&](geom::Vec2 at, geom::Vec2 next, int road) {
    if (at == next) return;
    auto [it, added] = node_of.emplace(at, static_cast<int>(nodes.size()));
    if (added) nodes.push_back({at, {}});
    const RoadLine& r = roads[road];
    nodes[it->second].arms.push_back({road, geom::unit_along(at, next), r.road_class, r.width / 2});
  };
  for (std::size_t r = 0; r < roads.size(); ++r) {
    const geom::Polyline& line = roads[r].line;
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (i > 0) add_arm(line[i], line[i - 1], static_cast<int>(r));
      if (i + 1 < line.size()) add_arm(line[i], line[i + 1], static_cast<int>(r));
    }
  }
  std::vector<StreetJunction> junctions;
  for (StreetJunction& n : nodes) {
    if (n.arms.size() < 3) continue;
    // Counter-clockwise by angle (atan2, from just past west); ties keep their order.
    std::stable_sort(n.arms.begin(), n.arms.end(), [](const RoadArm& a, const RoadArm& b) {
      return std::atan2(a.toward.y, a.toward.x) < std::atan2(b.toward.y, b.toward.x);
    });
    junctions.push_back(std::move(n));
  }
  return junctions;
}

}  // namespace exacity
