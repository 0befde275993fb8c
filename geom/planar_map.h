// One exact planar map (a CGAL arrangement on the exact kernel) behind a plain interface.
//
// Curves are inserted in batches (or, for rings that each lie in a known set of faces,
// region by region: insert_within). Each curve carries tags: a ring edge tagged
// (counter, +1) raises `counter`'s winding number by one for the face on its left, so
// after a batch every face knows, per counter, how often the tagged rings wind around it.
// Callers turn those windings into face labels (small integers whose meaning is theirs);
// an observer keeps a label on both halves when a later batch splits a labelled face.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "geom/cell.h"
#include "geom/plain.h"

namespace geom {

class FaceLocator;  // geom/face_locator.h

struct CurveTag {
  int counter = 0;
  int sign = 0;  // +1: edge of a ring around `counter`; 0: a tagged curve that bounds nothing
  int aux = 0;   // caller's index (ring index, segment index, ...)
  friend bool operator==(const CurveTag&, const CurveTag&) = default;
};

// Non-zero winding numbers of one face, sorted by counter.
using Windings = std::vector<std::pair<int, int>>;

int winding_of(const Windings& w, int counter);

// The kernel this build computes with (geom/exact.h): exact, or a floating-point one for
// the robustness benchmark.
const char* kernel_name();

// A piece of a tagged polyline between two map vertices, with the labels on its sides.
struct PolylinePiece {
  int segment = 0;  // index of the polyline segment it lies on
  Vec2 from, to;
  int left_label = -1, right_label = -1;
};

// A polygon made of faces, and the labels of the faces just outside it.
struct Dissolved {
  Polygon polygon;
  std::vector<int> neighbour_labels;  // sorted, unique
};

struct PlanarMapCounts {
  std::size_t vertices = 0, edges = 0, faces = 0;
};

class PlanarMap {
 public:
  PlanarMap();
  ~PlanarMap();
  PlanarMap(PlanarMap&&) noexcept;
  PlanarMap& operator=(PlanarMap&&) noexcept;

  // Queued for the next insert_batch(). Zero-length edges are skipped.
  void add_ring(const Ring& ring, int counter, int aux = 0);
  // One edge a -> b of some ring around `counter`, for outlines built edge by edge.
  void add_edge(Vec2 a, Vec2 b, int counter);
  // A stroke of `half_width` around the polyline: flat ends, mitred joints (bevelled
  // past a mitre limit of 4), built by the grid-line rule; all pieces wind around `counter`.
  void add_stroke(const Polyline& line, double half_width, int counter);
  // The joint a stroke would have at q on a path a -> q -> b, for two strokes that meet
  // end to end; and a 16-gon around a disc, for where several meet.
  void add_joint(Vec2 a, Vec2 q, Vec2 b, double half_width, int counter);
  void add_disc(Vec2 centre, double radius, int counter);
  // The mitred junction of streets meeting at q (docs/design.md, Exactness rule 3): one polygon whose sides lie on
  // the streets' stroke sides. False, and nothing queued, where none is needed or none can
  // be drawn (see exact::junction_piece).
  bool add_junction(Vec2 q, const std::vector<JunctionArm>& arms, int counter);
  // The polyline itself, bounding nothing, findable later with polyline_pieces(tag).
  void add_polyline(const Polyline& line, int tag);
  // The same for exact paths, and a path's stroke (its vertices rounded for the offsets).
  void add_path(const Path& path, int tag);
  void add_path_stroke(const Path& path, double half_width, int counter);

  // Inserts everything queued in one sweep.
  void insert_batch();

  // Rings (a cell's: holes wind the other way) that each belong to one region, a set of
  // faces (see insert_within); only what lies inside the region's faces reaches the map.
  void add_ring_within(int region, const Ring& ring, int counter);
  void add_cell_within(int region, const Cell& cell, int counter);
  // A map of one cell alone (a block, for its lots: docs/design.md, Lots): the cell's
  // edges exactly as it has them, the faces inside it labelled `inside` and the rest
  // `outside`. Where cells() meets the outside across one of those edges, it takes the
  // label across to be label_across(the edge's kind in the cell): what the city's map has
  // across that edge, which the outside, one face, cannot say.
  static PlanarMap of_cell(const Cell& cell, int inside, int outside, const std::function<int(int)>& label_across);
  // In a map of one cell (of_cell), the cell's outline as the map has cut it: each of the
  // cell's edges split at the vertices the map has on it (where later batches met it, or
  // snap rounding split it), in the cell's order from the same start. Each piece's kind is
  // the index of the cell's edge it lies on, counting the outer ring's, then each hole's.
  Cell outline_as_cut() const;

