// Which of the city's tiles a camera sees (render/scene.h): the tiles' boxes in scene
// coordinates, the view frustum's side planes, and a bounding volume hierarchy over the
// boxes that the frustum is tested against.
#pragma once

#include <cmath>
#include <vector>

#include "render/camera.h"
#include "render/vec.h"

namespace render {

struct Plane {
  V3 n;
  float d;  // inside where dot(n, p) + d >= 0
};

// A box in scene coordinates.
struct Box3 {
  V3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  void add(V3 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)},
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void add(const Box3& b) { add(b.lo), add(b.hi); }
  bool outside(const Plane& p) const {
    V3 far{p.n.x >= 0 ? hi.x : lo.x, p.n.y >= 0 ? hi.y : lo.y, p.n.z >= 0 ? hi.z : lo.z};
    return dot(p.n, far) + p.d < 0;
  }
};

// The four side planes of the camera's view, facing in.
std::vector<Plane> frustum(const Camera& c, float aspect);

// A bounding volume hierarchy over tile boxes, for the tiles a frustum can see.
class TileBvh {
 public:
  explicit TileBvh(const std::vector<Box3>& boxes);
  // Sets seen[k] for every tile k whose box is not wholly outside one of the planes.
  void visible(const std::vector<Plane>& planes, std::vector<bool>& seen) const;

 private:
  struct Node {
    Box3 box;
    int left = -1, right = -1, tile = -1;
  };
  int build(std::vector<int>& ids, int begin, int end);
  void visit(int n, const std::vector<Plane>& planes, std::vector<bool>& seen) const;
  const std::vector<Box3>& boxes_;
  std::vector<Node> nodes_;
};

// Shadows reach in from outside the view: grows each box towards the sun by its shadow.
void grow_towards_sun(std::vector<Box3>& boxes, V3 sun);

}  // namespace render
