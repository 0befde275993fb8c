#include "generate/city/street_graph.h"

#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

#include "geom/box_index.h"
#include "geom/grid.h"
#include "geom/measure.h"

namespace exacity {
namespace {

// How many times each point is a vertex of a line (a closed line's end counts twice).
std::unordered_map<geom::Vec2, int, geom::Vec2Hash> vertex_counts(const std::vector<RoadFeature>& roads) {
  std::unordered_map<geom::Vec2, int, geom::Vec2Hash> count;
  for (const RoadFeature& r : roads)
    for (const geom::Polyline& line : r.lines)
      for (geom::Vec2 p : line) ++count[p];
  return count;
}


using geom::segment_key;
using Segments = std::set<geom::SegmentKey>;

Segments segments_of(const std::vector<RoadFeature>& roads) {
  Segments out;
  for (const RoadFeature& r : roads)
    for (const geom::Polyline& line : r.lines)
      for (std::size_t i = 0; i + 1 < line.size(); ++i) out.insert(segment_key(line[i], line[i + 1]));
  return out;
}

// Moves a line's end to p unless that would leave the line a single point, or lay its end
// segment along one another line already has (two lines drawn a few degrees apart from one
// node would become one).
bool move_end(geom::Polyline& line, bool back, geom::Vec2 p, Segments& segments) {
  geom::Vec2& end = back ? line.back() : line.front();
  if (end == p) return false;
  const geom::Vec2 next = back ? line[line.size() - 2] : line[1];
  if (next == p) {
    // The end segment folds away; the one before it now ends the line.
    if (line.size() < 3) return false;
    segments.erase(segment_key(next, end));
    back ? line.pop_back() : static_cast<void>(line.erase(line.begin()));
    return true;
  }
  if (segments.count(segment_key(next, p))) return false;
  segments.erase(segment_key(next, end));
  segments.insert(segment_key(next, p));
  end = p;
  return true;
}

struct LineEnd {
  std::size_t road, line;
  bool back;
};

// Both ends of every line, in order of road, then line.
std::vector<LineEnd> line_ends(const std::vector<RoadFeature>& roads) {
  std::vector<LineEnd> ends;
  for (std::size_t r = 0; r < roads.size(); ++r)
    for (std::size_t k = 0; k < roads[r].lines.size(); ++k) ends.push_back({r, k, false}), ends.push_back({r, k, true});
  return ends;
}

geom::Vec2& point_of(std::vector<RoadFeature>& roads, const LineEnd& e) {
  geom::Polyline& l = roads[e.road].lines[e.line];
  return e.back ? l.back() : l.front();
}

// A box around p, a metre wider than `snap` each way: the index filters in doubles, the
// callers measure exactly as before.
geom::Box around(geom::Vec2 p, double snap) { return {p.x - snap - 1, p.y - snap - 1, p.x + snap + 1, p.y + snap + 1}; }

// Each end joins the first earlier end of another line near it. An end moves only as its
// turn comes, so the earlier ends are in the index where they now are.
int join_ends_to_ends(std::vector<RoadFeature>& roads, const std::vector<LineEnd>& ends, double snap,
                      Segments& segments) {
  int moved = 0;
  geom::BoxIndex earlier(snap + 1);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    for (int j : earlier.meeting(around(point_of(roads, ends[i]), snap))) {
      if (ends[j].road == ends[i].road && ends[j].line == ends[i].line) continue;
      const geom::Vec2 target = point_of(roads, ends[j]);
      if (geom::distance(point_of(roads, ends[i]), target) > snap) continue;
      if (!(point_of(roads, ends[i]) == target))
        moved += move_end(roads[ends[i].road].lines[ends[i].line], ends[i].back, target, segments);
      break;
    }
    const geom::Vec2 now = point_of(roads, ends[i]);
    earlier.add(static_cast<int>(i), {now.x, now.y, now.x, now.y});
  }
  return moved;
}

struct Side {
  geom::Polyline* line = nullptr;
  std::size_t segment = 0;
};

// Every line's box in an index, by its place in the order of roads, then lines; a line
// that changes is added again with its new points (its box only grows).
struct LineBoxes {
  std::vector<geom::Polyline*> lines;
  std::map<const geom::Polyline*, int> place;
  geom::BoxIndex index;

