#include "generate/export/validate_nesting.h"

#include <vector>

#include "geom/plain.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using nlohmann::ordered_json;

struct WrittenSlab {
  double bottom = 0, top = 0;
  std::vector<geom::Ring> outline;
};

struct Stack {
  double floor = 0;
  std::vector<WrittenSlab> slabs;
};

bool is_number(const ordered_json& j, const char* key) { return j.contains(key) && j[key].is_number(); }

// The building's slabs as written, or why they cannot be read.
std::optional<Stack> read_stack(const ordered_json& props, std::string& why) {
  if (!props.contains("slabs") || !is_number(props, "floor"))
    return why = "carries no \"slabs\" and \"floor\"", std::nullopt;
  const ordered_json& slabs = props["slabs"];
  if (!slabs.is_array() || slabs.empty()) return why = "has no slabs", std::nullopt;
  Stack stack{props["floor"].get<double>(), {}};
  for (const ordered_json& s : slabs) {
    if (!s.is_object() || !is_number(s, "bottom") || !is_number(s, "top") || !s.contains("outline") ||
        !s["outline"].is_array())
      return why = "has a slab without \"bottom\", \"top\" and \"outline\"", std::nullopt;
    WrittenSlab w{s["bottom"].get<double>(), s["top"].get<double>(), {}};
    if (!(w.bottom < w.top)) return why = "has a slab whose top is not above its bottom", std::nullopt;
    if (!stack.slabs.empty() && w.bottom != stack.slabs.back().top)
      return why = "has slabs that leave a gap or overlap in height", std::nullopt;
    for (const ordered_json& ring : s["outline"]) {
      geom::Ring r;
      if (!ring.is_array() || ring.size() < 4 || ring.front() != ring.back())
        return why = "has a slab outline ring that is not closed", std::nullopt;
      for (std::size_t k = 0; k + 1 < ring.size(); ++k) {
        if (!ring[k].is_array() || ring[k].size() < 2 || !ring[k][0].is_number() || !ring[k][1].is_number())
          return why = "has a slab outline position that is not [x, y]", std::nullopt;
        r.push_back({ring[k][0].get<double>(), ring[k][1].get<double>()});
      }
      if (geom::ring_orientation(r) != 1)
        return why = "has a slab outline ring not simple and counter-clockwise", std::nullopt;
      w.outline.push_back(std::move(r));
    }
    if (w.outline.empty()) return why = "has a slab with no outline", std::nullopt;
    stack.slabs.push_back(std::move(w));
  }
  // Its slabs span it from the ground up: the lowest from at most its floor, the highest to
  // its height (so a model made taller without its slabs is refused).
  if (stack.slabs.front().bottom > 0) return why = "has slabs that do not reach down to its floor", std::nullopt;
  if (!is_number(props, "height") || stack.slabs.back().top != props["height"].get<double>())
    return why = "has slabs that do not reach its height", std::nullopt;
  return stack;
}

}  // namespace

std::optional<std::string> nested_overlap_problem(const ordered_json& a, const std::string& a_name,
                                                  const ordered_json& b, const std::string& b_name) {
  std::string why;
  const std::optional<Stack> sa = read_stack(a, why);
  if (!sa) return a_name + " and " + b_name + " overlap, and " + a_name + " " + why;
  const std::optional<Stack> sb = read_stack(b, why);
  if (!sb) return a_name + " and " + b_name + " overlap, and " + b_name + " " + why;
  for (std::size_t i = 0; i < sa->slabs.size(); ++i)
    for (std::size_t j = 0; j < sb->slabs.size(); ++j) {
      const WrittenSlab &s = sa->slabs[i], &t = sb->slabs[j];
      // Closed ranges, as footprints that touch are not apart.
      if (geom::compare_sums(sa->floor, s.top, sb->floor, t.bottom) < 0 ||
          geom::compare_sums(sb->floor, t.top, sa->floor, s.bottom) < 0)
        continue;
      for (const geom::Ring& p : s.outline)
        for (const geom::Ring& q : t.outline)
          if (geom::rings_meet(p, q))
            return a_name + " and " + b_name + " overlap in 3D: slab " + std::to_string(i) + " of the one and slab " +
                   std::to_string(j) + " of the other meet in height and in plan";
    }
  return std::nullopt;
}

}  // namespace exacity
