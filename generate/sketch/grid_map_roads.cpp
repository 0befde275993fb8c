// A grid map's roads (docs/design.md, The sketch; docs/sketch.md, Grid maps): road cells stacked into bands
// both ways, a road down the middle of each band longer than it is thick, roads meeting at
// shared vertices, and connectors through road cells that join pieces of roads.
#include "generate/sketch/grid_map_roads.h"

#include <algorithm>
#include <map>
#include <optional>

namespace exacity::grid_map {
namespace {

// A rectangle of road cells: rows (east-west) or columns (north-south) [across0, across1),
// each holding one maximal run of road cells, the same [along0, along1).
struct Band {
  bool east_west = true;
  int across0 = 0, across1 = 0, along0 = 0, along1 = 0;
  int thickness() const { return across1 - across0; }
  int length() const { return along1 - along0; }
  int centre() const { return across0 + across1; }  // in half cells
};

// The bands one way: maximal runs of road cells in each row (or column), a run stacked onto
// the band of the run just before it when the two have the same extent.
std::vector<Band> stack_runs(const GridMap& map, bool east_west, std::vector<int>& band_of) {
  const int across_n = east_west ? map.height : map.width, along_n = east_west ? map.width : map.height;
  auto index = [&](int a, int b) { return east_west ? a * map.width + b : b * map.width + a; };
  std::vector<Band> out;
  std::map<std::pair<int, int>, int> before;
  for (int a = 0; a < across_n; ++a) {
    std::map<std::pair<int, int>, int> now;
    for (int b = 0; b < along_n;) {
      if (map.cells[index(a, b)] != Status::Road) {
        ++b;
        continue;
      }
      int e = b;
      while (e < along_n && map.cells[index(a, e)] == Status::Road) ++e;
      int id;
      if (auto it = before.find({b, e}); it != before.end()) {
        id = it->second;
        out[id].across1 = a + 1;
      } else {
        id = static_cast<int>(out.size());
        out.push_back({east_west, a, a + 1, b, e});
      }
      now[{b, e}] = id;
      for (int k = b; k < e; ++k) band_of[index(a, k)] = id;
      b = e;
    }
    before = std::move(now);
  }
  return out;
}

// Each of the points that lies on the path made a vertex of it. A band's road is straight,
// so its points sort along it; a connector has a few segments, each searched.
void insert_vertices(RoadPath& path, std::vector<Half> points) {
  const Half front = path.points.front(), back = path.points.back();
  if (path.straight) {
    points.insert(points.end(), path.points.begin(), path.points.end());
    const bool east_west = front.y == back.y;
    const int sign = (east_west ? back.x - front.x : back.y - front.y) > 0 ? 1 : -1;
    auto along = [&](Half h) { return sign * (east_west ? h.x : h.y); };
    std::sort(points.begin(), points.end(), [&](Half p, Half q) { return along(p) < along(q); });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    path.points = std::move(points);
    return;
  }
  std::vector<Half> out{front};
  for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
    const Half a = path.points[i], b = path.points[i + 1];
    std::vector<Half> on;
    for (Half p : points)
      if (p != a && p != b && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
          p.y <= std::max(a.y, b.y))
        on.push_back(p);
    auto from_a = [&](Half p) { return std::abs(p.x - a.x) + std::abs(p.y - a.y); };
    std::sort(on.begin(), on.end(), [&](Half p, Half q) { return from_a(p) < from_a(q); });
    on.erase(std::unique(on.begin(), on.end()), on.end());
    out.insert(out.end(), on.begin(), on.end());
    out.push_back(b);
  }
  path.points = std::move(out);
}

// Where two roads meet or cross, a vertex of both, so that the sketch reader makes a
// junction there (it joins streets that share a vertex). Every half-cell point each road
// passes through, sorted, brings the roads at one point together: linear in the roads'
// length, where testing every pair of roads would be quadratic in their number.
void node(std::vector<RoadPath>& paths) {
  std::vector<std::pair<Half, int>> passes;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const std::vector<Half>& p = paths[i].points;
    for (std::size_t s = 0; s + 1 < p.size(); ++s) {
      const Half a = p[s], b = p[s + 1];
      const int dx = (b.x > a.x) - (b.x < a.x), dy = (b.y > a.y) - (b.y < a.y);
      for (Half h = a;; h = {h.x + dx, h.y + dy}) {
        passes.push_back({h, static_cast<int>(i)});
        if (h == b) break;
      }
    }
  }
  std::sort(passes.begin(), passes.end());
  passes.erase(std::unique(passes.begin(), passes.end()), passes.end());
  std::vector<std::vector<Half>> at(paths.size());
  for (std::size_t k = 0; k < passes.size();) {
    std::size_t end = k;
    while (end < passes.size() && passes[end].first == passes[k].first) ++end;
    if (end - k > 1)
      for (std::size_t j = k; j < end; ++j) at[passes[j].second].push_back(passes[k].first);
    k = end;
  }
  for (std::size_t i = 0; i < paths.size(); ++i) insert_vertices(paths[i], std::move(at[i]));
}

