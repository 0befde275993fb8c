// The split grammar: the file format and its errors, the parameter mappings, the
// layout tree, and the grammar layout end to end (no two roads side by side on a border).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "generate/errors.h"
#include "generate/export/geojson.h"
#include "generate/layout/grammar.h"
#include "generate/pipeline.h"
#include "generate/export/validate.h"
#include "tests/test_util.h"

using namespace exacity;
using geom::Vec2;

namespace {

// The message of the UserError parsing `text` throws, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_grammar(text, "city.grammar");
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

const std::string kTown = "1 Town 4 Inner,0.1,0.1,0.9,0.1,0.9,0.9,0.1,0.9\n";

double leaf_area(const std::vector<GrammarLeaf>& leaves) {
  double sum = 0;
  for (const auto& l : leaves) sum += std::abs(geom::signed_area(l.corners));
  return sum;
}

}  // namespace

TEST(GrammarFile, EveryMistakeNamesTheFileAndLine) {
  struct Case {
    std::string text, where, what;
  };
  const std::vector<Case> cases = {
      {kTown + "1 Inner 4\n", "city.grammar:2:", "expected WEIGHT LEFT N CHILD"},
      {kTown + "heavy Inner 4 Park,0,0,1,0,1,1,0,1\n", "city.grammar:2:", "weight \"heavy\""},
      {kTown + "-1 Inner 4 Park,0,0,1,0,1,1,0,1\n", "city.grammar:2:", "weight \"-1\""},
      {kTown + "1 Inner 5 Park,0,0,1,0,1,1,0,1\n", "city.grammar:2:", "must be 3 (a triangle) or 4"},
      {kTown + "1 Inner 4 Park,0,0,1,0,1,1,0\n", "city.grammar:2:", "has 7 values"},
      {kTown + "1 Inner 4 Park,0,0,1,0,1,x,0,1\n", "city.grammar:2:", "not a pair of numbers"},
      {kTown + "\n# a comment\n1 Inner 4 Park,0,0,1.5,0,1,1,0,1\n", "city.grammar:4:", "outside the parent's parameter space"},
      {kTown + "0 Inner 4 Park,0,0,1,0,1,1,0,1\n0 Inner 4 Residential,0,0,1,0,1,1,0,1\n", "city.grammar:2:", "summing to 0"},
      {kTown + "1 Inner 4 Shop,0,0,1,0,1,1,0,1\n", "city.grammar:2:", "\"Shop\" has no rule and is no terminal"},
      {kTown + "1 Inner 4 Lot,0,0,1,0,0,1\n1 Lot 4 Park,0,0,1,0,1,1,0,1\n", "city.grammar:2:", "child Lot has 3 corners"},
      {"1 Inner 4 Park,0,0,1,0,1,1,0,1\n", "city.grammar:1:", "no rule for Town"},
  };
  for (const Case& c : cases) {
    const std::string m = error_of(c.text);
    EXPECT_EQ(m.rfind(c.where, 0), 0u) << c.text << " -> " << m;
    EXPECT_NE(m.find(c.what), std::string::npos) << c.text << " -> " << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  EXPECT_EQ(error_of(kTown + "1 Inner 4 Residential_Dense,0,0,1,0,1,1,0,1 Commercial_Sparse,0,0,1,0,0,1 "
                             "Park,0,0,1,0,1,1,0,1 Side_Road,0,0,1,0,1,1,0,1 Road_Intersection,0,0,1,0,0,1\n"),
            "");
}

TEST(GrammarFile, TerminalNamesAreAZoneAndDensityARoadOrAPark) {
  Terminal t;
  ASSERT_TRUE(parse_terminal("Industrial_Sparse", t));
  EXPECT_EQ(t.kind, Terminal::Land);
  EXPECT_EQ(t.type, ZoneType::Industrial);
  EXPECT_EQ(t.density, "sparse");
  ASSERT_TRUE(parse_terminal("Road_Intersection", t));
  EXPECT_EQ(t.kind, Terminal::Road);
  ASSERT_TRUE(parse_terminal("Park", t));
  EXPECT_EQ(t.kind, Terminal::Park);
  EXPECT_FALSE(parse_terminal("Residential_Tall", t));
  EXPECT_FALSE(parse_terminal("_Dense", t));
}

TEST(GrammarMapping, BilinearOverAQuadAndAffineOverATriangle) {
  // u along the first edge, v along the second.
  const std::vector<Vec2> quad{{0, 0}, {8, 0}, {8, 4}, {0, 4}};
  EXPECT_EQ(map_corner(quad, {0.5, 0.5}), (Vec2{4, 2}));
  EXPECT_EQ(map_corner(quad, {0.25, 1}), (Vec2{2, 4}));
  // A quad that is no parallelogram: (u, v) = (0.5, 0.5) is the mean of the corners.
  const std::vector<Vec2> kite{{0, 0}, {8, 0}, {12, 8}, {0, 4}};
  EXPECT_EQ(map_corner(kite, {0.5, 0.5}), (Vec2{5, 3}));
  EXPECT_EQ(map_corner(kite, {1, 0.5}), (Vec2{10, 4}));
  // p = a + u(b - a) + v(c - a).
  const std::vector<Vec2> tri{{1, 1}, {9, 1}, {1, 5}};
  EXPECT_EQ(map_corner(tri, {0.25, 0.5}), (Vec2{3, 3}));
  EXPECT_EQ(map_corner(tri, {0, 1}), (Vec2{1, 5}));
}

TEST(GrammarTree, ARuleSetThatTilesItsParentFillsTheRootExactly) {
  // Halves with a road between them, the halves in quarters, one triangle pair: every
  // child's corners are dyadic, so the doubles add up exactly.
  const Grammar g = parse_grammar(
      "1 Town 4 Half,0,0,0.375,0,0.375,1,0,1 Road,0.375,0,0.375,1,0.625,1,0.625,0 Half,0.625,0,1,0,1,1,0.625,1\n"
      "1 Half 4 Residential,0,0,1,0,1,0.5,0,0.5 Corner,0,0.5,1,0.5,0,1 Park,1,0.5,1,1,0,1\n"
      "1 Corner 3 Commercial_Dense,0,0,0.5,0,0,0.5 Road,0.5,0,0,0.5,0,1,1,0\n",
      "tiles.grammar");
  const std::vector<std::vector<Vec2>> roots{{{0, 0}, {64, 0}, {64, 32}, {0, 32}}, {{64, 0}, {128, 32}, {64, 32}}};
  auto leaves = grow_layout(g, roots, 8, 0, 1);
  EXPECT_EQ(leaf_area(leaves), 64 * 32 + 64 * 32 / 2.0);
  EXPECT_EQ(leaves.size(), 1u /*road*/ + 2 * (1 + 1 + 2) + 1 /*the triangle root has no rule: a leaf*/);
}

TEST(GrammarTree, ASelfRecursiveGrammarStopsAtItsDepth) {
  const Grammar g = parse_grammar("1 Town 4 Town,0,0,0.5,0,0.5,1,0,1 Town,0.5,0,1,0,1,1,0.5,1\n", "self.grammar");
  for (int depth : {1, 3, 8}) {
    auto leaves = grow_layout(g, {{{0, 0}, {256, 0}, {256, 256}, {0, 256}}}, depth, 0, 7);
    EXPECT_EQ(leaves.size(), 1u << depth);
    for (const auto& l : leaves) EXPECT_EQ(l.depth, depth);
    EXPECT_EQ(leaf_area(leaves), 256 * 256);
  }
  // And below the smallest area a node is split no further.
  auto leaves = grow_layout(g, {{{0, 0}, {256, 0}, {256, 256}, {0, 256}}}, 32, 256 * 256 / 16.0 + 1, 7);
  EXPECT_EQ(leaves.size(), 16u);
}

TEST(GrammarTree, ATreeGrowingPastTheBlocksOneRunBuildsIsRefusedAsItGrows) {
  // Four towns and two roads between them at each step: 9 deep, 262,144 towns and 174,762
  // roads, down to pieces of a ten-thousandth of a square metre. The pieces are counted as
  // they are made and the tree refused at 60,000, naming the settings that bound it.
  const Grammar g = parse_grammar(
      "1 Town 4 Town,0,0,0.5,0,0.5,0.5,0,0.5 Town,0.5,0,1,0,1,0.5,0.5,0.5 Town,0.5,0.5,1,0.5,1,1,0.5,1 "
      "Town,0,0.5,0.5,0.5,0.5,1,0,1 Road,0.45,0,0.55,0,0.55,1,0.45,1 Road,0,0.45,1,0.45,1,0.55,0,0.55\n",
      "split.grammar");
  try {
    grow_layout(g, {{{0, 0}, {600, 0}, {600, 600}, {0, 600}}}, 9, 0.0001, 1);
    ADD_FAILURE() << "grown";
  } catch (const exacity::UserError& e) {
    EXPECT_EQ(std::string(e.what()),
              "split.grammar: the grammar grows more than 60000 pieces (blocks and roads) in one region, the blocks one "
              "run builds, at \"grammar_depth\" 9 and \"min_block_area\" 0.0001; lower \"grammar_depth\" or raise "
              "\"min_block_area\"");
  }
  // Seven deep it stays under: 16,384 towns and 10,922 roads.
  EXPECT_EQ(grow_layout(g, {{{0, 0}, {600, 0}, {600, 600}, {0, 600}}}, 7, 0.0001, 1).size(), 16384u + 2 * 5461u);
}

TEST(GrammarRoots, TrianglesPairIntoQuadsWhereTheyMakeARectangle) {
  auto roots = layout_roots({{{0, 0}, {300, 0}, {300, 200}, {0, 200}}, {}});
  ASSERT_EQ(roots.size(), 1u);
  EXPECT_EQ(roots[0].size(), 4u);
  EXPECT_EQ(std::abs(geom::signed_area(roots[0])), 60000);
  // An L: its roots cover it exactly, each counter-clockwise from its longest edge.
  const geom::Polygon l{{{0, 0}, {400, 0}, {400, 100}, {100, 100}, {100, 300}, {0, 300}}, {}};
  double sum = 0;
  for (const auto& r : layout_roots(l)) {
    EXPECT_GT(geom::signed_area(r), 0);
    for (std::size_t i = 1; i < r.size(); ++i)
      EXPECT_GE(std::hypot(r[1].x - r[0].x, r[1].y - r[0].y), std::hypot(r[(i + 1) % r.size()].x - r[i].x, r[(i + 1) % r.size()].y - r[i].y));
    sum += geom::signed_area(r);
  }
  EXPECT_EQ(sum, geom::area(l));
}

namespace {

// Generates `features` with every zone type laid out by `grammar`; returns the out folder.
std::filesystem::path generate_with_grammar(const std::string& name, const std::string& features, const std::string& grammar,
                                            const std::string& layout = R"("layout": "grammar", "grammar": "g.grammar")") {
  auto dir = testing_util::temp_dir("grammar-" + name);
  std::ofstream(dir / "g.grammar") << grammar;
  std::ofstream(dir / "in.geojson") << R"({"type": "FeatureCollection", "exacity": {"seed": 3, "zones": {"residential": {)"
                                    << layout << R"(}, "commercial": {)" << layout << R"(}}}, "features": [)" << features
                                    << "]}";
  std::filesystem::create_directories(dir / "out");
  generate_city(load_sketch(dir / "in.geojson"), dir / "out", nullptr);
  return dir / "out";
}

// A plain split grammar run: the grammar's pieces are kept whole, however large.
const std::string kKeptWhole = R"("layout": "grammar", "grammar": "g.grammar", "grow_large_pieces": false)";

std::string zone(const std::string& type, const std::string& ring) {
  return R"({"type": "Feature", "properties": {"zone": ")" + type + R"("}, "geometry": {"type": "Polygon", "coordinates": [)" +
         ring + "]}}";
}

std::string example_grammar() {
  std::ifstream in(std::filesystem::path(EXACITY_SOURCE_DIR) / "examples" / "grammars" / "town.grammar");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(GrammarLayout, ABorderTwoRootsShareGetsOneRoadCentredOnIt) {
  // A pentagon triangulates into roots that share edges; every root is surrounded by roads.
  const std::string grammar =
      "1 Town 4 Residential,0.05,0.05,0.95,0.05,0.95,0.95,0.05,0.95 Road_1,0,0,1,0,0.95,0.05,0.05,0.05 "
      "Road_2,1,0,1,1,0.95,0.95,0.95,0.05 Road_3,1,1,0,1,0.05,0.95,0.95,0.95 Road_4,0,1,0,0,0.05,0.05,0.05,0.95\n"
      "1 Town 3 Residential,0.1,0.1,0.8,0.1,0.1,0.8 Road_1,0,0,1,0,0.8,0.1,0.1,0.1 Road_2,1,0,0,1,0.1,0.8,0.8,0.1 "
      "Road_3,0,1,0,0,0.1,0.1,0.1,0.8\n";
  auto out = generate_with_grammar("border", zone("residential", "[[0,0],[500,0],[650,300],[250,520],[-150,300],[0,0]]"), grammar);
  EXPECT_TRUE(validate_output(out).ok());
  std::vector<std::string> problems;
  Layer roads = read_geojson(out / "vector" / "roads.geojson", problems);
  ASSERT_TRUE(problems.empty());
  // No two roads run side by side: segments nearly parallel and overlapping along their
  // length never leave less than a lot's depth (30 m) of land between them.
  struct Segment {
    Vec2 a, b;
    double width;
  };
  std::vector<Segment> segments;
  for (const auto& f : roads.features)
    for (std::size_t i = 0; i + 1 < f.line.size(); ++i) segments.push_back({f.line[i], f.line[i + 1], f.properties["width"]});
  ASSERT_GT(segments.size(), 8u);
  int compared = 0;
  for (std::size_t i = 0; i < segments.size(); ++i)
    for (std::size_t j = i + 1; j < segments.size(); ++j) {
      const Segment &s = segments[i], &t = segments[j];
      const double sx = s.b.x - s.a.x, sy = s.b.y - s.a.y, tx = t.b.x - t.a.x, ty = t.b.y - t.a.y;
      const double ls = std::hypot(sx, sy), lt = std::hypot(tx, ty);
      if (std::abs(sx * ty - sy * tx) > 0.05 * ls * lt) continue;  // not parallel
      // Overlap along s of t's projection.
      auto along = [&](Vec2 p) { return ((p.x - s.a.x) * sx + (p.y - s.a.y) * sy) / ls; };
      const double lo = std::max(0.0, std::min(along(t.a), along(t.b))), hi = std::min(ls, std::max(along(t.a), along(t.b)));
      if (hi - lo < 5) continue;
      ++compared;
      const Vec2 m = t.a.x == t.b.x && t.a.y == t.b.y ? t.a : Vec2{(t.a.x + t.b.x) / 2, (t.a.y + t.b.y) / 2};
      EXPECT_GE(geom::distance_to_segment(m, s.a, s.b), (s.width + t.width) / 2 + 30) << "side by side near " << m.x << "," << m.y;
    }
  EXPECT_GT(compared, 0);
}

TEST(GrammarLayout, AwkwardZonesValidateWithEveryLotOnAStreet) {
  const std::vector<std::pair<std::string, std::string>> shapes = {
      {"u", zone("residential", "[[0,0],[900,0],[900,900],[650,900],[650,250],[250,250],[250,900],[0,900],[0,0]]")},
      {"comb", zone("residential", "[[0,0],[900,0],[900,600],[780,600],[780,150],[600,150],[600,600],[480,600],[480,150],"
                                   "[300,150],[300,600],[0,600],[0,0]]")},
      {"ring", zone("commercial", "[[0,0],[800,0],[800,800],[0,800],[0,0]],[[200,200],[200,600],[600,600],[600,200],[200,200]]")},
      {"sliver", zone("residential", "[[0,0],[1000,0],[1000,3],[0,40],[0,0]]")},
      {"far", zone("residential", "[[6000000,2000000],[6000400,2000000],[6000300,2000300],[6000000,2000250],[6000000,2000000]]")},
  };
  for (const auto& [name, features] : shapes) {
    SCOPED_TRACE(name);
    auto out = generate_with_grammar(name, features, example_grammar());
    Validation v = validate_output(out);
    EXPECT_TRUE(v.ok()) << (v.problems.empty() ? "" : v.problems[0]);
  }
}

TEST(GrammarLayout, ARoadWrittenShortEdgeFirstRunsAlongItsLongAxis) {
  // Quarters with a road across and two half-roads; the park quarter must stay a green
  // block. The second grammar writes the half-roads from a short edge.
  const std::string quarters =
      "1 Town 4 Residential,0,0,0.48,0,0.48,0.48,0,0.48 Residential,0.52,0,1,0,1,0.48,0.52,0.48 "
      "Residential,0.52,0.52,1,0.52,1,1,0.52,1 Park,0,0.52,0.48,0.52,0.48,1,0,1 Road,0,0.48,1,0.48,1,0.52,0,0.52 ";
  const std::string long_first = quarters + "Road,0.48,0,0.48,0.48,0.52,0.48,0.52,0 Road,0.48,0.52,0.48,1,0.52,1,0.52,0.52\n";
  const std::string short_first = quarters + "Road,0.48,0,0.52,0,0.52,0.48,0.48,0.48 Road,0.52,1,0.48,1,0.48,0.52,0.52,0.52\n";
  const std::string square = zone("residential", "[[0,0],[600,0],[600,600],[0,600],[0,0]]");
  auto read = [](const std::filesystem::path& out, const char* layer) {
    std::vector<std::string> problems;
    Layer l = read_geojson(out / "vector" / (std::string(layer) + ".geojson"), problems);
    EXPECT_TRUE(problems.empty());
    return l;
  };
  // The grammar's roads alone: its quarters are kept whole.
  const auto a = generate_with_grammar("long-first", square, long_first, kKeptWhole);
  const auto b = generate_with_grammar("short-first", square, short_first, kKeptWhole);
  // The same centre lines, whichever way each runs.
  auto lines = [&](const std::filesystem::path& out) {
    std::vector<std::vector<std::pair<double, double>>> all;
    for (const auto& f : read(out, "roads").features) {
      std::vector<std::pair<double, double>> line;
      for (Vec2 p : f.line) line.push_back({p.x, p.y});
      if (line.back() < line.front()) std::reverse(line.begin(), line.end());
      all.push_back(line);
    }
    std::sort(all.begin(), all.end());
    return all;
  };
  ASSERT_EQ(lines(a).size(), 3u);
  EXPECT_EQ(lines(b), lines(a));
  int parks = 0;
  for (const auto& f : read(b, "blocks").features) parks += f.properties["zone"] == "park";
  EXPECT_EQ(parks, 1);
}

nlohmann::json report_of(const std::filesystem::path& out) {
  std::ifstream in(out / "report.json");
  return nlohmann::json::parse(in);
}

// Land between the grammar's roads over 4 times block_area is grown by recursive road growth;
// "grow_large_pieces": false keeps the grammar's pieces whole.
TEST(GrammarLayout, PiecesOverFourBlocksAreGrownUnlessKeptWhole) {
  const std::string ring_road =
      "1 Town 4 Inner,0.03,0.03,0.97,0.03,0.97,0.97,0.03,0.97 Road,0,0,1,0,0.97,0.03,0.03,0.03 Road,1,0,1,1,0.97,0.97,0.97,0.03 "
      "Road,1,1,0,1,0.03,0.97,0.97,0.97 Road,0,1,0,0,0.03,0.03,0.03,0.97\n"
      "1 Town 3 Inner,0.06,0.06,0.88,0.06,0.06,0.88 Road,0,0,1,0,0.88,0.06,0.06,0.06 Road,1,0,0,1,0.06,0.88,0.88,0.06 "
      "Road,0,1,0,0,0.06,0.06,0.06,0.88\n"
      "1 Inner 4 Residential,0,0,1,0,1,1,0,1\n1 Inner 3 Residential,0,0,1,0,0,1\n";
  const std::string pentagon = zone("residential", "[[0,0],[500,0],[650,300],[250,520],[-150,300],[0,0]]");
  const auto grown = generate_with_grammar("pieces", pentagon, ring_road);
  EXPECT_TRUE(validate_output(grown).ok());
  const auto lots = report_of(grown)["statistics"]["zones"]["residential"];
  EXPECT_EQ(lots["blocks"]["share_area_over_4x_block_area"].get<double>(), 0.0);
  EXPECT_LE(lots["lots"]["share_without_building"].get<double>(), 0.03);
  EXPECT_EQ(lots["lots"]["share_touching_road"].get<double>(), 1.0);

  const auto kept = generate_with_grammar("pieces-whole", pentagon, ring_road, kKeptWhole);
  EXPECT_TRUE(validate_output(kept).ok());
  EXPECT_GT(report_of(kept)["statistics"]["zones"]["residential"]["blocks"]["share_area_over_4x_block_area"].get<double>(), 0.5);
}

// A zone whose every root becomes Residential at once gets no road from the grammar: growth
// lays its streets; kept whole, it is reported empty, with the reason.
TEST(GrammarLayout, AZoneTheGrammarGivesNoRoadIsGrownOrReportedEmpty) {
  const std::string zone_only = zone("residential", "[[0,0],[500,0],[650,300],[250,520],[-150,300],[0,0]]");
  const std::string no_road = "1 Town 3 Residential,0,0,1,0,0,1\n1 Town 4 Residential,0,0,1,0,1,1,0,1\n";
  const auto report = report_of(generate_with_grammar("no-road", zone_only, no_road));
  EXPECT_GT(report["counts"]["lots"].get<int>(), 50);
  EXPECT_TRUE(report["empty_zones"].empty()) << report["empty_zones"];

  const auto strict = report_of(generate_with_grammar("no-road-whole", zone_only, no_road, kKeptWhole));
  EXPECT_EQ(strict["counts"]["lots"].get<int>(), 0);
  ASSERT_EQ(strict["empty_zones"].size(), 1u);
  EXPECT_EQ(strict["empty_zones"][0]["feature"].get<int>(), 0);
  EXPECT_EQ(strict["empty_zones"][0]["zone"].get<std::string>(), "residential");
  EXPECT_NE(strict["empty_zones"][0]["why"].get<std::string>().find("no street reaches"), std::string::npos);
}
