// The split grammar (docs/design.md, Algorithms): its text file, and the growth of a layout tree from it.
//
// One rule per line, `#` starts a comment: `WEIGHT LEFT N CHILD CHILD ...`, N the left
// symbol's corner count (3 or 4), each CHILD `Name,u1,v1,u2,v2,u3,v3` (a triangle) or
// `Name,u1,v1,...,u4,v4` (a quad) in the parent's parameter space. Rules for one symbol
// and corner count are picked by weight; a symbol with no rule is a terminal.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "generate/city/random.h"
#include "generate/city/zone_type.h"
#include "geom/plain.h"

namespace exacity {

struct GrammarChild {
  std::string name;
  std::vector<geom::Vec2> corners;  // (u, v) in the parent's parameter space: 3 or 4
};

struct GrammarRule {
  double weight = 0;
  std::vector<GrammarChild> children;
  int line = 0;
};

// What a terminal symbol stands for (the grammar's land uses).
struct Terminal {
  enum Kind { Land, Park, Road } kind = Land;
  ZoneType type = ZoneType::Residential;  // for Land
  std::string density;                    // for Land: "dense", "sparse" or "" (the zone's own)
};

struct Grammar {
  std::filesystem::path file;
  // By (left symbol, corner count).
  std::map<std::pair<std::string, int>, std::vector<GrammarRule>> rules;
};

// Throws UserError naming the file and line: bad syntax, a child with other than 6 or 8
// values, N not 3 or 4, a corner outside [0, 1], rules for a symbol whose weights sum to 0,
// a terminal that is none of the land uses' names, a child whose corner count its symbol has no
// rule for, no rule for `Town`.
Grammar parse_grammar(const std::string& text, const std::filesystem::path& file);
Grammar load_grammar(const std::filesystem::path& file);

// The terminal a symbol names: Residential, Commercial, Industrial (each maybe _Dense or
// _Sparse), Park, or anything containing "Road"; false for any other name.
bool parse_terminal(const std::string& name, Terminal& out);

// A corner (u, v) of the parameter space of a parent with 3 corners (p = a + u(b - a) +
// v(c - a)) or 4 (bilinear: u along the first edge, v along the second).
geom::Vec2 map_corner(const std::vector<geom::Vec2>& parent, geom::Vec2 uv);

// A leaf of the layout tree: its symbol and corners in the plane (in doubles).
struct GrammarLeaf {
  std::string name;
  std::vector<geom::Vec2> corners;
  int root = 0;    // index of the root it grew from
  int depth = 0;
};

// Grows each root (a `Town`) by the grammar until every leaf is terminal, `max_depth`
// rules deep, or smaller than `min_area` (a symbol left there stays a leaf). A symbol
// containing "Road" is not split further: it is one road, drawn whole.
std::vector<GrammarLeaf> grow_layout(const Grammar& grammar, const std::vector<std::vector<geom::Vec2>>& roots,
                                     int max_depth, double min_area, std::uint64_t seed);

// The grammar's roots for a polygon: its triangles, neighbouring pairs that make a near
// rectangle (every corner within 20 degrees of square) merged into quads, best first.
// Counter-clockwise, each starting at its longest edge.
std::vector<std::vector<geom::Vec2>> layout_roots(const geom::Polygon& polygon);

}  // namespace exacity