  LineBoxes(std::vector<RoadFeature>& roads, double bucket) : index(bucket) {
    for (RoadFeature& r : roads)
      for (geom::Polyline& line : r.lines) place[&line] = static_cast<int>(lines.size()), lines.push_back(&line), update(line);
  }
  void update(const geom::Polyline& line) {
    geom::Box box = geom::Box::none();
    for (geom::Vec2 p : line) box.add(p);
    index.add(place.at(&line), box);
  }
};

// The segment nearest p within snap, not counting the end's own segment, which already
// touches it; on a tie, the last found. Only lines whose box lies near p hold one, and
// they are searched in the order of all lines.
Side nearest_side(const LineBoxes& boxes, const geom::Polyline& own, bool back, geom::Vec2 p, double snap) {
  double best = snap;
  Side side;
  for (int k : boxes.index.meeting(around(p, snap))) {
    geom::Polyline& line = *boxes.lines[k];
    for (std::size_t s = 0; s + 1 < line.size(); ++s) {
      if (&line == &own && (back ? s + 2 == line.size() : s == 0)) continue;
      const geom::Vec2 a = line[s], b = line[s + 1];
      if (std::min(a.x, b.x) - snap > p.x || std::max(a.x, b.x) + snap < p.x ||
          std::min(a.y, b.y) - snap > p.y || std::max(a.y, b.y) + snap < p.y)
        continue;
      const double d = geom::distance_to_segment(p, a, b);
      if (d <= best) best = d, side = {&line, s};
    }
  }
  return side;
}

// Moves the end at p onto the side (onto one of its vertices if both are near it),
// splitting the side there; returns how many ends moved.
int join_end_to_side(geom::Polyline& own, bool back, geom::Vec2 p, Side side, double snap, Segments& segments,
                     std::unordered_map<geom::Vec2, int, geom::Vec2Hash>& counts) {
  geom::Polyline& target = *side.line;
  const geom::Vec2 a = target[side.segment], b = target[side.segment + 1];
  geom::Vec2 at = geom::snap(geom::nearest_on_segment(p, a, b));
  if (geom::distance(at, a) <= snap && geom::distance(p, a) <= snap) at = a;  // onto a vertex rather than beside it
  else if (geom::distance(at, b) <= snap && geom::distance(p, b) <= snap) at = b;
  int moved = 0;
  if (!(at == p)) {
    if (!move_end(own, back, at, segments)) return 0;
    ++moved;
  }
  if (!(at == a) && !(at == b)) {
    target.insert(target.begin() + side.segment + 1, at);
    segments.erase(segment_key(a, b));
    segments.insert(segment_key(a, at)), segments.insert(segment_key(at, b));
  }
  ++counts[at];
  return moved;
}

// Ends still meeting nothing join the nearest side of another line.
int join_ends_to_sides(std::vector<RoadFeature>& roads, const std::vector<LineEnd>& ends, double snap,
                       Segments& segments) {
  int moved = 0;
  auto counts = vertex_counts(roads);
  LineBoxes boxes(roads, snap + 1);
  for (const LineEnd& e : ends) {
    geom::Polyline& own = roads[e.road].lines[e.line];
    const geom::Vec2 p = point_of(roads, e);
    if (counts[p] > 1) continue;
    const Side side = nearest_side(boxes, own, e.back, p, snap);
    if (!side.line) continue;
    moved += join_end_to_side(own, e.back, p, side, snap, segments, counts);
    boxes.update(own), boxes.update(*side.line);
  }
  return moved;
}

}  // namespace

int join_near_ends(std::vector<RoadFeature>& roads, double snap) {
  const std::vector<LineEnd> ends = line_ends(roads);
  Segments segments = segments_of(roads);
  int moved = join_ends_to_ends(roads, ends, snap, segments);
  moved += join_ends_to_sides(roads, ends, snap, segments);
  return moved;
}

std::vector<StreetNode> street_nodes(const std::vector<RoadFeature>& roads) {
  struct Meeting {
    std::vector<StreetArm> arms;
    int lines = 0;  // vertices of lines at the point (a line's two ends count twice)
  };
  std::map<std::pair<double, double>, Meeting> at;  // ordered: nodes come out in a fixed order
  for (std::size_t r = 0; r < roads.size(); ++r)
    for (const geom::Polyline& line : roads[r].lines) {
      // Length along the line up to each vertex.
      std::vector<double> along{0};
      for (std::size_t i = 1; i < line.size(); ++i) along.push_back(along.back() + geom::distance(line[i - 1], line[i]));
      for (std::size_t i = 0; i < line.size(); ++i) {
        Meeting& m = at[{line[i].x, line[i].y}];
        ++m.lines;
        if (i > 0) m.arms.push_back({static_cast<int>(r), line[i - 1], along[i]});
        if (i + 1 < line.size()) m.arms.push_back({static_cast<int>(r), line[i + 1], along.back() - along[i]});
      }
    }
  std::vector<StreetNode> nodes;
  for (auto& [p, m] : at)
    if (m.lines > 1 && m.arms.size() > 1) nodes.push_back({{p.first, p.second}, std::move(m.arms)});
  return nodes;
}

std::vector<DeadEnd> dead_ends(const std::vector<RoadFeature>& roads) {
  auto counts = vertex_counts(roads);
  std::vector<DeadEnd> out;
  for (const RoadFeature& r : roads)
    for (const geom::Polyline& line : r.lines)
      for (geom::Vec2 end : {line.front(), line.back()})
        if (counts[end] == 1) out.push_back({r.index, end});
  return out;
}

}  // namespace exacity
