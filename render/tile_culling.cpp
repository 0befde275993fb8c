#include "render/tile_culling.h"

#include <algorithm>

namespace render {

std::vector<Plane> frustum(const Camera& c, float aspect) {
  const V3 f = c.forward(), r = c.right(), u = cross(r, f);
  std::vector<Plane> planes;
  auto add = [&](V3 n, V3 p) { planes.push_back({n, -dot(n, p)}); };
  if (c.orthographic) {
    const float hh = c.ortho_height / 2, hw = hh * aspect;
    add(r, c.from - r * hw), add(r * -1, c.from + r * hw), add(u, c.from - u * hh), add(u * -1, c.from + u * hh);
    return planes;
  }
  const float t = std::tan(c.fov_y * kPi / 360), ta = t * aspect;
  // A side plane holds the camera and the two corner directions on that side.
  const V3 tl = f + r * -ta + u * t, tr = f + r * ta + u * t, bl = f + r * -ta + u * -t, br = f + r * ta + u * -t;
  add(normalize(cross(bl, tl)), c.from), add(normalize(cross(tr, br)), c.from);
  add(normalize(cross(tl, tr)), c.from), add(normalize(cross(br, bl)), c.from);
  return planes;
}

TileBvh::TileBvh(const std::vector<Box3>& boxes) : boxes_(boxes) {
  std::vector<int> ids;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    if (boxes[i].lo.x <= boxes[i].hi.x) ids.push_back(i);
  if (!ids.empty()) build(ids, 0, static_cast<int>(ids.size()));
}

void TileBvh::visible(const std::vector<Plane>& planes, std::vector<bool>& seen) const {
  if (!nodes_.empty()) visit(0, planes, seen);
}

int TileBvh::build(std::vector<int>& ids, int begin, int end) {
  Node node;
  for (int i = begin; i < end; ++i) node.box.add(boxes_[ids[i]]);
  const int at = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (end - begin == 1) {
    nodes_[at].tile = ids[begin];
    return at;
  }
  const V3 size = node.box.hi - node.box.lo;
  const int axis = size.x >= size.y ? 0 : 1;
  const int mid = (begin + end) / 2;
  std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end, [&](int a, int b) {
    return (boxes_[a].lo[axis] + boxes_[a].hi[axis]) < (boxes_[b].lo[axis] + boxes_[b].hi[axis]);
  });
  const int left = build(ids, begin, mid), right = build(ids, mid, end);
  nodes_[at].left = left, nodes_[at].right = right;
  return at;
}

void TileBvh::visit(int n, const std::vector<Plane>& planes, std::vector<bool>& seen) const {
  for (const Plane& p : planes)
    if (nodes_[n].box.outside(p)) return;
  if (nodes_[n].tile >= 0) {
    seen[nodes_[n].tile] = true;
    return;
  }
  visit(nodes_[n].left, planes, seen), visit(nodes_[n].right, planes, seen);
}

void grow_towards_sun(std::vector<Box3>& boxes, V3 sun) {
  const float sun_run = sun.z > 0.05f ? std::min(600.0f, 1.0f / std::tan(std::asin(sun.z))) : 600.0f;
  for (Box3& b : boxes)
    if (b.lo.x <= b.hi.x) {
      const float reach = (b.hi.z - b.lo.z) * sun_run;
      b.add(b.lo + V3{sun.x, sun.y, 0} * reach), b.add(b.hi + V3{sun.x, sun.y, 0} * reach);
    }
}

}  // namespace render
