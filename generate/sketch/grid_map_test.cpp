// Grid maps (docs/sketch.md, Grid maps): each cell's status becomes the right zone or road, regions become
// exact polygons, road bands one connected network, every mistake one line naming the
// file, line and column, and a map generates a city that validates without gaps.
#include "generate/sketch/grid_map.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "generate/sketch/sketch.h"
#include "generate/errors.h"
#include "generate/parcels/allocation.h"
#include "generate/export/validate.h"
#include "generate/pipeline.h"
#include "geom/measure.h"
#include "geom/polygon_check.h"
#include "tests/test_util.h"

using namespace exacity;
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

ordered_json features_of(const std::string& text) { return grid_map_features(text, "city.grid"); }

std::vector<ordered_json> of_kind(const ordered_json& features, const char* key) {
  std::vector<ordered_json> out;
  for (const auto& f : features)
    if (f["properties"].contains(key)) out.push_back(f);
  return out;
}

geom::Ring ring_of(const ordered_json& positions) {
  geom::Ring r;
  for (const auto& p : positions) r.push_back({p[0].get<double>(), p[1].get<double>()});
  EXPECT_EQ(r.front(), r.back()) << "GeoJSON rings are closed";
  r.pop_back();
  return r;
}

geom::Polygon polygon_of(const ordered_json& geometry) {
  EXPECT_EQ(geometry["type"], "Polygon");
  geom::Polygon p;
  const auto& rings = geometry["coordinates"];
  p.outer = ring_of(rings[0]);
  for (std::size_t i = 1; i < rings.size(); ++i) p.holes.push_back(ring_of(rings[i]));
  return p;
}

geom::Polyline line_of(const ordered_json& geometry) {
  EXPECT_EQ(geometry["type"], "LineString");
  geom::Polyline l;
  for (const auto& p : geometry["coordinates"]) l.push_back({p[0].get<double>(), p[1].get<double>()});
  return l;
}

// Zone polygons by type, each checked to be simple, outer ring counter-clockwise and holes
// clockwise.
std::map<std::string, std::vector<geom::Polygon>> zones_of(const ordered_json& features) {
  std::map<std::string, std::vector<geom::Polygon>> out;
  for (const auto& f : of_kind(features, "zone")) {
    geom::Polygon p = polygon_of(f["geometry"]);
    EXPECT_TRUE(geom::ring_is_simple(p.outer));
    EXPECT_EQ(geom::ring_orientation(p.outer), 1) << "outer rings counter-clockwise";
    for (const auto& h : p.holes) {
      EXPECT_TRUE(geom::ring_is_simple(h));
      EXPECT_EQ(geom::ring_orientation(h), -1) << "holes clockwise";
    }
    out[f["properties"]["zone"].get<std::string>()].push_back(std::move(p));
  }
  return out;
}

double total_area(const std::vector<geom::Polygon>& polygons) {
  double a = 0;
  for (const auto& p : polygons) a += geom::area(p);
  return a;
}

struct Road {
  std::string road_class;
  double width = 0;
  geom::Polyline line;
};

std::vector<Road> roads_of(const ordered_json& features) {
  std::vector<Road> out;
  for (const auto& f : of_kind(features, "road"))
    out.push_back(
        {f["properties"]["road"].get<std::string>(), f["properties"]["width"].get<double>(), line_of(f["geometry"])});
  return out;
}

// How many pieces the roads make, two roads joined where they share a vertex.
int pieces(const std::vector<Road>& roads) {
  std::vector<int> parent(roads.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t a = 0; a < roads.size(); ++a)
    for (std::size_t b = a + 1; b < roads.size(); ++b)
      for (geom::Vec2 p : roads[a].line)
        if (std::find(roads[b].line.begin(), roads[b].line.end(), p) != roads[b].line.end())
          parent[find(static_cast<int>(a))] = find(static_cast<int>(b));
  std::set<int> roots;
  for (std::size_t i = 0; i < roads.size(); ++i) roots.insert(find(static_cast<int>(i)));
  return static_cast<int>(roots.size());
}

bool has_vertex(const Road& road, geom::Vec2 p) {
  return std::find(road.line.begin(), road.line.end(), p) != road.line.end();
}

// The message of the UserError reading `text` throws, checked to be one line starting with
// the file, line and column; "" when it reads.
std::string error_of(const std::string& text) {
  try {
    features_of(text);
  } catch (const UserError& e) {
    std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
    return m;
  }
  return "";
}

void expect_error(const std::string& text, const std::string& at, std::initializer_list<const char*> parts) {
  const std::string m = error_of(text);
  ASSERT_FALSE(m.empty()) << "accepted:\n" << text;
  EXPECT_EQ(m.rfind("city.grid:" + at + ": ", 0), 0u) << "names city.grid:" << at << " first: " << m;
  for (const char* p : parts) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' missing in: " << m;
}

// ---- Whole cities ----------------------------------------------------------------------