// The points without repeats, nor corners where the path goes straight on or back.
std::vector<Half> simplified(const std::vector<Half>& points) {
  std::vector<Half> out;
  auto in_line = [](Half a, Half b, Half c) { return (a.x == b.x && b.x == c.x) || (a.y == b.y && b.y == c.y); };
  for (Half p : points) {
    while (out.size() >= 2 && in_line(out[out.size() - 2], out.back(), p)) out.pop_back();
    if (out.empty() || out.back() != p) out.push_back(p);
  }
  return out;
}

// Which roads are joined, as pieces grow.
class Pieces {
 public:
  int add() {
    parent_.push_back(static_cast<int>(parent_.size()));
    return parent_.back();
  }
  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(int a, int b) { parent_[find(a)] = find(b); }

 private:
  std::vector<int> parent_;
};

class RoadBands {
 public:
  explicit RoadBands(const GridMap& map) : map_(map) {
    const std::size_t n = map.cells.size();
    std::vector<int> east_of(n, -1), north_of(n, -1);
    bands_ = stack_runs(map, true, east_of);
    const int east_west = static_cast<int>(bands_.size());
    for (const Band& b : stack_runs(map, false, north_of)) bands_.push_back(b);
    band_at_.assign(n, {-1, -1});
    for (std::size_t i = 0; i < n; ++i)
      if (map.cells[i] == Status::Road) band_at_[i] = {east_of[i], east_west + north_of[i]};
    choose();
  }

  // A road down each band kept, its ends run on to the centre line of the road across
  // them; the roads made vertices of each other where they meet; and where road cells
  // join two pieces of roads that do not meet (a blob of road cells, a road changing
  // width), a connector one cell wide between them through those cells.
  std::vector<RoadPath> paths() {
    std::vector<RoadPath> out;
    path_of_.assign(bands_.size(), -1);
    band_of_.clear();
    for (std::size_t b = 0; b < bands_.size(); ++b) {
      if (!kept_[b]) continue;
      const Band& band = bands_[b];
      int from = end_at(band, band.along0, 2 * band.along0), to = end_at(band, band.along1 - 1, 2 * band.along1);
      if (from >= to) from = 2 * band.along0, to = 2 * band.along1;
      path_of_[b] = static_cast<int>(out.size());
      band_of_.push_back(static_cast<int>(b));
      const int row = band.east_west ? band.across0 : band.along0;
      const int column = band.east_west ? band.along0 : band.across0;
      out.push_back({{on_axis(band, from), on_axis(band, to)}, band.thickness(), row, column});
    }
    node(out);
    join_pieces(out);
    node(out);
    return out;
  }

 private:
  Half on_axis(const Band& band, int along) const {
    return band.east_west ? Half{along, band.centre()} : Half{band.centre(), along};
  }

  // The roads kept over a road cell: one or two.
  std::vector<int> paths_at(int cell) const {
    std::vector<int> out;
    for (int b : {band_at_[cell].first, band_at_[cell].second})
      if (kept_[b]) out.push_back(path_of_[b]);
    return out;
  }

  // From the band's road to the centre of one of its cells: across from the road at the
  // cell, the road run on along its line first where its end stops short of the cell.
  std::vector<Half> to_cell(const RoadPath& road, int band, int cell) const {
    const Band& b = bands_[band];
    const int row = cell / map_.width, column = cell % map_.width;
    const Half centre{2 * column + 1, 2 * row + 1};
    const Half front = road.points.front(), back = road.points.back();
    const int along = b.east_west ? centre.x : centre.y;
    const int lo = std::min(b.east_west ? front.x : front.y, b.east_west ? back.x : back.y);
    const int hi = std::max(b.east_west ? front.x : front.y, b.east_west ? back.x : back.y);
    return {on_axis(b, std::clamp(along, lo, hi)), on_axis(b, along), centre};
  }

