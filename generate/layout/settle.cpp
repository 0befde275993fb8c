#include "generate/layout/settle.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "generate/city/street_graph.h"
#include "geom/box_index.h"
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
      if (piece.size() >= 2) out.push_back({static_cast<int>(out.size()), r.road_class, r.width, {piece}, {}});
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
// Only the kept roads whose box lies within the widest half width of a sample can cover it
// (the index is asked a metre further: a filter in doubles).
std::vector<RoadFeature> without_roads_inside_others(const std::vector<RoadFeature>& roads) {
  double widest = 0;
  for (const RoadFeature& r : roads) widest = std::max(widest, r.width);
  std::vector<RoadFeature> kept;
  std::vector<geom::Box> boxes;
  geom::BoxIndex index(std::max(widest, 1.0));
  for (const RoadFeature& r : roads) {
    const geom::Polyline& line = r.lines[0];
    std::vector<geom::Vec2> samples = line;
    for (std::size_t k = 0; k + 1 < line.size(); ++k)
      samples.push_back({(line[k].x + line[k + 1].x) / 2, (line[k].y + line[k + 1].y) / 2});
    auto covered = [&](geom::Vec2 p) {
      const double near = widest / 2 + 1;
      for (int j : index.meeting({p.x - near, p.y - near, p.x + near, p.y + near})) {
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
    index.add(static_cast<int>(kept.size()), box);
    kept.push_back(r), boxes.push_back(box);
  }
  return kept;
}

std::vector<RoadFeature> planned_roads(const LinePlan& plan) {
  std::vector<RoadFeature> roads;
  for (const PlannedRoad& r : plan.roads) roads.push_back({static_cast<int>(roads.size()), r.road_class, r.width, {r.line}, {}});
  return roads;
}

double widest_planned(const LinePlan& plan) {
  double widest = 0;
  for (const PlannedRoad& r : plan.roads) widest = std::max(widest, r.width);
  return widest;
}

// The region's rings, closed: an open end may run on to the region's edge.
std::vector<geom::Path> region_edges(const geom::Cell& cell) {
  std::vector<geom::Path> edges;
  for (const geom::KindedRing& r : cell.kinded_rings()) {
    geom::Polyline closed = r.points;
    closed.push_back(r.points.front());
    edges.push_back(geom::Path::from(closed));
  }
  return edges;
}

// Roads of fewer than two points, or closed on themselves, take no part.
std::vector<char> roads_with_ends(const std::vector<RoadFeature>& roads) {
  std::vector<char> live(roads.size(), 1);
  for (std::size_t i = 0; i < roads.size(); ++i) {
    const geom::Polyline& l = roads[i].lines[0];
    live[i] = l.size() >= 2 && !(l.front() == l.back());
  }
  return live;
}

struct SettledRoad {
  geom::Path path;
  double width = 0;
  RoadClass road_class = RoadClass::Local;
  int piece = 0;
  bool reaches_sketch = false;  // its piece runs on to a sketch road
};

// What an open end may run on to, and how far.
struct Targets {
  const std::vector<geom::Path>& sketch_roads;
  double sketch_width;
  const std::vector<geom::Path>& edges;
  double reach;  // to another road
};

// The live roads as one round of settling starts.
struct Round {
  std::map<std::pair<double, double>, int> uses;  // road vertices at each point; an end used once is open
  std::vector<int> others;                        // the live roads
  std::vector<geom::Path> paths;                  // of the live roads, in `others` order
  std::vector<int> position;                      // per road, its place in `others` (-1: not live)
  geom::BoxIndex boxes{0};                        // of the live roads' lines, by place in `others`
};

Round start_round(const std::vector<RoadFeature>& roads, const std::vector<char>& live, double reach) {
  Round round;
  round.position.assign(roads.size(), -1);
  round.boxes = geom::BoxIndex(reach);
  for (std::size_t i = 0; i < roads.size(); ++i)
    if (live[i]) {
      round.position[i] = static_cast<int>(round.others.size());
      geom::Box box = geom::Box::none();
      for (geom::Vec2 p : roads[i].lines[0]) ++round.uses[{p.x, p.y}], box.add(p);
      round.boxes.add(static_cast<int>(round.others.size()), box);
      round.others.push_back(static_cast<int>(i));
      round.paths.push_back(geom::Path::from(roads[i].lines[0]));
    }
  return round;
}

struct RunOn {
  geom::Path path;
  bool to_road = false, to_sketch = false;
};

// Straight on to another road; to a sketch road or the edge, turning if need be; else
// turning to the nearest other road. None when the end reaches none of them.
std::optional<RunOn> run_on(const geom::Path& path, const std::vector<geom::Path>& ahead, double width,
                            const Targets& targets) {
  // An end drawn exactly onto a road or the edge (a grammar's road across its whole piece)
  // meets it already.
  if (geom::ends_on(path, ahead)) return RunOn{path, true, false};
  if (geom::ends_on(path, targets.sketch_roads)) return RunOn{path, false, true};
  if (geom::ends_on(path, targets.edges)) return RunOn{path, false, false};
  const std::size_t n = path.size();
  for (int step = 0; step < 4; ++step) {
    geom::Path longer = step == 0   ? geom::extend_to(path, ahead, targets.reach, false)
                        : step == 1 ? geom::extend_to(path, targets.sketch_roads, width + targets.sketch_width)
                        : step == 2 ? geom::extend_to(path, targets.edges, 2 * width)
                                    : geom::extend_to(path, ahead, targets.reach);
    if (longer.size() == n) continue;
    return RunOn{longer, step == 0 || step == 3, step == 1};
  }
  return std::nullopt;
}

// The road an end ran on to: the one nearest its new end.
int nearest_road(geom::Vec2 p, const std::vector<int>& candidates, const std::vector<RoadFeature>& roads) {
  double best = INFINITY;
  int met = -1;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const geom::Polyline& l = roads[candidates[k]].lines[0];
    for (std::size_t s = 0; s + 1 < l.size(); ++s)
      if (const double d = geom::distance_to_segment(p, l[s], l[s + 1]); d < best) best = d, met = candidates[k];
  }
  return met;
}

// Road i with its open ends run on, each road it ran on to added to `meetings`; none when
// an end reaches nothing, and the road must be dropped. An end looks at the other roads
// near it only: run_on reaches no further than targets.reach (extend_to searches a metre
// past it), and every road it could meet or find nearest lies in that box, in their order.
std::optional<SettledRoad> settle_road(int i, const std::vector<RoadFeature>& roads, Round& round, const Targets& targets,
                                       std::vector<std::pair<int, int>>& meetings) {
  const geom::Polyline& line = roads[i].lines[0];
  geom::Path path = round.paths[round.position[i]];
  bool to_sketch = false;
  for (bool back : {true, false}) {
    const geom::Vec2 end = back ? line.back() : line.front();
    if (!back) path = path.reversed();
    if (round.uses[{end.x, end.y}] > 1) continue;
    const double near = targets.reach + 2;
    std::vector<geom::Path> ahead;
    std::vector<int> ahead_road;
    for (int k : round.boxes.meeting({end.x - near, end.y - near, end.x + near, end.y + near}))
      if (round.others[k] != i) ahead.push_back(round.paths[k]), ahead_road.push_back(round.others[k]);
    std::optional<RunOn> on = run_on(path, ahead, roads[i].width, targets);
    if (!on) return std::nullopt;
    path = on->path;
    to_sketch |= on->to_sketch;
    const geom::Vec2 p = path.point(path.size() - 1);
    // An open end run on to is no longer open: the road there does not run back.
    if (auto it = round.uses.find({p.x, p.y}); it != round.uses.end()) ++it->second;
    if (on->to_road) meetings.push_back({i, nearest_road(p, ahead_road, roads)});
  }
  return SettledRoad{path, roads[i].width, roads[i].road_class, 0, to_sketch};
}

struct Settlement {
  std::vector<SettledRoad> settled;
  std::vector<int> index;                     // settled road -> road
  std::vector<std::pair<int, int>> meetings;  // (road, road) met by running on
};

// Every live road settled in order. A road that cannot be is dropped and the round starts
// again without it, as the ends it used may now be open.
Settlement settle_live_roads(const std::vector<RoadFeature>& roads, std::vector<char> live, const Targets& targets) {
  for (;;) {
    Round round = start_round(roads, live, targets.reach);
    Settlement s;
    bool dropped = false;
    for (std::size_t i = 0; i < roads.size(); ++i) {
      if (!live[i]) continue;
      std::optional<SettledRoad> road = settle_road(static_cast<int>(i), roads, round, targets, s.meetings);
      if (!road) {
        live[i] = 0, dropped = true;
        break;
      }
      s.index.push_back(static_cast<int>(i));
      s.settled.push_back(*road);
    }
    if (!dropped) return s;
  }
}

// Pieces: roads sharing a vertex, or one running on to another. A piece reaches the sketch
// when one of its roads does.
void join_pieces(Settlement& s, const std::vector<RoadFeature>& roads) {
  std::vector<int> piece(roads.size());
  std::iota(piece.begin(), piece.end(), 0);
  std::function<int(int)> find = [&](int x) { return piece[x] == x ? x : piece[x] = find(piece[x]); };
  std::map<std::pair<double, double>, int> first_at;
  for (int i : s.index)
    for (geom::Vec2 p : roads[i].lines[0])
      if (auto [it, added] = first_at.emplace(std::make_pair(p.x, p.y), i); !added) piece[find(i)] = find(it->second);
  for (auto [a, b] : s.meetings) piece[find(a)] = find(b);
  std::map<int, bool> reaches;
  for (std::size_t k = 0; k < s.settled.size(); ++k) reaches[find(s.index[k])] |= s.settled[k].reaches_sketch;
  for (std::size_t k = 0; k < s.settled.size(); ++k) {
    s.settled[k].piece = find(s.index[k]);
    s.settled[k].reaches_sketch = reaches[s.settled[k].piece];
  }
}

// The settled roads as a plan: pieces numbered in the order they first appear; a junction
// where roads share a vertex, in the order of the points.
RoadPlan plan_of(const std::vector<SettledRoad>& settled) {
  RoadPlan plan;
  std::map<int, int> piece_number;
  std::map<std::pair<double, double>, std::vector<int>> at;
  for (const SettledRoad& r : settled) {
    auto [it, added] = piece_number.emplace(r.piece, static_cast<int>(plan.piece_reaches_sketch.size()));
    if (added) plan.piece_reaches_sketch.push_back(r.reaches_sketch);
    for (std::size_t k = 0; k < r.path.size(); ++k) {
      const geom::Vec2 p = r.path.point(k);
      at[{p.x, p.y}].push_back(static_cast<int>(plan.roads.size()));
    }
    plan.roads.push_back({r.path, r.width, r.road_class, r.road_class == RoadClass::Main ? 0 : 1, it->second});
  }
  for (const auto& [p, here] : at)
    if (here.size() > 1) plan.junctions.push_back({{p.first, p.second}, here.front()});
  return plan;
}

}  // namespace

RoadPlan settle(LinePlan plan, const geom::Cell& cell, const SketchLines& sketch) {
  std::vector<geom::Path> sketch_roads;
  double sketch_width = 0;
  for (const SketchRoad& s : sketch) {
    sketch_roads.insert(sketch_roads.end(), s.lines.begin(), s.lines.end());
    sketch_width = std::max(sketch_width, s.width);
  }
  std::vector<RoadFeature> roads = planned_roads(plan);
  const double widest = widest_planned(plan);
  join_near_ends(roads, plan.join);
  roads = without_roads_inside_others(without_repeated_segments(roads));
  const double reach = std::max(3 * widest, 0.1 * std::sqrt(cell.area()));
  const std::vector<geom::Path> edges = region_edges(cell);
  Settlement s = settle_live_roads(roads, roads_with_ends(roads), {sketch_roads, sketch_width, edges, reach});
  join_pieces(s, roads);
  RoadPlan settled = plan_of(s.settled);
  settled.uses = std::move(plan.uses);
  settled.dropped_roads = static_cast<int>(roads.size() - s.settled.size());
  return settled;
}

}  // namespace exacity