std::vector<geom::Polygon> layer_polygons(const fs::path& file) {
  std::ifstream in(file);
  const auto layer = ordered_json::parse(in);
  std::vector<geom::Polygon> out;
  for (const auto& f : layer["features"]) out.push_back(polygon_of(f["geometry"]));
  return out;
}

bool inside(const std::vector<geom::Polygon>& polygons, geom::Vec2 p) {
  for (const auto& poly : polygons) {
    if (geom::winding_number(poly.outer, p) == 0) continue;
    if (std::none_of(poly.holes.begin(), poly.holes.end(),
                     [&](const geom::Ring& h) { return geom::winding_number(h, p) != 0; }))
      return true;
  }
  return false;
}

// Every cell but X is covered by what the city wrote: zones, water or road areas (a road
// cell by a road area), checked at points spread over each cell, its corners' neighbourhoods
// included. `rows` are the map's rows, north first; its south-west corner at `origin`.
void expect_no_gaps(const fs::path& out, const std::vector<std::string>& rows, double cell, geom::Vec2 origin = {}) {
  const auto zones = layer_polygons(out / "vector" / "zones.geojson");
  const auto water = layer_polygons(out / "vector" / "water.geojson");
  const auto roads = layer_polygons(out / "vector" / "road_areas.geojson");
  const int h = static_cast<int>(rows.size());
  int gaps = 0;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < static_cast<int>(rows[r].size()); ++c) {
      const char status = rows[r][c];
      if (status == 'X') continue;
      for (double fx : {0.01, 0.25, 0.5, 0.75, 0.99})
        for (double fy : {0.01, 0.25, 0.5, 0.75, 0.99}) {
          const geom::Vec2 p{origin.x + (c + fx) * cell, origin.y + (h - r - 1 + fy) * cell};
          const bool covered =
              status == '=' ? inside(roads, p) : inside(zones, p) || inside(water, p) || inside(roads, p);
          if (!covered && ++gaps < 5)
            ADD_FAILURE() << "row " << r << " column " << c << " ('" << status << "') uncovered at " << p.x << ", "
                          << p.y;
        }
    }
  EXPECT_EQ(gaps, 0);
}

struct Generated {
  nlohmann::ordered_json report;
  Validation validation;
};

// Writes the map to a fresh folder, generates its city into out/ and validates it again.
Generated generate(const std::string& name, const std::string& text, const fs::path& models = {}) {
  const fs::path dir = testing_util::temp_dir("grid-" + name);
  std::ofstream(dir / "city.grid") << text;
  fs::create_directories(dir / "out");
  GenerateResult result = generate_city(load_sketch(dir / "city.grid", true, models), dir / "out", nullptr);
  return {result.report, validate_output(dir / "out")};
}

fs::path out_of(const std::string& name) { return testing_util::test_dir("grid-" + name) / "out"; }

std::vector<std::string> rows_of(const std::string& text) {
  std::vector<std::string> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != ';' && line.rfind("cell", 0) != 0 && line.rfind("origin", 0) != 0)
      rows.push_back(line);
  return rows;
}

}  // namespace

// ---- Cells to features -----------------------------------------------------------------

TEST(GridMap, EveryStatusCharacterIsItsZoneOrARoad) {
  const ordered_json f = features_of("cell 10\n.XrXcXiX~X\"X=\n");
  auto zones = zones_of(f);
  ASSERT_EQ(zones.size(), 5u);
  EXPECT_EQ(zones["residential"].size(), 2u) << "'.' and 'r' are residential";
  EXPECT_DOUBLE_EQ(total_area(zones["residential"]), 200);
  for (const char* z : {"commercial", "industrial", "water", "park"}) {
    ASSERT_EQ(zones[z].size(), 1u) << z;
    EXPECT_DOUBLE_EQ(total_area(zones[z]), 100) << z;
  }
  EXPECT_EQ(zones["commercial"][0].outer.front().x, 40) << "the fifth column starts 40 m east";
  const auto roads = roads_of(f);
  ASSERT_EQ(roads.size(), 1u) << "X is no feature; = is a road";
  EXPECT_EQ(roads[0].line, (geom::Polyline{{120, 5}, {130, 5}}));
  EXPECT_EQ(roads[0].width, 10);
  // Residential '.' and 'r' next to each other are one region.
  auto merged = zones_of(features_of("cell 10\n.r.\nr.r\n"));
  ASSERT_EQ(merged["residential"].size(), 1u);
  EXPECT_DOUBLE_EQ(total_area(merged["residential"]), 600);
  EXPECT_EQ(merged["residential"][0].outer.size(), 4u) << "one rectangle, not six squares";
}

