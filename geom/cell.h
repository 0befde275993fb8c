// Exact cells for road growth: a cell is a polygon with holes whose boundary vertices are
// exact (grid points or meetings of grid lines) and whose edges carry a kind chosen by the
// caller (say, "road" or "zone edge"); a path is a road centre line with exact vertices.
// Roads grow inside a cell step by step; a step that meets the cell's boundary or an
// earlier road ends exactly where it first meets it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geom/plain.h"

namespace geom {

class Path {
 public:
  struct Impl;
  Path() = default;
  explicit Path(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  static Path from(const Polyline& line);  // the doubles as exact points
  Path reversed() const;

  std::size_t size() const;
  bool empty() const { return size() < 2; }
  Vec2 point(std::size_t i) const;  // rounded to doubles
  Polyline to_plain() const;
  // Every vertex exactly on the line through the first two.
  bool is_straight() const;
  const Impl& exact() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
};

// A ring rounded to doubles, the interior on its left, with a kind per edge:
// kinds[i] belongs to the edge points[i] -> points[i + 1].
struct KindedRing {
  Ring points;
  std::vector<int> kinds;
};

class Cell {
 public:
  struct Impl;
  Cell() = default;
  explicit Cell(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

  bool has_value() const { return impl_ != nullptr; }  // false for a Cell() (a lot planned without one)
  double area() const;  // the exact area, rounded
  Box bounds() const;
  Vec2 centroid() const;
  // Strictly inside, decided exactly.
  bool contains(Vec2 p) const;
  // The simple ring and all it encloses lie strictly inside, decided exactly: touching
  // the boundary counts as leaving it.
  bool holds(const Ring& ring) const;
  // A grid point strictly inside: `wanted` rounded to the grid when that is inside,
  // otherwise a point just inside the boundary near where it passes closest to `wanted`.
  std::optional<Vec2> point_inside_near(Vec2 wanted) const;
  // The outer ring's vertices but those exactly in line with their neighbours, rounded
  // (corners that round to one double become one; empty when fewer than 3 are left).
  std::vector<Vec2> corners() const;
  // The kinds of the boundary's edges, each once, sorted.
  std::vector<int> edge_kinds() const;
  // The outer ring, then the holes, rounded; edges that round to nothing are left out.
  std::vector<KindedRing> kinded_rings() const;
  // Boundary edges of the given kind, rounded.
  std::vector<std::pair<Vec2, Vec2>> edges_of_kind(int kind) const;
  // Rounded to doubles and untangled (geom/untangle.h): the simple polygons it becomes,
  // none when it collapses.
  std::vector<Polygon> rounded() const;
  // The largest of them; an empty outer ring when it collapses.
  Polygon to_plain() const;
  // The cell with its vertices rounded to doubles and its edge kinds kept, less the edges
  // and spikes (edges run there and straight back) rounding collapsed, when that leaves
  // every vertex apart (in a snap-rounded map its rings then stay simple); none when two
  // still land on one double pair (a neck or a hole rounded to touch), or its outer ring
  // collapsed.
  std::optional<Cell> as_written() const;
  const Impl& exact() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
};

// A vertex on an edge from -> to (as rounded) that a cell lacks: one a map has on a
// region's boundary that the region's outline lacks (PlanarMap::add_outlines).
struct VertexOnEdge {
  Vec2 from, to, at;
};

// The cell with each vertex of `added` put into its edge from -> to (ends as the cell
// rounds them), in the order given, as a double (for a cell as written); edges none lies on
// stay as they are. None when none lies on its edges.
std::optional<Cell> with_vertices_on_edges(const Cell& cell, const std::vector<VertexOnEdge>& added);

// Every vertex written exactly (a double as a hex float, any other coordinate as its exact
// rational) and every edge's kind: two cells with equal texts are the same cell, vertex for
// vertex from the same start. A cache's key (generate/city/memo.h). Empty for a Cell().
std::string exact_text(const Cell& cell);
std::string exact_text(const Path& path);
// The cell or path exact_text wrote, vertex for vertex the same (a plan's task writes the
// items it computed this way: generate/plan/memo_text.h). Throws std::invalid_argument on
// any other text.
Cell cell_from_exact_text(std::string_view text);
Path path_from_exact_text(std::string_view text);

// Roads growing inside one cell.
class Growth {
 public:
  // What a step met: nothing, a road grown in this cell, or a boundary edge of `kind`.
  struct Met {
    enum What : std::uint8_t { Nothing, OwnRoad, Edge } what = Nothing;
    int kind = 0;  // the edge's kind, for Edge
    bool edge_of_kind(int k) const { return what == Edge && kind == k; }
    friend bool operator==(const Met&, const Met&) = default;
  };

  // `step` is the usual step length, to size the search index.
  Growth(const Cell& cell, double step);
  ~Growth();
  Growth(const Growth&) = delete;
  Growth& operator=(const Growth&) = delete;

  // Starts a road at a grid point strictly inside the cell.
  void begin(Vec2 start);
  // Extends the road towards the grid point `next`. Where the segment met something, the
  // road now ends at the first point it met; where two things meet there, a boundary edge
  // beats a road grown here, and the larger kind beats the smaller.
  Met extend(Vec2 next);
  // The road begun last (empty when it has no length); later roads stop where they meet it.
  Path end();
  // A road grown before, which later roads stop at.
  void add_obstacle(const Path& road);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The shortest segment from one set of paths to another, as a path of two points lying
// exactly on both (the closer pair is chosen in doubles, between a vertex of one set and
// its nearest point on the other), with its length; nullopt when a set is empty. A link of
// length zero, with an empty path, when the sets meet at a vertex.
struct Link {
  Path path;
  double length = 0;
};
std::optional<Link> shortest_link(const std::vector<Path>& from, const std::vector<Path>& to);

// The road with its last segment carried on along its own line to the first point where it
// meets one of `targets` within `reach` metres past its end (a grown road running on to the
// centre line of the road whose surface it stopped at). Where its line meets none there (it
// stopped at a road's end cap, or met the surface at so shallow an angle that the centre
// line is beyond reach), it turns to the nearest point of the targets within `reach`
// instead, unless `may_turn` is false; unchanged when there is none.
Path extend_to(const Path& road, const std::vector<Path>& targets, double reach, bool may_turn = true);

// Whether the road's last point lies exactly on one of `targets`: it meets it already.
bool ends_on(const Path& road, const std::vector<Path>& targets);

// The cell less a band of width `setback` inside every boundary edge (docs/design.md, Exactness rule 3:
// each band's inner side runs through two offset points rounded to the grid); the parts
// left, exact. Bands run `setback` past each edge's ends, so corners are cleared too.
std::vector<Cell> inset_cell(const Cell& cell, double setback);

// The cell cut by roads that run inside it from boundary to boundary or to each other:
// the parts, their new edges of kind `road_kind`.
std::vector<Cell> split_cell(const Cell& cell, const std::vector<Path>& roads, int road_kind);

}  // namespace geom
