#include "generate/layout/settle.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "generate/layout/street_graph.h"
#include "geom/measure.h"

namespace exacity {
namespace {

// Joining ends can lay a short road along another's segment: each segment is kept in the
// first road that has it, the roads cut where they repeat one.
std::vector<RoadFeature> without_repeated_segments(const std::vector<RoadFeature>& roads) {
  std::set<geom::SegmentKey> seen;
  std::vector<RoadFeature> out;
  for (const RoadFeature& r : roads) {
    const geom::Polyline& line = r.lines[0];
    geom::Polyline piece;
    auto flush = [&] {
      if (piece.size() >= 2) out.push_back({static_cast<int>(out.size()), r.road_class, r.width, {piece}});
      piece.clear();
    };
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      if (!seen.insert(geom::segment_key(line[k], line[k + 1])).second) {
        flush();
        continue;
      }
      if (piece.empty()) piece.push_back(line[k]);
      piece.push_back(line[k + 1]);
    }
    flush();
  }
  return out;
}

// A road that runs wholly inside the surface of roads before it (a grammar can lay thin
// road pieces side by side) adds nothing but overlapping centre lines: it is left out.
std::vector<RoadFeature> without_roads_inside_others(const std::vector<RoadFeature>& roads) {
  std::vector<RoadFeature> kept;
  std::vector<geom::Box> boxes;
  for (const RoadFeature& r : roads) {
    const geom::Polyline& line = r.lines[0];
    std::vector<geom::Vec2> samples = line;
    for (std::size_t k = 0; k + 1 < line.size(); ++k)
      samples.push_back({(line[k].x + line[k + 1].x) / 2, (line[k].y + line[k + 1].y) / 2});
    auto covered = [&](geom::Vec2 p) {
      for (std::size_t j = 0; j < kept.size(); ++j) {
        const double reach = std::max(r.width, kept[j].width) / 2;
        const geom::Box& b = boxes[j];
        if (p.x < b.min_x - reach || p.x > b.max_x + reach || p.y < b.min_y - reach || p.y > b.max_y + reach) continue;
        const geom::Polyline& l = kept[j].lines[0];
        for (std::size_t k = 0; k + 1 < l.size(); ++k)
          if (geom::distance_to_segment(p, l[k], l[k + 1]) < reach) return true;
      }
      return false;
    };
    if (!kept.empty() && std::all_of(samples.begin(), samples.end(), covered)) continue;
    geom::Box box = geom::Box::none();
    for (geom::Vec2 p : line) box.add(p);
    kept.push_back(r), boxes.push_back(box);
  }
  return kept;
}

}  // namespace