TEST(GridMap, ARegionWithAHoleAndAnIslandInIt) {
  const ordered_json f = features_of(
      "cell 10\n"
      "ccccc\n"
      "c...c\n"
      "c.c.c\n"
      "c...c\n"
      "ccccc\n");
  auto zones = zones_of(f);
  ASSERT_EQ(zones["commercial"].size(), 2u) << "the ring and the island in it";
  const geom::Polygon& ring = zones["commercial"][0];
  ASSERT_EQ(ring.holes.size(), 1u);
  EXPECT_EQ(ring.outer.size(), 4u);
  EXPECT_DOUBLE_EQ(geom::area(ring), 16 * 100);
  EXPECT_DOUBLE_EQ(geom::signed_area(ring.holes[0]), -9 * 100);
  EXPECT_DOUBLE_EQ(geom::area(zones["commercial"][1]), 100);
  ASSERT_EQ(zones["residential"].size(), 1u);
  EXPECT_EQ(zones["residential"][0].holes.size(), 1u);
  EXPECT_DOUBLE_EQ(geom::area(zones["residential"][0]), 8 * 100);
}

TEST(GridMap, RegionsMeetingAtACornerAreApart) {
  auto zones = zones_of(features_of("cell 5\nir\nri\n"));
  ASSERT_EQ(zones["industrial"].size(), 2u);
  ASSERT_EQ(zones["residential"].size(), 2u);
  for (const auto& [type, polygons] : zones)
    for (const auto& p : polygons) {
      EXPECT_DOUBLE_EQ(geom::area(p), 25) << type;
      EXPECT_TRUE(p.holes.empty());
    }
  // A region whose holes meet at a corner: two square holes touching, not one ring
  // through the corner twice; the region itself stays one polygon.
  auto holed =
      zones_of(features_of("cell 10\n"
                           "rrrr\n"
                           "rrcr\n"
                           "rcrr\n"
                           "rrrr\n"));
  ASSERT_EQ(holed["residential"].size(), 1u);
  ASSERT_EQ(holed["residential"][0].holes.size(), 2u);
  for (const auto& h : holed["residential"][0].holes) EXPECT_DOUBLE_EQ(geom::signed_area(h), -100);
  EXPECT_DOUBLE_EQ(geom::area(holed["residential"][0]), 14 * 100);
  EXPECT_EQ(holed["commercial"].size(), 2u);
  // A region meeting itself at a corner round a hole of other cells.
  auto pinched =
      zones_of(features_of("cell 10\n"
                           "rr.\n"
                           "rcr\n"
                           ".rr\n"));
  ASSERT_EQ(pinched["residential"].size(), 1u);
  EXPECT_DOUBLE_EQ(geom::area(pinched["residential"][0]), 8 * 100);
}

TEST(GridMap, AreasAreExactOnARandomMap) {
  // Every region's area is its cells, every ring simple and rightly turned, whatever the
  // cells (zones_of checks the rings).
  std::uint64_t state = 12345;
  auto next = [&] { return (state = state * 6364136223846793005ULL + 1442695040888963407ULL) >> 33; };
  const std::string statuses = ".rci~\"=X";
  std::string text = "cell 3\n";
  std::map<std::string, int> cells;
  const std::map<char, std::string> zone_of{{'.', "residential"}, {'r', "residential"}, {'c', "commercial"},
                                            {'i', "industrial"},  {'~', "water"},       {'"', "park"}};
  for (int r = 0; r < 40; ++r) {
    for (int c = 0; c < 40; ++c) {
      const char s = statuses[next() % (r < 20 ? 3 : statuses.size())];  // the north half in big regions
      text += s;
      if (zone_of.count(s)) ++cells[zone_of.at(s)];
    }
    text += "\n";
  }
  auto zones = zones_of(features_of(text));
  for (const auto& [type, n] : cells) EXPECT_DOUBLE_EQ(total_area(zones[type]), n * 9.0) << type;
}

TEST(GridMap, AStraightRunIsOneRoadDownItsMiddle) {
  const auto roads = roads_of(features_of("cell 10\nrrrrr\n=====\nrrrrr\n"));
  ASSERT_EQ(roads.size(), 1u);
  EXPECT_EQ(roads[0].line, (geom::Polyline{{0, 15}, {50, 15}}));
  EXPECT_EQ(roads[0].width, 10);
  EXPECT_EQ(roads[0].road_class, "local");
  const auto north_south = roads_of(features_of("cell 10\nr=r\nr=r\nr=r\n"));
  ASSERT_EQ(north_south.size(), 1u);
  EXPECT_EQ(north_south[0].line, (geom::Polyline{{15, 30}, {15, 0}}));
}

TEST(GridMap, ABandTwoCellsTallIsOneRoadTwiceAsWide) {
  const auto roads = roads_of(features_of("cell 10\nrrrrrr\n======\n======\nrrrrrr\n"));
  ASSERT_EQ(roads.size(), 1u);
  EXPECT_EQ(roads[0].line, (geom::Polyline{{0, 20}, {60, 20}}));
  EXPECT_EQ(roads[0].width, 20);
  EXPECT_EQ(roads[0].road_class, "main");
  const auto avenue = roads_of(features_of("cell 12.5\nr==r\nr==r\nr==r\n"));
  ASSERT_EQ(avenue.size(), 1u);
  EXPECT_EQ(avenue[0].width, 25);
  EXPECT_EQ(avenue[0].road_class, "highway");
}

