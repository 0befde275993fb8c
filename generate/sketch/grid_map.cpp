#include "generate/sketch/grid_map.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

#include "generate/sketch/sketch.h"
#include "generate/errors.h"
#include "geom/grid.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// What a cell holds (a planned map grid's lot statuses; `.` is an empty lot, residential land).
enum class Status : unsigned char { Residential, Commercial, Industrial, Water, Park, Road, Blocked };

std::optional<Status> status_of(char c) {
  switch (c) {
    case '.':
    case 'r': return Status::Residential;
    case 'c': return Status::Commercial;
    case 'i': return Status::Industrial;
    case '~': return Status::Water;
    case '"': return Status::Park;
    case '=': return Status::Road;
    case 'X': return Status::Blocked;
    default: return std::nullopt;
  }
}

bool is_zone(Status s) { return s != Status::Road && s != Status::Blocked; }

ZoneType zone_type(Status s) {
  switch (s) {
    case Status::Commercial: return ZoneType::Commercial;
    case Status::Industrial: return ZoneType::Industrial;
    case Status::Water: return ZoneType::Water;
    case Status::Park: return ZoneType::Park;
    default: return ZoneType::Residential;
  }
}

constexpr const char* kCellCharacters = ". r c i = ~ \" X";

// A cell is 1 to 500 m: a road is at least one cell across, and the sketch reader's roads are
// at most kMaxRoadWidth wide; below a metre a map is no city (and would pass for lon/lat).
constexpr double kMinCell = 1;

// The most cells a map may have (2000 x 2000): reading one takes some 25 bytes a cell, and a
// 300 x 300 map's city takes 5 s to generate.
constexpr long long kMaxCells = 4'000'000;

// A character as a message shows it.
std::string shown(char c) {
  switch (c) {
    case ' ': return "a space (rows hold no spaces, at their ends either)";
    case '\t': return "a tab";
    case '\r': return "a carriage return";
    default: break;
  }
  const auto u = static_cast<unsigned char>(c);
  if (u >= 32 && u < 127) return std::string("'") + c + "'";
  static const char* hex = "0123456789ABCDEF";
  return std::string("the byte 0x") + hex[u >> 4] + hex[u & 15];
}

struct Token {
  std::string text;
  int column = 0;  // 1-based
};

std::vector<Token> tokens_of(const std::string& line) {
  std::vector<Token> out;
  for (std::size_t i = 0; i < line.size();) {
    if (line[i] == ' ' || line[i] == '\t') {
      ++i;
      continue;
    }
    std::size_t end = line.find_first_of(" \t", i);
    if (end == std::string::npos) end = line.size();
    out.push_back({line.substr(i, end - i), static_cast<int>(i) + 1});
    i = end;
  }
  return out;
}

// A header line: `cell` or `origin`, or a word of letters that are not all cells followed by
// more (a misspelt header). Every other line is a row of cells.
bool is_header(const std::string& line) {
  if (line.rfind("cell", 0) == 0 || line.rfind("origin", 0) == 0) return true;
  std::size_t word = 0;
  while (word < line.size() && std::isalpha(static_cast<unsigned char>(line[word]))) ++word;
  if (word < 2 || word == line.size() || (line[word] != ' ' && line[word] != '\t')) return false;
  return std::any_of(line.begin(), line.begin() + static_cast<long>(word), [](char c) { return !status_of(c); });
}

struct GridMap {
  double cell = 0;     // m, a multiple of 1/512 m so that half a cell lies on Exacity's grid
  geom::Vec2 origin;   // the south-west corner, on the grid
  int width = 0, height = 0;
  std::vector<Status> cells;  // row after row, the northernmost first
  std::vector<int> lines;     // each row's line in the file, 1-based

  // A point `hx` half cells east and `hy` half cells north of the south-west corner:
  // every one a point of the grid, computed one way, so equal points are equal doubles.
  geom::Vec2 point(long long hx, long long hy) const {
    const double half = cell / 2;
    return {origin.x + static_cast<double>(hx) * half, origin.y + static_cast<double>(hy) * half};
  }
};

class Reader {
 public:
  explicit Reader(const fs::path& path) : file_(path.string()) {}