  void join_pieces(std::vector<RoadPath>& roads) {
    Pieces pieces;
    std::map<Half, int> first_at;
    for (std::size_t r = 0; r < roads.size(); ++r) {
      pieces.add();
      for (Half p : roads[r].points)
        if (auto [it, fresh] = first_at.emplace(p, static_cast<int>(r)); !fresh)
          pieces.join(it->second, static_cast<int>(r));
    }
    auto connect = [&](int a, int p, int b, int q) {
      std::vector<Half> points = to_cell(roads[a], band_of_[a], p);
      std::vector<Half> back = to_cell(roads[b], band_of_[b], q);
      points.insert(points.end(), back.rbegin(), back.rend());
      points = simplified(points);
      if (points.size() < 2) return;
      roads.push_back({points, 1, p / map_.width, p % map_.width, false});
      const int c = pieces.add();
      pieces.join(c, a), pieces.join(c, b);
    };
    const int w = map_.width, h = map_.height;
    for (int cell = 0; cell < w * h; ++cell) {
      if (map_.cells[cell] != Status::Road) continue;
      const std::vector<int> here = paths_at(cell);
      if (here.size() == 2 && pieces.find(here[0]) != pieces.find(here[1])) connect(here[0], cell, here[1], cell);
      const int row = cell / w, column = cell % w;
      for (int next : {column + 1 < w ? cell + 1 : -1, row + 1 < h ? cell + w : -1}) {
        if (next < 0 || map_.cells[next] != Status::Road) continue;
        for (int a : here)
          for (int b : paths_at(next))
            if (pieces.find(a) != pieces.find(b)) connect(a, cell, b, next);
      }
    }
  }

  // Every band longer than it is wide is a road; a cell in no such band (a square of road
  // cells) takes its east-west band, a square road. Then a band lying wholly in one road
  // across it (a stub of a wider road) is dropped, the thinnest and shortest first; a band
  // whose cells lie in two roads across it joins them (a step of a staircase), so it stays.
  void choose() {
    kept_.assign(bands_.size(), 0);
    for (std::size_t b = 0; b < bands_.size(); ++b) kept_[b] = bands_[b].length() > bands_[b].thickness();
    for (auto [east, north] : band_at_)
      if (east >= 0 && !kept_[east] && !kept_[north]) kept_[east] = 1;
    std::vector<int> order;
    for (std::size_t b = 0; b < bands_.size(); ++b)
      if (kept_[b]) order.push_back(static_cast<int>(b));
    auto size = [&](int b) { return std::pair{bands_[b].thickness(), bands_[b].length()}; };
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return size(a) < size(b); });
    for (int b : order) {
      const std::vector<int> cells = cells_of(bands_[b]);
      auto across = [&](int i) { return bands_[b].east_west ? band_at_[i].second : band_at_[i].first; };
      const int first = across(cells.front());
      if (kept_[first] && std::all_of(cells.begin(), cells.end(), [&](int i) { return across(i) == first; }))
        kept_[b] = 0;
    }
  }

  std::vector<int> cells_of(const Band& band) const {
    std::vector<int> out;
    for (int a = band.across0; a < band.across1; ++a)
      for (int b = band.along0; b < band.along1; ++b) out.push_back(index(band, a, b));
    return out;
  }

  int index(const Band& band, int across, int along) const {
    return band.east_west ? across * map_.width + along : along * map_.width + across;
  }

  // Where a band's end at the cells `along` lies: on the centre line of the road across it
  // that holds most of those cells, or `otherwise` (the band's own end) when none does.
  int end_at(const Band& band, int along, int otherwise) const {
    std::map<int, int> held;
    for (int a = band.across0; a < band.across1; ++a) {
      const auto [east, north] = band_at_[index(band, a, along)];
      const int across = band.east_west ? north : east;
      if (kept_[across]) ++held[across];
    }
    int best = -1;
    for (auto [b, n] : held)
      if (best < 0 || n > held[best]) best = b;
    return best < 0 ? otherwise : bands_[best].centre();
  }

  const GridMap& map_;
  std::vector<Band> bands_;                    // east-west first, then north-south
  std::vector<std::pair<int, int>> band_at_;   // each road cell's east-west and north-south band
  std::vector<char> kept_;
  std::vector<int> path_of_, band_of_;         // each kept band's road, each band's road's band
};

}  // namespace

std::vector<RoadPath> road_paths(const GridMap& map) { return RoadBands(map).paths(); }

}  // namespace exacity::grid_map