TEST(GridMap, ATJoinsItsStemToTheBarsCentreLine) {
  const auto roads =
      roads_of(features_of("cell 10\n"
                           "=====\n"
                           "rr=rr\n"
                           "rr=rr\n"));
  ASSERT_EQ(roads.size(), 2u);
  EXPECT_EQ(roads[0].line, (geom::Polyline{{0, 25}, {25, 25}, {50, 25}})) << "the meeting is a vertex of the bar";
  EXPECT_EQ(roads[1].line, (geom::Polyline{{25, 25}, {25, 0}})) << "the stem runs on to the bar's centre line";
  EXPECT_EQ(pieces(roads), 1);
}

TEST(GridMap, ACrossMeetsAtAVertexOfBoth) {
  const auto roads =
      roads_of(features_of("cell 10\n"
                           "rr=rr\n"
                           "rr=rr\n"
                           "=====\n"
                           "rr=rr\n"
                           "rr=rr\n"));
  ASSERT_EQ(roads.size(), 2u);
  for (const Road& r : roads) {
    EXPECT_TRUE(has_vertex(r, {25, 25}));
    EXPECT_EQ(r.width, 10);
  }
  EXPECT_EQ(pieces(roads), 1);
}

TEST(GridMap, StreetsOfTwoWidthsMakeOneNetwork) {
  // A two-cell avenue, a street crossing it, one ending on it (a T) and one turning off its
  // end (an L), and a ring of streets round the north: one piece.
  const std::string map =
      "cell 10\n"
      "==========\n"
      "=rr=rrrr.=\n"
      "=rr=rrrr.=\n"
      "==========\n"
      "==========\n"
      "rrr=rr=rr=\n"
      "rrr=rr=rr=\n";
  const auto roads = roads_of(features_of(map));
  EXPECT_EQ(pieces(roads), 1);
  int avenues = 0;
  for (const Road& r : roads) {
    if (r.width == 20) {
      ++avenues;
      EXPECT_EQ(r.line.front(), (geom::Vec2{5, 30})) << "ends on the western street's centre line";
      EXPECT_EQ(r.line.back(), (geom::Vec2{95, 30})) << "ends on the eastern street's centre line";
    } else {
      EXPECT_EQ(r.width, 10);
    }
  }
  EXPECT_EQ(avenues, 1);
  // A staircase of road cells is one network too.
  EXPECT_EQ(pieces(roads_of(features_of("cell 10\n=rrr\n==rr\nr==r\nrr==\n"))), 1);
}

TEST(GridMap, ASquareOfRoadCellsIsARoadAndAStubInAWideRoadIsNone) {
  const auto square = roads_of(features_of("cell 10\nrrrr\nr==r\nr==r\nrrrr\n"));
  ASSERT_EQ(square.size(), 1u);
  EXPECT_EQ(square[0].width, 20);
  // A plus of two bands two cells wide: their ends one cell out are not roads of their own.
  const auto plus = roads_of(features_of("cell 10\nr==r\n====\n====\nr==r\n"));
  ASSERT_EQ(plus.size(), 2u);
  for (const Road& r : plus) EXPECT_EQ(r.width, 20);
  EXPECT_EQ(pieces(plus), 1);
}

// The pieces road cells make, joined side to side.
int road_cell_pieces(const std::vector<std::string>& rows) {
  std::set<std::pair<int, int>> seen;
  int pieces = 0;
  for (int r = 0; r < static_cast<int>(rows.size()); ++r)
    for (int c = 0; c < static_cast<int>(rows[r].size()); ++c) {
      if (rows[r][c] != '=' || seen.count({r, c})) continue;
      ++pieces;
      std::vector<std::pair<int, int>> stack{{r, c}};
      seen.insert({r, c});
      while (!stack.empty()) {
        auto [a, b] = stack.back();
        stack.pop_back();
        for (auto [x, y] : {std::pair{a + 1, b}, std::pair{a - 1, b}, std::pair{a, b + 1}, std::pair{a, b - 1}})
          if (x >= 0 && x < static_cast<int>(rows.size()) && y >= 0 && y < static_cast<int>(rows[x].size()) &&
              rows[x][y] == '=' && seen.insert({x, y}).second)
            stack.push_back({x, y});
      }
    }
  return pieces;
}