  GridMap read(const std::string& text) {
    GridMap map;
    int line_no = 0;
    for (std::size_t start = 0; start <= text.size();) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(start, end - start);
      start = end + 1;
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF line endings
      const std::size_t first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line[first] == ';') continue;  // blank, or a comment
      if (is_header(line)) header(line, line_no, map);
      else row(line, line_no, map);
    }
    if (!cell_line_ && !origin_line_ && !first_row_line_)
      fail(1, 1, "no grid map here (the file is empty or holds only comments); write \"cell METRES\", then the rows, "
                 "north first");
    if (!cell_line_)
      fail(first_row_line_ ? first_row_line_ : origin_line_, 1,
           "no \"cell METRES\" line; add one above the rows, e.g. \"cell 10\"");
    if (!first_row_line_) {
      const int after = line_no + (text.empty() || text.back() == '\n' ? 0 : 1);
      fail(after, 1, "the map has no rows; draw them below the header, one line a row, the northernmost first");
    }
    if (std::all_of(map.cells.begin(), map.cells.end(), [](Status s) { return s == Status::Blocked; }))
      fail(first_row_line_, 1, "every cell is X (blocked), so there is no city; draw zone or road cells");
    check_extent(map);
    check_buildable(map);
    return map;
  }

  [[noreturn]] void fail(int line, int column, const std::string& what) const {
    throw UserError(file_ + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + what);
  }

  std::string where(const GridMap& map, int row, int column) const {
    return file_ + ":" + std::to_string(map.lines[row]) + ":" + std::to_string(column + 1);
  }

 private:
  void header(const std::string& line, int n, GridMap& map) {
    const std::vector<Token> t = tokens_of(line);
    const std::string& key = t[0].text;
    const bool is_cell = key == "cell", is_origin = key == "origin";
    if (!is_cell && !is_origin) {
      for (const std::string known : {"cell 10", "origin 0 0"}) {
        const std::string word = known.substr(0, known.find(' '));
        if (key.rfind(word, 0) == 0)
          fail(n, t[0].column + static_cast<int>(word.size()),
               "write a space after \"" + word + "\", e.g. \"" + known + "\"");
      }
      fail(n, t[0].column,
           "unknown header \"" + key + "\"; the headers are \"cell METRES\" and \"origin X Y\", then come the rows");
    }
    int& seen = is_cell ? cell_line_ : origin_line_;
    if (first_row_line_)
      fail(n, t[0].column, "\"" + key + "\" after the rows (they begin on line " + std::to_string(first_row_line_) +
                               "); move it above the first row");
    if (seen)
      fail(n, t[0].column, "a second \"" + key + "\" line (the first is line " + std::to_string(seen) + "); keep one");
    seen = n;
    const std::size_t want = is_cell ? 2 : 3;
    if (t.size() < want)
      fail(n, static_cast<int>(line.size()) + 1,
           is_cell ? "\"cell\" needs the cell size in metres, e.g. \"cell 10\""
                   : "\"origin\" needs the map's south-west corner in metres, e.g. \"origin 0 0\"");
    if (t.size() > want)
      fail(n, t[want].column, "\"" + t[want].text + "\" is one value too many; write \"" +
                                  (is_cell ? "cell METRES\"" : "origin X Y\""));
    if (is_cell) {
      const double cell = number(t[1], n);
      if (!(cell > 0))
        fail(n, t[1].column, "the cell size must be a positive number of metres, from 1 to 500; e.g. \"cell 10\"");
      if (cell < kMinCell || cell > kMaxRoadWidth)
        fail(n, t[1].column, "a cell of " + t[1].text + " m is " + (cell < kMinCell ? "under 1 m" : "over 500 m") +
                                 "; give 1 to 500 m (a road is at least one cell across, and at most 500 m wide)");
      // Half a cell on the grid of 1/1024 m, so that the roads' sides (half a width from
      // their centre lines) fall exactly on the zones' edges (docs/design.md, Exactness rule 2).
      map.cell = std::nearbyint(cell * 512) / 512;
      cell_column_ = t[1].column;
    } else {
      map.origin = geom::snap(geom::Vec2{number(t[1], n), number(t[2], n)});
    }
  }

  double number(const Token& t, int n) const {
    const char* begin = t.text.data() + (t.text[0] == '+' ? 1 : 0);
    const char* end = t.text.data() + t.text.size();
    double v = 0;
    const auto [stop, error] = std::from_chars(begin, end, v);
    if (error == std::errc::result_out_of_range || (error == std::errc() && stop == end && !std::isfinite(v)))
      fail(n, t.column, "\"" + t.text + "\" is not a finite number; give metres, e.g. 10 or -250.5");
    if (error != std::errc() || stop != end)
      fail(n, t.column, "\"" + t.text + "\" is not a number; give metres, e.g. 10 or -250.5");
    return v;
  }

  void row(const std::string& line, int n, GridMap& map) {
    if (!first_row_line_) first_row_line_ = n;
    for (std::size_t k = 0; k < line.size(); ++k)
      if (!status_of(line[k]))
        fail(n, static_cast<int>(k) + 1,
             shown(line[k]) + " is not a cell; a cell is one of " + kCellCharacters + " (docs/sketch.md, Grid maps)");
    const int length = static_cast<int>(line.size());
    if (map.height > 0 && length != map.width)
      fail(n, std::min(length, map.width) + 1,
           "this row is " + std::to_string(length) + " cells long, the first (line " + std::to_string(first_row_line_) +
               ") " + std::to_string(map.width) + "; make every row " + std::to_string(map.width) + " cells long");
    if (static_cast<long long>(map.cells.size()) + length > kMaxCells)
      fail(n, 1, "the map has over " + std::to_string(kMaxCells) + " cells here, more than one run reads (2000 x 2000); "
                 "use fewer, larger cells");
    map.width = length;
    for (char c : line) map.cells.push_back(*status_of(c));
    map.lines.push_back(n);
    ++map.height;
  }

  // Every corner within the range the sketch reader accepts.
  void check_extent(const GridMap& map) const {
    const geom::Vec2 far = map.point(2LL * map.width, 2LL * map.height);
    for (double v : {map.origin.x, map.origin.y, far.x, far.y})
      if (std::abs(v) > kMaxCoordinate)
        fail(origin_line_ ? origin_line_ : cell_line_, 1,
             "the map reaches " + nlohmann::json(v).dump() + " m, beyond the 1e10 m Exacity computes exactly in; "
                                                              "move its origin nearer 0 0, or use fewer or smaller cells");
  }

  // The sketch reader's limit on blocks (the zones' area over their block_area), said in the
  // map's own terms, since a grid map has no zones to draw smaller.
  void check_buildable(const GridMap& map) const {
    std::map<ZoneType, double> cells;
    for (Status s : map.cells)
      if (is_zone(s) && grows_roads(zone_type(s))) cells[zone_type(s)] += 1;
    double blocks = 0;
    for (auto [type, count] : cells)
      blocks += count * map.cell * map.cell / default_zone_settings(type).roads.growth.block_area;
    if (blocks > kMaxBlocks)
      fail(cell_line_, cell_column_,
           "the map's zones would make about " + std::to_string(static_cast<long long>(blocks)) +
               " blocks, more than the " + std::to_string(static_cast<long long>(kMaxBlocks)) +
               " one run builds; use a smaller cell or a smaller map");
  }

  std::string file_;
  int cell_line_ = 0, cell_column_ = 1, origin_line_ = 0, first_row_line_ = 0;
};

