#include "generate/layout/grammar.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <sstream>

#include "generate/city/features.h"
#include "generate/errors.h"
#include "generate/input_file.h"
#include "geom/measure.h"
#include "geom/triangulate.h"

namespace exacity {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw UserError(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

bool read_number(const std::string& token, double& out) {
  std::istringstream in(token);
  in >> out;
  return in && in.eof() && std::isfinite(out);
}

}  // namespace

bool parse_terminal(const std::string& name, Terminal& out) {
  out = {};
  if (name.find("Road") != std::string::npos) return out.kind = Terminal::Road, true;
  if (name == "Park") return out.kind = Terminal::Park, true;
  std::string base = name;
  for (const char* suffix : {"_Dense", "_Sparse"})
    if (base.size() > std::strlen(suffix) && base.ends_with(suffix)) {
      base.erase(base.size() - std::strlen(suffix));
      out.density = suffix[1] == 'D' ? "dense" : "sparse";
    }
  if (base == "Residential") out.type = ZoneType::Residential;
  else if (base == "Commercial") out.type = ZoneType::Commercial;
  else if (base == "Industrial") out.type = ZoneType::Industrial;
  else return false;
  return true;
}

namespace {

// The words of a line, without its comment.
std::vector<std::string> tokens_of(std::string raw) {
  if (auto hash = raw.find('#'); hash != std::string::npos) raw.resize(hash);
  std::istringstream words(raw);
  std::vector<std::string> tokens;
  for (std::string t; words >> t;) tokens.push_back(t);
  return tokens;
}

// One child token, NAME,u1,v1,...; `t` is its position on the line, for messages.
GrammarChild parse_child(const std::string& token, std::size_t t, const std::filesystem::path& file, int line) {
  std::vector<std::string> parts;
  std::istringstream child(token);
  for (std::string p; std::getline(child, p, ',');) parts.push_back(p);
  if (parts.empty() || parts[0].empty()) fail(file, line, "child " + std::to_string(t - 2) + " has no name");
  GrammarChild c{parts[0], {}};
  const std::size_t values = parts.size() - 1;
  if (values != 6 && values != 8)
    fail(file, line, "child " + c.name + " has " + std::to_string(values) +
                         " values; a triangle has 6 (u1,v1,u2,v2,u3,v3), a quad 8");
  for (std::size_t k = 1; k < parts.size(); k += 2) {
    geom::Vec2 uv;
    if (!read_number(parts[k], uv.x) || !read_number(parts[k + 1], uv.y))
      fail(file, line, "child " + c.name + ": \"" + parts[k] + "," + parts[k + 1] + "\" is not a pair of numbers");
    if (uv.x < 0 || uv.x > 1 || uv.y < 0 || uv.y > 1)
      fail(file, line, "child " + c.name + ": corner (" + parts[k] + ", " + parts[k + 1] +
                           ") lies outside the parent's parameter space [0, 1] x [0, 1]");
    c.corners.push_back(uv);
  }
  return c;
}

// A line WEIGHT LEFT N CHILD..., as the rule and the (left symbol, corner count) it rewrites.
std::pair<std::pair<std::string, int>, GrammarRule> parse_rule(const std::vector<std::string>& tokens,
                                                               const std::filesystem::path& file, int line) {
  if (tokens.size() < 4)
    fail(file, line, "expected WEIGHT LEFT N CHILD..., e.g. \"1.0 Town 4 Inner,0.1,0.1,0.9,0.1,0.9,0.9,0.1,0.9\"");
  GrammarRule rule;
  rule.line = line;
  if (!read_number(tokens[0], rule.weight) || rule.weight < 0)
    fail(file, line, "the weight \"" + tokens[0] + "\" is not a number of 0 or more");
  const std::string& left = tokens[1];
  if (tokens[2] != "3" && tokens[2] != "4")
    fail(file, line, "the corner count \"" + tokens[2] + "\" of " + left + " must be 3 (a triangle) or 4 (a quad)");
  const int n = tokens[2][0] - '0';
  for (std::size_t t = 3; t < tokens.size(); ++t) rule.children.push_back(parse_child(tokens[t], t, file, line));
  return {{left, n}, std::move(rule)};
}

// Growing picks a rule by weight, so each symbol needs some weight to pick by.
void check_weights(const Grammar& g, const std::filesystem::path& file) {
  for (const auto& [key, rules] : g.rules) {
    double sum = 0;
    for (const GrammarRule& r : rules) sum += r.weight;
    if (sum <= 0)
      fail(file, rules.front().line, "the rules for " + key.first + " (" + std::to_string(key.second) +
                                         " corners) have weights summing to 0; give one a positive weight");
  }
}

// Every child must be a terminal or a symbol with a rule for its corner count.
void check_children(const Grammar& g, const std::vector<std::pair<GrammarChild, int>>& used,
                    const std::filesystem::path& file) {
  std::set<std::string> left_symbols;
  for (const auto& [key, rules] : g.rules) left_symbols.insert(key.first);
  if (!left_symbols.count("Town")) fail(file, 1, "no rule for Town, the symbol every root starts as; add one");
  for (const auto& [child, line] : used) {
    const int n = static_cast<int>(child.corners.size());
    Terminal t;
    if (parse_terminal(child.name, t) && (t.kind == Terminal::Road || !left_symbols.count(child.name))) continue;
    if (!left_symbols.count(child.name))
      fail(file, line, "\"" + child.name + "\" has no rule and is no terminal: write a rule for it or use Residential, "
                       "Commercial, Industrial (maybe _Dense or _Sparse), Park, or a name containing Road");
    if (!g.rules.count({child.name, n}))
      fail(file, line, "child " + child.name + " has " + std::to_string(n) + " corners, but the rules for " + child.name +
                           " are for " + std::to_string(7 - n) + "; add a rule for " + std::to_string(n));
  }
}

}  // namespace

Grammar parse_grammar(const std::string& text, const std::filesystem::path& file) {
  Grammar g;
  g.file = file;
  std::istringstream in(text);
  std::string raw;
  std::vector<std::pair<GrammarChild, int>> used;  // every child, with its line
  for (int line = 1; std::getline(in, raw); ++line) {
    const std::vector<std::string> tokens = tokens_of(raw);
    if (tokens.empty()) continue;
    auto [key, rule] = parse_rule(tokens, file, line);
    for (const GrammarChild& c : rule.children) used.push_back({c, line});
    g.rules[key].push_back(std::move(rule));
  }
  check_weights(g, file);
  check_children(g, used, file);
  return g;
}

Grammar load_grammar(const std::filesystem::path& file) {
  return parse_grammar(read_input(file, kMaxSettingsFileBytes, "the grammar",
                                  "give the path of a grammar file, relative to the sketch"),
                       file);
}

geom::Vec2 map_corner(const std::vector<geom::Vec2>& p, geom::Vec2 uv) {
  const double u = uv.x, v = uv.y;
  if (p.size() == 3)
    return {p[0].x + u * (p[1].x - p[0].x) + v * (p[2].x - p[0].x), p[0].y + u * (p[1].y - p[0].y) + v * (p[2].y - p[0].y)};
  const double w00 = (1 - u) * (1 - v), w10 = u * (1 - v), w11 = u * v, w01 = (1 - u) * v;
  return {w00 * p[0].x + w10 * p[1].x + w11 * p[2].x + w01 * p[3].x,
          w00 * p[0].y + w10 * p[1].y + w11 * p[2].y + w01 * p[3].y};
}

std::vector<GrammarLeaf> grow_layout(const Grammar& grammar, const std::vector<std::vector<geom::Vec2>>& roots,
                                     int max_depth, double min_area, std::uint64_t seed) {
  std::vector<GrammarLeaf> leaves;
  struct Node {
    GrammarLeaf leaf;
    std::uint64_t id;
  };
  std::vector<Node> open;
  for (std::size_t r = roots.size(); r-- > 0;) open.push_back({{"Town", roots[r], static_cast<int>(r), 0}, mix(seed, r)});
  while (!open.empty()) {
    Node node = std::move(open.back());
    open.pop_back();
    const GrammarLeaf& at = node.leaf;
    auto rules = grammar.rules.find({at.name, static_cast<int>(at.corners.size())});
    const bool road = at.name.find("Road") != std::string::npos;
    if (rules == grammar.rules.end() || road || at.depth >= max_depth ||
        std::abs(geom::signed_area(at.corners)) < min_area) {
      leaves.push_back(std::move(node.leaf));
      continue;
    }
    // Each piece is a block or a road: the tree is refused as it grows past the blocks one
    // run builds, before the work of growing it further (a rule that makes roads beside its
    // symbols grows a third more pieces than blocks, every one to be settled and inserted).
    if (static_cast<double>(leaves.size() + open.size()) >= kMaxBlocks)
      throw UserError(grammar.file.string() + ": the grammar grows more than " +
                      std::to_string(static_cast<long long>(kMaxBlocks)) +
                      " pieces (blocks and roads) in one region, the blocks one run builds, at \"grammar_depth\" " +
                      std::to_string(max_depth) + " and \"min_block_area\" " + number_text(min_area) +
                      "; lower \"grammar_depth\" or raise \"min_block_area\"");
    Random rng(node.id);
    double total = 0;
    for (const GrammarRule& r : rules->second) total += r.weight;
    double pick = rng.uniform(0, total);
    const GrammarRule* rule = &rules->second.back();
    for (const GrammarRule& r : rules->second)
      if ((pick -= r.weight) < 0 && r.weight > 0) {
        rule = &r;
        break;
      }
    for (std::size_t c = rule->children.size(); c-- > 0;) {
      const GrammarChild& child = rule->children[c];
      GrammarLeaf next{child.name, {}, at.root, at.depth + 1};
      for (geom::Vec2 uv : child.corners) next.corners.push_back(map_corner(at.corners, uv));
      open.push_back({std::move(next), mix(node.id, c)});
    }
  }
  return leaves;
}

std::vector<std::vector<geom::Vec2>> layout_roots(const geom::Polygon& polygon) {
  std::vector<geom::Vec2> points = polygon.outer;
  for (const geom::Ring& h : polygon.holes) points.insert(points.end(), h.begin(), h.end());
  const auto triangles = geom::triangulate(polygon);
  // Each triangle's neighbour across each edge.
  std::map<std::pair<int, int>, int> by_edge;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) by_edge[{triangles[t][k], triangles[t][(k + 1) % 3]}] = static_cast<int>(t);
  auto squareness = [&](const std::vector<geom::Vec2>& q) {
    double worst = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      const geom::Vec2 a = q[(i + q.size() - 1) % q.size()], b = q[i], c = q[(i + 1) % q.size()];
      const double cross = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
      const double dot = (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y);
      if (cross <= 0) return 180.0;  // not convex
      worst = std::max(worst, std::abs(std::atan2(dot, cross)) * 180 / M_PI);
    }
    return worst;
  };
  struct Merge {
    double worst;
    int t, u;
    std::vector<geom::Vec2> quad;
  };
  std::vector<Merge> merges;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3], c = triangles[t][(k + 2) % 3];
      auto across = by_edge.find({b, a});
      if (across == by_edge.end() || across->second <= static_cast<int>(t)) continue;
      const auto& other = triangles[across->second];
      int d = other[0] + other[1] + other[2] - a - b;
      std::vector<geom::Vec2> quad{points[a], points[d], points[b], points[c]};
      const double worst = squareness(quad);
      if (worst <= 20) merges.push_back({worst, static_cast<int>(t), across->second, std::move(quad)});
    }
  std::stable_sort(merges.begin(), merges.end(), [](const Merge& x, const Merge& y) { return x.worst < y.worst; });
  std::vector<char> merged(triangles.size(), 0);
  std::vector<std::vector<geom::Vec2>> roots;
  for (Merge& m : merges)
    if (!merged[m.t] && !merged[m.u]) merged[m.t] = merged[m.u] = 1, roots.push_back(std::move(m.quad));
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (!merged[t]) roots.push_back({points[triangles[t][0]], points[triangles[t][1]], points[triangles[t][2]]});
  // Each root starts at its longest edge.
  for (auto& r : roots) {
    std::size_t longest = 0;
    double best = -1;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const geom::Vec2 a = r[i], b = r[(i + 1) % r.size()];
      if (const double len = std::hypot(b.x - a.x, b.y - a.y); len > best) best = len, longest = i;
    }
    std::rotate(r.begin(), r.begin() + longest, r.end());
  }
  return roots;
}

}  // namespace exacity