TEST(GridMap, RoadCellsJoinedSideBySideMakeOnePieceOfRoads) {
  // An avenue narrowing from two cells to one: two bands side by side, joined by a
  // connector one cell wide.
  const auto narrowing = roads_of(features_of("cell 10\nrrrrrrrrrr\n==========\n=====rrrrr\nrrrrrrrrrr\n"));
  EXPECT_EQ(pieces(narrowing), 1);
  // A blob of road cells, and a street leaving it off its middle.
  EXPECT_EQ(pieces(roads_of(features_of("cell 10\nr\"crc\nr====\nr====\n.====\nr====\nc===X\nc===r\n====c\n"))), 1);
  // Random maps: as many pieces of roads as of road cells, whatever the cells.
  std::uint64_t state = 99;
  auto next = [&] { return (state = state * 6364136223846793005ULL + 1442695040888963407ULL) >> 33; };
  for (int map = 0; map < 60; ++map) {
    const int w = 3 + static_cast<int>(next() % 15), h = 3 + static_cast<int>(next() % 15);
    const int roads = static_cast<int>(next() % 70);
    std::vector<std::string> rows(h, std::string(w, 'r'));
    for (auto& row : rows)
      for (char& c : row) c = static_cast<int>(next() % 100) < roads ? '=' : "rci~\".X"[next() % 7];
    std::string text = "cell 10\n";
    for (const auto& row : rows) text += row + "\n";
    if (text.find_first_not_of("X\n", 8) == std::string::npos) continue;  // all blocked: refused
    const auto got = roads_of(features_of(text));
    EXPECT_EQ(pieces(got), road_cell_pieces(rows)) << text;
    for (const Road& r : got) EXPECT_GE(r.line.size(), 2u);
  }
}

TEST(GridMap, OriginShiftsEverything) {
  const std::string map = "rr=rr\n=====\nc~=\"i\n";
  const ordered_json at_zero = features_of("cell 10\n" + map);
  const ordered_json shifted = features_of("cell 10\norigin 1000.5 -250\n" + map);
  ASSERT_EQ(at_zero.size(), shifted.size());
  for (std::size_t i = 0; i < at_zero.size(); ++i) {
    const auto& a = at_zero[i]["geometry"]["coordinates"];
    const auto& b = shifted[i]["geometry"]["coordinates"];
    const bool line = at_zero[i]["geometry"]["type"] == "LineString";
    const auto& pa = line ? a : a[0];
    const auto& pb = line ? b : b[0];
    ASSERT_EQ(pa.size(), pb.size());
    for (std::size_t k = 0; k < pa.size(); ++k) {
      EXPECT_EQ(pb[k][0].get<double>(), pa[k][0].get<double>() + 1000.5);
      EXPECT_EQ(pb[k][1].get<double>(), pa[k][1].get<double>() - 250);
    }
  }
  // A negative origin, and the south-west corner is where it says.
  auto zones = zones_of(features_of("cell 10\norigin -500 -300\nrr\nrr\n"));
  EXPECT_EQ(zones["residential"][0].outer, (geom::Ring{{-500, -280}, {-500, -300}, {-480, -300}, {-480, -280}}));
}

TEST(GridMap, CommentsBlankLinesAndCrlfAreAccepted) {
  const ordered_json unix_map = features_of("; a town\ncell 10\n\n; the rows\nr=r\n\nr=r\n");
  const ordered_json dos_map = features_of("; a town\r\ncell 10\r\n\r\n; the rows\r\nr=r\r\n\r\nr=r\r\n");
  EXPECT_EQ(unix_map.dump(), dos_map.dump());
  EXPECT_EQ(unix_map.size(), 3u);
  EXPECT_EQ(unix_map[0]["properties"]["grid_cell"], "city.grid:5:1") << "lines count from 1, comments included";
}

TEST(GridMap, ALargeMapIsReadWhole) {
  // 300 x 300 cells: a street every sixth row and column, zones between.
  std::string text = "cell 10\n";
  for (int r = 0; r < 300; ++r) {
    for (int c = 0; c < 300; ++c) text += r % 6 == 5 || c % 6 == 5 ? '=' : "rci\"~."[(r / 6 * 7 + c / 6) % 6];
    text += "\n";
  }
  const ordered_json f = features_of(text);
  const auto roads = roads_of(f);
  EXPECT_EQ(roads.size(), 100u) << "50 streets each way";
  EXPECT_EQ(pieces(roads), 1);
  EXPECT_EQ(of_kind(f, "zone").size(), 2500u);
}

// ---- Mistakes --------------------------------------------------------------------------

TEST(GridMapErrors, RowsOfUnequalLength) {
  expect_error("cell 10\nrrrr\nrrr\n", "3:4", {"3 cells long", "line 2", "make every row 4 cells long"});
  expect_error("cell 10\nrrrr\nrrrrrr\n", "3:5", {"6 cells long"});
}

TEST(GridMapErrors, UnknownCharacterWithItsColumn) {
  expect_error("cell 10\nrrrr\nrrqr\n", "3:3", {"'q' is not a cell", ". r c i = ~ \" X"});
  expect_error("cell 10\nrr\tr\n", "2:3", {"a tab"});
  expect_error("cell 10\nrrR\n", "2:3", {"'R'"});
  expect_error("cell 10\nrr\xc3\xa9\n", "2:3", {"0xC3"});
  // Trailing spaces are an error naming the first; CRLF is not.
  expect_error("cell 10\r\nrrr  \r\nrrr\r\n", "2:4", {"a space"});
}