// ---- Zones: the outline of each connected region of equal cells --------------------------

// A cell corner: x cells east and y cells north of the map's south-west corner.
struct Corner {
  int x = 0, y = 0;
  friend auto operator<=>(const Corner&, const Corner&) = default;
};

struct Edge {
  Corner from, to;
};

struct Region {
  Status status = Status::Residential;
  int row = 0, column = 0;                 // its first cell, in reading order
  std::vector<std::vector<Corner>> rings;  // the outer ring (counter-clockwise) first, then holes
};

// The edge leaving `at` that turns right from `in`, where the region's cells touch only at
// this corner: the outline goes round the cells between them, so that the region is one
// piece through the corner and what it encloses on either side stays apart. Two regions
// touching at a corner are two regions, so that corner never comes up here.
int turn_right(const Edge& in, const std::vector<int>& out, const std::vector<Edge>& edges) {
  const int dx = in.to.x - in.from.x, dy = in.to.y - in.from.y;
  for (int e : out) {
    const int ex = edges[e].to.x - edges[e].from.x, ey = edges[e].to.y - edges[e].from.y;
    if (dx * ey - dy * ex < 0) return e;
  }
  throw InternalError("grid map: an outline corner with no right turn");
}

// Closed rings of the edges (each region's boundary, the region on the left), corners where
// the outline goes straight on left out.
std::vector<std::vector<Corner>> trace(const std::vector<Edge>& edges) {
  std::map<Corner, std::vector<int>> leaving;
  for (std::size_t e = 0; e < edges.size(); ++e) leaving[edges[e].from].push_back(static_cast<int>(e));
  std::vector<char> used(edges.size(), 0);
  std::vector<std::vector<Corner>> rings;
  for (std::size_t start = 0; start < edges.size(); ++start) {
    if (used[start]) continue;
    std::vector<Corner> ring;
    for (int e = static_cast<int>(start); !used[e];) {
      used[e] = 1;
      ring.push_back(edges[e].from);
      const std::vector<int>& next = leaving.at(edges[e].to);
      e = next.size() == 1 ? next[0] : turn_right(edges[e], next, edges);
    }
    std::vector<Corner> corners;
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Corner a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
      if (!((a.x == b.x && b.x == c.x) || (a.y == b.y && b.y == c.y))) corners.push_back(b);
    }
    rings.push_back(std::move(corners));
  }
  return rings;
}