std::vector<SettledRoad> settle(const RoadPlan& plan, const geom::Cell& cell, const std::vector<geom::Path>& sketch_roads,
                                double sketch_width) {
  std::vector<RoadFeature> roads;
  double widest = 0;
  for (const PlannedRoad& r : plan.roads) {
    roads.push_back({static_cast<int>(roads.size()), r.road_class, r.width, {r.line}});
    widest = std::max(widest, r.width);
  }
  join_near_ends(roads, plan.join);
  roads = without_roads_inside_others(without_repeated_segments(roads));
  const double reach = std::max(3 * widest, 0.1 * std::sqrt(cell.area()));
  std::vector<geom::Path> edges;
  for (const geom::KindedRing& r : cell.kinded_rings()) {
    geom::Polyline closed = r.points;
    closed.push_back(r.points.front());
    edges.push_back(geom::Path::from(closed));
  }
  std::vector<char> live(roads.size(), 1);
  for (std::size_t i = 0; i < roads.size(); ++i) {
    const geom::Polyline& l = roads[i].lines[0];
    live[i] = l.size() >= 2 && !(l.front() == l.back());
  }
  std::vector<SettledRoad> settled;
  std::vector<std::pair<int, int>> meetings;  // (road, road) met by running on
  std::vector<int> index;                     // settled road -> road
  for (bool dropped = true; dropped;) {
    dropped = false;
    std::map<std::pair<double, double>, int> uses;
    std::vector<int> others;
    std::vector<geom::Path> paths;  // of the live roads, in `others` order
    for (std::size_t i = 0; i < roads.size(); ++i)
      if (live[i]) {
        others.push_back(static_cast<int>(i));
        paths.push_back(geom::Path::from(roads[i].lines[0]));
        for (geom::Vec2 p : roads[i].lines[0]) ++uses[{p.x, p.y}];
      }
    settled.clear(), meetings.clear(), index.clear();
    for (std::size_t i = 0; i < roads.size() && !dropped; ++i) {
      if (!live[i]) continue;
      const geom::Polyline& line = roads[i].lines[0];
      std::vector<geom::Path> ahead;
      std::vector<int> ahead_road;
      geom::Path path;
      for (std::size_t k = 0; k < others.size(); ++k)
        if (others[k] != static_cast<int>(i)) ahead.push_back(paths[k]), ahead_road.push_back(others[k]);
        else path = paths[k];
      bool to_sketch = false;
      for (bool back : {true, false}) {
        const geom::Vec2 end = back ? line.back() : line.front();
        if (!back) path = path.reversed();
        if (uses[{end.x, end.y}] > 1) continue;
        const std::size_t n = path.size();
        // Straight on to another road; to a sketch road or the edge, turning if need be;
        // else turning to the nearest other road.
        std::optional<geom::Path> on;
        bool to_road = false;
        for (int step = 0; step < 4 && !on; ++step) {
          geom::Path longer = step == 0   ? geom::extend_to(path, ahead, reach, false)
                              : step == 1 ? geom::extend_to(path, sketch_roads, roads[i].width + sketch_width)
                              : step == 2 ? geom::extend_to(path, edges, 2 * roads[i].width)
                                          : geom::extend_to(path, ahead, reach);
          if (longer.size() == n) continue;
          on = longer, to_road = step == 0 || step == 3, to_sketch |= step == 1;
        }
        if (!on) {
          live[i] = 0, dropped = true;
          break;
        }
        path = *on;
        const geom::Vec2 p = path.point(path.size() - 1);
        // An open end run on to is no longer open: the road there does not run back.
        if (auto it = uses.find({p.x, p.y}); it != uses.end()) ++it->second;
        if (to_road) {
          // The road it ran on to: the one nearest its new end.
          double best = INFINITY;
          int met = -1;
          for (std::size_t k = 0; k < ahead_road.size(); ++k) {
            const geom::Polyline& l = roads[ahead_road[k]].lines[0];
            for (std::size_t s = 0; s + 1 < l.size(); ++s)
              if (const double d = geom::distance_to_segment(p, l[s], l[s + 1]); d < best) best = d, met = ahead_road[k];
          }
          meetings.push_back({static_cast<int>(i), met});
        }
      }
      if (dropped) break;
      index.push_back(static_cast<int>(i));
      settled.push_back({path, roads[i].width, roads[i].road_class, 0, to_sketch});
    }
  }
  // Pieces: roads sharing a vertex, or one running on to another.
  std::vector<int> piece(roads.size());
  std::iota(piece.begin(), piece.end(), 0);
  std::function<int(int)> find = [&](int x) { return piece[x] == x ? x : piece[x] = find(piece[x]); };
  std::map<std::pair<double, double>, int> first_at;
  for (int i : index)
    for (geom::Vec2 p : roads[i].lines[0])
      if (auto [it, added] = first_at.emplace(std::make_pair(p.x, p.y), i); !added) piece[find(i)] = find(it->second);
  for (auto [a, b] : meetings) piece[find(a)] = find(b);
  std::map<int, bool> reaches;
  for (std::size_t k = 0; k < settled.size(); ++k) reaches[find(index[k])] |= settled[k].reaches_sketch;
  for (std::size_t k = 0; k < settled.size(); ++k) {
    settled[k].piece = find(index[k]);
    settled[k].reaches_sketch = reaches[settled[k].piece];
  }
  return settled;
}

}  // namespace exacity