TEST(GridMapErrors, MissingRepeatedOrLateHeader) {
  expect_error("rrr\nrrr\n", "1:1", {"no \"cell METRES\" line", "cell 10"});
  expect_error("; only a comment\norigin 0 0\nrrr\n", "3:1", {"no \"cell METRES\" line"});
  expect_error("cell 10\ncell 20\nrrr\n", "2:1", {"a second \"cell\"", "line 1", "keep one"});
  expect_error("cell 10\norigin 0 0\norigin 5 5\nrrr\n", "3:1", {"a second \"origin\"", "line 2"});
  expect_error("cell 10\nrrr\norigin 5 5\n", "3:1", {"\"origin\" after the rows", "line 2", "above"});
  expect_error("rrr\ncell 10\n", "2:1", {"\"cell\" after the rows"});
  expect_error("cell 10\nsize 30\nrrr\n", "2:1", {"unknown header \"size\""});
  expect_error("cell10\nrrr\n", "1:5", {"space after \"cell\"", "\"cell 10\""});
  expect_error("origin5 5\ncell 10\nrrr\n", "1:7", {"\"origin 0 0\""});
}

TEST(GridMapErrors, BadNumbers) {
  expect_error("cell ten\nrrr\n", "1:6", {"\"ten\" is not a number"});
  expect_error("cell 10m\nrrr\n", "1:6", {"\"10m\" is not a number"});
  expect_error("cell -5\nrrr\n", "1:6", {"positive"});
  expect_error("cell 0\nrrr\n", "1:6", {"positive"});
  expect_error("cell inf\nrrr\n", "1:6", {"not a finite number"});
  expect_error("cell 1e999\nrrr\n", "1:6", {"not a finite number"});
  expect_error("cell nan\nrrr\n", "1:6", {"not a finite number"});
  expect_error("cell\nrrr\n", "1:5", {"needs the cell size"});
  expect_error("cell 10 20\nrrr\n", "1:9", {"one value too many"});
  expect_error("cell 10\norigin 5\nrrr\n", "2:9", {"needs the map's south-west corner"});
  expect_error("cell 10\norigin 5 north\nrrr\n", "2:10", {"\"north\" is not a number"});
  // A cell is 1 to 500 m; a road at most 500 m wide.
  expect_error("cell 1e6\nr=r\n", "1:6", {"over 500 m", "1 to 500 m"});
  expect_error("cell 0.01\nr=r\n", "1:6", {"under 1 m"});
  expect_error("cell 300\nrrr\n===\n===\n", "3:1", {"2 cells across", "500 m"});
  expect_error("cell 100\norigin 1e10 0\nrrr\n", "2:1", {"beyond the 1e10 m"});
  std::string huge = "cell 500\n";
  for (int r = 0; r < 60; ++r) huge += std::string(60, 'r') + "\n";
  expect_error(huge, "1:6", {"75000 blocks", "smaller"});
  std::string vast = "cell 1\n";
  for (int r = 0; r < 2001; ++r) vast += std::string(2000, r % 7 ? 'r' : '=') + "\n";
  expect_error(vast, "2002:1", {"over 4000000 cells", "fewer, larger cells"});
}

// Each region is a zone polygon and a block (or park face) at least, however small its area:
// a checkerboard of 1 m cells is 102,400 one-cell regions, which the blocks counted from the
// zones' area (9 of them) let through to an exact map of gigabytes.
TEST(GridMapErrors, MoreSeparateRegionsThanBlocksOneRunBuilds) {
  std::string board = "cell 1\n";
  for (int r = 0; r < 320; ++r) {
    for (int c = 0; c < 320; ++c) board += (r + c) % 2 ? 'r' : '"';
    board += "\n";
  }
  // The 60,001st region in reading order: row 187 (file line 189), column 161.
  expect_error(board, "189:161", {"102400 separate regions", "more than the 60000 one run builds", "smaller map"});
}

TEST(GridMapErrors, NoRowsOrNothingButBlockedCells) {
  expect_error("", "1:1", {"no grid map here"});
  expect_error("; just a comment\n\n", "1:1", {"no grid map here"});
  expect_error("cell 10\n", "2:1", {"no rows"});
  expect_error("cell 10", "2:1", {"no rows"});
  expect_error("cell 10\n; nothing\n", "3:1", {"no rows"});
  expect_error("cell 10\nXXX\nXXX\n", "2:1", {"every cell is X"});
}

