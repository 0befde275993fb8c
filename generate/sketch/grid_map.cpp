#include "generate/sketch/grid_map.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

#include "generate/sketch/grid_map_roads.h"
#include "generate/sketch/sketch.h"
#include "generate/errors.h"
#include "geom/grid.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;
using namespace grid_map;

namespace {

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
  for (const RoadPath& road : road_paths(map)) {
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