long long twice_area(const std::vector<Corner>& ring) {
  long long a = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Corner p = ring[i], q = ring[(i + 1) % ring.size()];
    a += static_cast<long long>(p.x) * q.y - static_cast<long long>(q.x) * p.y;
  }
  return a;
}

std::vector<Region> zone_regions(const GridMap& map) {
  const int w = map.width, h = map.height;
  std::vector<int> region_of(static_cast<std::size_t>(w) * h, -1);
  std::vector<Region> regions;
  // Regions of equal cells joined side to side, found in reading order (a fixed order).
  std::vector<int> stack;
  for (int i = 0; i < w * h; ++i) {
    const Status s = map.cells[i];
    if (!is_zone(s) || region_of[i] >= 0) continue;
    const int id = static_cast<int>(regions.size());
    regions.push_back({s, i / w, i % w, {}});
    region_of[i] = id;
    stack.push_back(i);
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      const int r = k / w, c = k % w;
      const std::pair<int, int> around[] = {{r - 1, c}, {r + 1, c}, {r, c - 1}, {r, c + 1}};
      for (auto [nr, nc] : around) {
        if (nr < 0 || nr >= h || nc < 0 || nc >= w) continue;
        const int j = nr * w + nc;
        if (region_of[j] < 0 && map.cells[j] == s) region_of[j] = id, stack.push_back(j);
      }
    }
  }
  // Each cell side on a region's boundary, directed with the region on its left.
  std::vector<std::vector<Edge>> edges(regions.size());
  auto region_at = [&](int r, int c) { return r < 0 || r >= h || c < 0 || c >= w ? -1 : region_of[r * w + c]; };
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const int id = region_of[r * w + c];
      if (id < 0) continue;
      const int south = h - r - 1, north = h - r;
      std::vector<Edge>& e = edges[id];
      if (region_at(r + 1, c) != id) e.push_back({{c, south}, {c + 1, south}});
      if (region_at(r, c + 1) != id) e.push_back({{c + 1, south}, {c + 1, north}});
      if (region_at(r - 1, c) != id) e.push_back({{c + 1, north}, {c, north}});
      if (region_at(r, c - 1) != id) e.push_back({{c, north}, {c, south}});
    }
  for (std::size_t id = 0; id < regions.size(); ++id) {
    std::vector<std::vector<Corner>> rings = trace(edges[id]);
    // A region joined side to side has one outline around it; the rest are its holes.
    auto outer = std::stable_partition(rings.begin(), rings.end(), [](const auto& r) { return twice_area(r) > 0; });
    if (outer - rings.begin() != 1) throw InternalError("grid map: a region traced into other than one outer ring");
    regions[id].rings = std::move(rings);
  }
  return regions;
}

// ---- Roads: a road down the middle of each straight band of road cells ------------------

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

// A point in half cells: x east from the map's west edge, y south from its north edge (rows
// count from the north).
struct Half {
  int x = 0, y = 0;
  friend auto operator<=>(const Half&, const Half&) = default;
};

// A road on the map: a polyline of axis-parallel segments through half-cell points, its
// width in cells, and the cell that names it.
struct RoadPath {
  std::vector<Half> points;
  int cells_across = 1;
  int row = 0, column = 0;
  bool straight = true;  // a band's road, along one line; false for a connector
};

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