TEST(GridMapErrors, AMissingFileOrGridIsOneLine) {
  const fs::path dir = testing_util::temp_dir("grid-missing");
  try {
    load_sketch(dir / "none.grid");
    ADD_FAILURE() << "read a missing file";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
  fs::create_directories(dir / "folder.grid");
  try {
    load_sketch(dir / "folder.grid");
    ADD_FAILURE() << "read a folder";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("(it is a folder)"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "sketch.geojson")
      << R"({"type": "FeatureCollection", "exacity": {"grid": "none.grid"}, "features": []})";
  try {
    load_sketch(dir / "sketch.geojson");
    ADD_FAILURE() << "read a missing grid map";
  } catch (const UserError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("\"exacity\".grid"), std::string::npos) << m;
    EXPECT_NE(m.find("no such file"), std::string::npos) << m;
  }
}

// ---- Whole cities ----------------------------------------------------------------------

namespace {

// 20 x 20 cells of 10 m: a two-cell avenue, streets, a park, a pond, blocked cells.
const std::string kSmallTown =
    "cell 10\n"
    "XXXrrrr=rrrrrr=\"\"\"\"\"\n"
    "XXrrrrr=rrrrrr=\"\"~~\"\n"
    "rrrrrrr=rrrrrr=\"\"~~\"\n"
    "rrrrrrr=rrrrrr=\"\"\"\"\"\n"
    "====================\n"
    "ccccccc=cccccc=rrrrr\n"
    "ccccccc=cccccc=rrrrr\n"
    "ccccccc=cccccc=rrrrr\n"
    "ccccccc=cccccc=rrrrr\n"
    "====================\n"
    "====================\n"
    "iiiiiii=cccccc=rrrrr\n"
    "iiiiiii=cccccc=rrrrr\n"
    "iiiiiii=cccccc=rrrrr\n"
    "iiiiiii=cccccc=rrrrr\n"
    "iiiiiii=============\n"
    "iiiiiii=......=rrrrr\n"
    "iiiiiii=......=rrrrX\n"
    "iiiiiii=......=rrrXX\n"
    "iiiiiii=......=rrXXX\n";

}  // namespace

TEST(GridMapCity, ASmallTownGeneratesValidatesAndLeavesNoGaps) {
  const Generated g = generate("town", kSmallTown);
  EXPECT_TRUE(g.report["validation"]["ok"].get<bool>()) << g.report["validation"];
  EXPECT_TRUE(g.validation.ok()) << (g.validation.problems.empty() ? "" : g.validation.problems[0]);
  EXPECT_TRUE(g.report["empty_zones"].empty()) << g.report["empty_zones"];
  EXPECT_GT(g.report["counts"]["lots"].get<int>(), 15);  // 19 with this seed's draws
  EXPECT_EQ(g.report["road_network"]["regions"], 0) << "streets only: no grown roads";
  expect_no_gaps(out_of("town"), rows_of(kSmallTown), 10);
  // OUT/sketch.geojson holds the sketch read, so validate and render read it too.
  const Sketch copy = load_sketch(out_of("town") / "sketch.geojson", false);
  EXPECT_EQ(copy.zones.size(), load_sketch(out_of("town").parent_path() / "city.grid").zones.size());
  EXPECT_EQ(copy.zone_settings.at(ZoneType::Residential).roads.layout->name(), "streets");
}

TEST(GridMapCity, AMapAllOfRoad) {
  const std::string map = "cell 10\n======\n======\n======\n======\n";
  const Generated g = generate("all-road", map);
  EXPECT_TRUE(g.validation.ok()) << (g.validation.problems.empty() ? "" : g.validation.problems[0]);
  EXPECT_EQ(g.report["counts"]["roads"], 1);
  expect_no_gaps(out_of("all-road"), rows_of(map), 10);
}

TEST(GridMapCity, MapsOfOneCell) {
  const Generated zone = generate("one-zone", "cell 10\nr\n");
  EXPECT_TRUE(zone.validation.ok());
  ASSERT_EQ(zone.report["empty_zones"].size(), 1u) << "no street reaches it";
  EXPECT_EQ(zone.report["empty_zones"][0]["grid_cell"],
            (testing_util::test_dir("grid-one-zone") / "city.grid").string() + ":2:1");
  const Generated road = generate("one-road", "cell 10\n=\n");
  EXPECT_TRUE(road.validation.ok());
  EXPECT_EQ(road.report["counts"]["roads"], 1);
  expect_no_gaps(out_of("one-road"), {"="}, 10);
  const Generated dot = generate("single-road", "cell 10\nrrr\nr=r\nrrr\n");
  EXPECT_TRUE(dot.validation.ok());
  expect_no_gaps(out_of("single-road"), {"rrr", "r=r", "rrr"}, 10);
}

TEST(GridMapCity, TinyAndLargeCellsAndANegativeOrigin) {
  const std::string map = "rrr=rrr\nrrr=rrr\n=======\nccc=ccc\n";
  for (const char* header : {"cell 1\norigin -12345.5 -678\n", "cell 3.3\norigin -1e6 2e6\n", "cell 120\n"}) {
    const std::string text = header + map;
    const std::string name = "cells-" + std::to_string(std::hash<std::string>()(header) % 1000);
    const Generated g = generate(name, text);
    EXPECT_TRUE(g.validation.ok()) << header << (g.validation.problems.empty() ? "" : g.validation.problems[0]);
    const Sketch s = load_sketch(out_of(name).parent_path() / "city.grid");
    const double cell = s.roads[0].width;  // one cell, as rounded to 1/512 m
    double west = 1e300, south = 1e300;
    for (const auto& z : s.zones)
      for (const auto& v : z.polygons[0].outer) west = std::min(west, v.x), south = std::min(south, v.y);
    expect_no_gaps(out_of(name), rows_of(map), cell, {west, south});
  }
}

TEST(GridMapCity, ASketchNamingAGridMapAddsItsOwnZonesOverIt) {
  const fs::path dir = testing_util::temp_dir("grid-in-sketch");
  std::ofstream(dir / "town.grid") << kSmallTown;
  // A park drawn over the north-east blocks: it wins there, as a later zone does.
  std::ofstream(dir / "sketch.geojson") << R"({"type": "FeatureCollection",
    "exacity": {"seed": 3, "grid": "town.grid", "zones": {"commercial": {"lot_width": [15, 30]}}},
    "features": [
      {"type": "Feature", "properties": {"zone": "park"},
       "geometry": {"type": "Polygon", "coordinates": [[[150, 140], [200, 140], [200, 200], [150, 200]]]}}]})";
  const Sketch sketch = load_sketch(dir / "sketch.geojson");
  const Sketch grid = load_sketch(dir / "town.grid");
  ASSERT_EQ(sketch.zones.size(), grid.zones.size() + 1);
  EXPECT_EQ(sketch.zones.back().type, ZoneType::Park);
  EXPECT_EQ(sketch.zones.back().index, static_cast<int>(grid.zones.size() + grid.roads.size()));
  EXPECT_EQ(sketch.roads.size(), grid.roads.size());
  EXPECT_EQ(sketch.seed, 3u);
  EXPECT_EQ(sketch.zone_settings.at(ZoneType::Residential).roads.layout->name(), "streets");
  EXPECT_EQ(sketch.zone_settings.at(ZoneType::Commercial).roads.layout->name(), "streets")
      << "set where the sketch says nothing of it";
  const LotLayoutChoice& lots = *sketch.zone_settings.at(ZoneType::Commercial).lots.layout;
  EXPECT_EQ(dynamic_cast<const AllocationChoice&>(lots).settings().lot_width.max, 30);
  fs::create_directories(dir / "out");
  const GenerateResult result = generate_city(sketch, dir / "out", nullptr);
  EXPECT_TRUE(result.valid) << result.report["validation"];
  EXPECT_TRUE(validate_output(dir / "out").ok());
  // The park covers the north-east corner in the written zones.
  const auto parks = [&] {
    std::vector<geom::Polygon> out;
    const auto layer = ordered_json::parse(std::ifstream(dir / "out" / "vector" / "zones.geojson"));
    for (const auto& f : layer["features"])
      if (f["properties"]["zone"] == "park") out.push_back(polygon_of(f["geometry"]));
    return out;
  }();
  EXPECT_TRUE(inside(parks, {190, 145})) << "drawn over residential cells";
  // A mistake in the sketch's own features names them as the user wrote them.
  std::ofstream(dir / "bad.geojson") << R"({"type": "FeatureCollection", "exacity": {"grid": "town.grid"},
    "features": [{"type": "Feature", "properties": {"zone": "parkk"},
                  "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}}]})";
  try {
    load_sketch(dir / "bad.geojson");
    ADD_FAILURE() << "read a bad zone type";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("features[0]"), std::string::npos) << e.what();
  }
  // A layout the sketch sets stands.
  std::ofstream(dir / "growth.geojson") << R"({"type": "FeatureCollection",
    "exacity": {"grid": "town.grid", "zones": {"residential": {"layout": "growth"}}}, "features": []})";
  EXPECT_EQ(load_sketch(dir / "growth.geojson").zone_settings.at(ZoneType::Residential).roads.layout->name(), "growth");
}

TEST(GridMapCity, ModelsGivenInPlaceOfTheSketchsOwn) {
  const fs::path library = fs::path(EXACITY_SOURCE_DIR) / "examples" / "models" / "library.json";
  const fs::path dir = testing_util::temp_dir("grid-models");
  std::ofstream(dir / "city.grid") << "cell 10\nrrr\n===\nccc\n";
  const Sketch sketch = load_sketch(dir / "city.grid", true, library);
  EXPECT_EQ(sketch.models, fs::absolute(library).lexically_normal());
  EXPECT_NE(sketch.geojson.find("library.json"), std::string::npos) << "the copy names it, for render";
  // On a GeoJSON sketch it replaces the sketch's own.
  std::ofstream(dir / "sketch.geojson") << R"({"type": "FeatureCollection", "exacity": {"models": "elsewhere.json"},
    "features": [{"type": "Feature", "properties": {"zone": "park"},
                  "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 0]]]}}]})";
  EXPECT_EQ(load_sketch(dir / "sketch.geojson", true, library).models, fs::absolute(library).lexically_normal());
  EXPECT_EQ(load_sketch(dir / "sketch.geojson").models, dir / "elsewhere.json");
}
