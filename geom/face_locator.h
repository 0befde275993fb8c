// The faces of a PlanarMap located without the map: label_at answers as PlanarMap::label_at
// does, from a copy of the vertices' exact points, each edge's two ends and the labels of
// the faces below them, in a small part of the arrangement's memory, so that the map can be
// freed while its faces are still asked about (the clutter: docs/design.md, The pipeline).
#pragma once

#include <memory>

#include "geom/plain.h"

namespace geom {

class PlanarMap;

class FaceLocator {
 public:
  struct Impl;
  FaceLocator() = default;  // no edges: every point in the unbounded face, labelled -1
  explicit FaceLocator(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

  // The label of the face holding the point; -1 on an edge or a vertex. Exact, and only
  // reads, so threads may call it at once.
  int label_at(Vec2 point) const;

 private:
  std::shared_ptr<const Impl> impl_;
};

}  // namespace geom