// A road's class from its width: the widest whose default width it reaches (local below 12 m,
// main from 12 m, highway from 24 m).
RoadClass class_of(double width) {
  if (width >= default_width(RoadClass::Highway)) return RoadClass::Highway;
  if (width >= default_width(RoadClass::Main)) return RoadClass::Main;
  return RoadClass::Local;
}

ordered_json position(geom::Vec2 p) { return ordered_json::array({p.x, p.y}); }

ordered_json zone_feature(const GridMap& map, const Region& region, const std::string& where) {
  ordered_json rings = ordered_json::array();
  for (const std::vector<Corner>& ring : region.rings) {
    ordered_json positions = ordered_json::array();
    for (Corner c : ring) positions.push_back(position(map.point(2LL * c.x, 2LL * c.y)));
    positions.push_back(positions.front());  // GeoJSON closes its rings
    rings.push_back(std::move(positions));
  }
  ordered_json properties = ordered_json::object();
  properties["zone"] = std::string(name(zone_type(region.status)));
  properties["grid_cell"] = where;
  ordered_json geometry = ordered_json::object();
  geometry["type"] = "Polygon";
  geometry["coordinates"] = std::move(rings);
  return {{"type", "Feature"}, {"properties", std::move(properties)}, {"geometry", std::move(geometry)}};
}

ordered_json road_feature(const GridMap& map, const RoadPath& road, const std::string& where) {
  ordered_json positions = ordered_json::array();
  // Half cells down from the north edge, y up from the south.
  for (Half h : road.points) positions.push_back(position(map.point(h.x, 2LL * map.height - h.y)));
  const double width = road.cells_across * map.cell;
  ordered_json properties = ordered_json::object();
  properties["road"] = std::string(name(class_of(width)));
  properties["width"] = width;
  properties["grid_cell"] = where;
  ordered_json geometry = ordered_json::object();
  geometry["type"] = "LineString";
  geometry["coordinates"] = std::move(positions);
  return {{"type", "Feature"}, {"properties", std::move(properties)}, {"geometry", std::move(geometry)}};
}

}  // namespace

ordered_json grid_map_features(const std::string& text, const fs::path& path) {
  Reader reader(path);
  const GridMap map = reader.read(text);
  ordered_json features = ordered_json::array();
  const std::vector<Region> regions = zone_regions(map);
  // Each region is a zone polygon, one block (or park or water face) at least, however few
  // its cells: the sketch reader's block limit, said before the features are made.
  if (static_cast<double>(regions.size()) > kMaxBlocks) {
    const Region& past = regions[static_cast<std::size_t>(kMaxBlocks)];
    reader.fail(map.lines[past.row], past.column + 1,
                "the map's zones are " + std::to_string(regions.size()) +
                    " separate regions (cells of one kind joined side to side), each a block at least, more than the " +
                    std::to_string(static_cast<long long>(kMaxBlocks)) +
                    " one run builds (this is the first past them); join them with fewer road or other cells between "
                    "them, or use a smaller map");
  }
  for (const Region& region : regions)
    features.push_back(zone_feature(map, region, reader.where(map, region.row, region.column)));
  for (const RoadPath& road : RoadBands(map).paths()) {
    if (road.cells_across * map.cell > kMaxRoadWidth)
      reader.fail(map.lines[road.row], road.column + 1,
                  "the road here is " + std::to_string(road.cells_across) + " cells across, wider than the " +
                      std::to_string(static_cast<int>(kMaxRoadWidth)) + " m a road may be; use a smaller cell or a "
                      "narrower band of =");
    features.push_back(road_feature(map, road, reader.where(map, road.row, road.column)));
  }
  return features;
}

ordered_json grid_map_sketch(const std::string& text, const fs::path& path) {
  ordered_json zones = ordered_json::object();
  for (const char* z : kGridMapStreetZones) zones[z] = {{"layout", "streets"}, {"placement", "grid"}};
  ordered_json settings = ordered_json::object();
  settings["version"] = 1;
  settings["zones"] = std::move(zones);
  ordered_json sketch = ordered_json::object();
  sketch["type"] = "FeatureCollection";
  sketch["exacity"] = std::move(settings);
  sketch["features"] = grid_map_features(text, path);
  return sketch;
}

}  // namespace exacity