  // Puts regions' outlines (outline_as_cut of a map of the region's cell alone, whose cell
  // is the region's boundary as this map has it) into the map: each region's boundary edges
  // split at the vertices its outline has on them, then the map snap-rounded (the last
  // batch). So the map's edges hold every vertex the regions' own maps put on them, and
  // nothing inside the regions is swept again. Returns, per region, the vertices its
  // boundary now has that its outline lacks (another region's on an edge they share, or
  // snap rounding's), in order along each edge, for what its own map made to take them.
  std::vector<std::vector<VertexOnEdge>> add_outlines(const std::vector<int>& region_of_label,
                                                      const std::vector<Cell>& outline_of_region);

  // Inserts what add_*_within queued, region by region: each region's rings are cut
  // against its faces (region_of_label[label]) in a small arrangement of their own and
  // then added to the map edge by edge, so the rest of the map is not swept again. Each
  // face inside a region gets label_of(its windings of the region's rings, the label of
  // the face it was cut from). The added edges bound nothing (they change no face's
  // windings), and rings connected to no edge of their region are left out.
  void insert_within(const std::vector<int>& region_of_label, const std::function<int(const Windings&, int)>& label_of);

  // Snap rounding (Hobby; Guibas and Marimont) to the grid of doubles, after the last
  // batch: a vertex's pixel is the box of points that round to the doubles it rounds to;
  // where an edge passes through the pixel of a vertex not its own, it gets a vertex
  // there. Rounding every vertex then moves each edge only through pixels it crossed:
  // rounded edges cross nowhere, and a face keeps its shape or collapses (untangle() turns
  // its collapsed rings back into simple polygons). Returns how many vertices it added.
  std::size_t snap_round();

  // Labels every face with label_of(its windings); the unbounded face included.
  void label_faces(const std::function<int(const Windings&)>& label_of);
  // The same after a later batch, counting only counters >= from_counter, and knowing each
  // face's label so far (faces split by the batch keep the label the face had).
  void relabel_faces(int from_counter, const std::function<int(const Windings&, int)>& label_of);

  // Merges faces by group (group_of_label[label], -1 for none) into polygons with
  // holes: result[g] lists group g's polygons. Rings are simple; a hole may touch its
  // outer ring at a vertex.
  std::vector<std::vector<Dissolved>> dissolve(const std::vector<int>& group_of_label,
                                               int group_count) const;

  // Components of faces with group >= 0 as exact cells, in face order: each boundary
  // edge's kind is kind_of_label[label of the face across it].
  // When `groups` is given, it receives each cell's group; `components`, the index of the
  // component of faces each cell came from.
  std::vector<Cell> cells(const std::vector<int>& group_of_label, const std::vector<int>& kind_of_label,
                          std::vector<int>* groups = nullptr, std::vector<int>* components = nullptr) const;

  // Gives each face of the components cells() would find the label relabel(component index,
  // its label).
  void relabel_components(const std::vector<int>& group_of_label, const std::function<int(int, int)>& relabel);

  // The pieces of every polyline, in order along each: result[tag].
  std::map<int, std::vector<PolylinePiece>> polyline_pieces() const;

  // Calls f with the tags of every edge and its end points.
  void for_each_edge(const std::function<void(const std::vector<CurveTag>&, Vec2, Vec2)>& f) const;

  // The label of the face holding a point (on an edge or vertex: -1), exactly. The first
  // call after the edges change indexes them (a grid of squares); later calls only read
  // the index and the map, so threads may call it at once.
  int label_at(Vec2 point) const;

  // label_at's answers without the map, for when it is freed (geom/face_locator.h), with
  // the faces' labels as they are now.
  FaceLocator face_locator() const;

  // How many polyline edges meet at each vertex where any meet: degree -> vertex count.
  std::map<int, int> polyline_degrees() const;

  // A vertex on the boundary of some face with this label, to point a user at it.
  bool point_near_label(int label, Vec2& out) const;

  // Per label in [0, labels): the largest 2·area/perimeter over the faces with it, about
  // the width of a thin face (a measure in doubles, relative to a vertex of each face);
  // 0 where no face has the label. One pass over the faces.
  std::vector<double> widest_faces(int labels) const;

  PlanarMapCounts counts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace geom
